#include "mesh/MeshDesign.h"

#include "mesh/MeshAdequacy.h"

#include <algorithm>
#include <cmath>

namespace indentsim::mesh
{
  namespace
  {
    // The radius of the indenter's cross-section at the height h_c: its largest reach from the
    // axis (a pyramid's corner) [um].
    double cross_section_radius(const indenter::IndenterSurface &surface, const double height)
    {
      const PatchExtent extent = indenter_extent(surface, height);
      return std::max(extent.x, extent.y);
    }

    // A length rounded up to 2 significant digits, so that the resolved case shows round
    // numbers (the design does not depend on the last digits).
    double round_up(const double length)
    {
      const double scale = std::pow(10., std::floor(std::log10(length)) - 1);
      return std::ceil(length / scale * (1 - 1e-12)) * scale;
    }
  } // namespace

  void design_mesh(io::Case &the_case, const indenter::IndenterSurface &surface,
                   const bool size_given)
  {
    io::SpecimenParameters &s = the_case.specimen;
    const bool              axisymmetric = s.symmetry == io::Symmetry::axisymmetric;
    const double n = axisymmetric ? design::elements_per_radius_2d : design::elements_per_radius_3d;

    const double h_c = predicted_contact_height(the_case, surface);
    const double a_d = cross_section_radius(surface, h_c);
    const double a_low = cross_section_radius(surface, design::smallest_resolved_depth * h_c);

    io::MeshGrading &g = s.grading;
    g.contact_radius = a_d;
    g.elements_per_radius = n;
    g.min_element = a_low / n;
    // The near field also reaches twice the depth, for tips whose contact stops growing (a
    // flat punch).
    g.graded_radius = std::max(design::near_field_radii * a_d, 2 * the_case.loading.max_depth);
    g.far_elements_per_radius = design::far_field_ratio * n;

    if (!size_given)
      {
        const double half = round_up(design::specimen_radii * a_d);
        s.size = {{2 * half, 2 * half, half}};
      }
    const double contact_half = round_up(design::contact_region_radii * a_d);
    s.refined_region = {{std::min(2 * contact_half, s.size[0]),
                         std::min(2 * contact_half, s.size[1]),
                         std::min(round_up(g.graded_radius), s.size[2])}};
  }

  double target_element_size(const io::MeshGrading &g, const double rho)
  {
    if (rho <= g.graded_radius)
      return std::max(g.min_element, rho / g.elements_per_radius);
    return rho / g.far_elements_per_radius;
  }
} // namespace indentsim::mesh
