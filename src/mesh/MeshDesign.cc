#include "mesh/MeshDesign.h"

#include "case/DamageProfile.h"
#include "mesh/MeshAdequacy.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

namespace indentsim::mesh
{
  namespace
  {
    // The radius of the circle of the same area as the indenter's cross-section at the height
    // h_c [um]: the contact radius of an axisymmetric tip, and for a pyramid the size that its
    // contact's area (and so the force) depends on. A pyramid's corners reach further (a
    // Vickers pyramid's half-diagonal 1.25 times, a Berkovich pyramid's corner 1.56 times),
    // its faces' middles less; sizing by either would resolve one pyramid 1.6 times finer
    // than another of the same area function.
    double equal_area_radius(const indenter::IndenterSurface &surface, const double height)
    {
      return std::sqrt(surface.projected_area(height) / std::numbers::pi);
    }

    // The largest extent of the indenter's cross-section at the height h_c along x or y (a
    // Berkovich corner along -x; a Vickers half-side at rotation 0) [um]: the box of contact
    // nodes must cover it.
    double cross_section_reach(const indenter::IndenterSurface &surface, const double height)
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
    const double            n = s.elements_per_radius != 0 ? double(s.elements_per_radius)
                                : axisymmetric             ? design::elements_per_radius_2d
                                                           : design::elements_per_radius_3d;

    const double h_c = predicted_contact_height(the_case, surface);
    const double a_d = equal_area_radius(surface, h_c);
    const double a_low = equal_area_radius(surface, design::smallest_resolved_depth * h_c);
    const double reach = cross_section_reach(surface, h_c);

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
    const double contact_half = round_up(design::contact_region_radii * std::max(a_d, reach));
    g.surface_radius = contact_half;
    g.surface_halvings = s.surface_refinement != 0
                             ? static_cast<unsigned int>(std::countr_zero(s.surface_refinement))
                         : axisymmetric ? design::surface_halvings_2d
                                        : design::surface_halvings_3d;
    g.layered_depth = io::graded_depth(the_case.material);
    g.layer_element = g.layered_depth > 0
                          ? io::graded_feature(the_case.material) / s.elements_across_layers
                          : 0.0;
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

  CoarseGrid coarse_grid(const io::SpecimenParameters &specimen)
  {
    CoarseGrid   grid;
    const bool   axisymmetric = specimen.symmetry == io::Symmetry::axisymmetric;
    const bool   half_line = specimen.symmetry != io::Symmetry::full;
    const double half_x = specimen.size[0] / 2, half_y = specimen.size[1] / 2,
                 depth = specimen.size[2];
    const double edge = 0.5 * std::min({half_x, axisymmetric ? half_x : half_y, depth});
    const auto   cells = [&](const double length) {
      return std::max(1L, std::lround(length / edge));
    };
    const long sides = half_line ? 1 : 2;
    if (axisymmetric)
      {
        grid.dim = 2;
        grid.cells = {{cells(half_x), cells(depth), 1}};
        grid.lower = {{0., -depth, 0.}};
        grid.upper = {{half_x, 0., 0.}};
        return grid;
      }
    grid.cells = {{sides * cells(half_x), sides * cells(half_y), cells(depth)}};
    grid.lower = {{half_line ? 0. : -half_x, half_line ? 0. : -half_y, -depth}};
    grid.upper = {{half_x, half_y, 0.}};
    return grid;
  }

  bool needs_halving(const io::MeshGrading &grading, const std::array<double, 3> &lower,
                     const std::array<double, 3> &upper, const unsigned int dim)
  {
    double distance2 = 0, edge = 0;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double nearest = std::clamp(0., lower[d], upper[d]);
        distance2 += nearest * nearest;
        edge = std::max(edge, upper[d] - lower[d]);
      }
    const double rho = std::sqrt(distance2);
    double       target = target_element_size(grading, rho);
    // The top face is z = 0 (the last coordinate's upper bound).
    if (upper[dim - 1] >= 0 && rho <= grading.surface_radius)
      target = std::ldexp(target, -static_cast<int>(grading.surface_halvings));
    // Across the layers of a depth-graded specimen, in the near field.
    if (grading.layer_element > 0 && rho <= grading.graded_radius &&
        -upper[dim - 1] < grading.layered_depth)
      target = std::min(target, grading.layer_element);
    return edge > target * (1 + 1e-9);
  }
} // namespace indentsim::mesh
