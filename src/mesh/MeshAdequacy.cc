#include "mesh/MeshAdequacy.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>

namespace indentsim::mesh
{
  namespace
  {
    // Where the ray from the axis at angle theta leaves {profile < height}: bisection between
    // a point inside and one outside (the profile rises along every ray of a convex tip).
    double boundary_radius(const indenter::IndenterSurface &surface, const double height,
                           const double theta)
    {
      const double c = std::cos(theta), s = std::sin(theta);
      const auto   inside = [&](const double r) { return surface.profile(r * c, r * s) < height; };
      double       lower = 0, upper = std::max(height, 1e-3);
      while (inside(upper) && upper < 1e9)
        {
          lower = upper;
          upper *= 2;
        }
      for (int i = 0; i < 60 && upper - lower > 1e-9 * upper; ++i)
        {
          const double middle = 0.5 * (lower + upper);
          (inside(middle) ? lower : upper) = middle;
        }
      return upper;
    }

    // The smallest initial critical shear of the crystal's slip families: a family's own block
    // where it has one, the common tau0 for the others [GPa].
    double softest_critical_shear(const io::MaterialParameters &material)
    {
      const std::size_t n_families =
          material.slip_families.empty() ? 1 : material.slip_families.size();
      double smallest = material.family_hardening.size() < n_families
                            ? material.tau0
                            : std::numeric_limits<double>::infinity();
      for (const io::FamilyHardening &block : material.family_hardening)
        smallest = std::min(smallest, block.tau0);
      return smallest;
    }

    // The hardness of H = 3 sigma_y, or 0 where the model has no yield stress.
    double estimated_hardness(const io::MaterialParameters &material)
    {
      if (material.model == io::ModelKind::j2)
        return guard::constraint_factor * material.yield_stress;
      if (material.model == io::ModelKind::crystal)
        return guard::constraint_factor * guard::fcc_taylor_factor *
               softest_critical_shear(material);
      return 0;
    }

    // The height h with projected_area(h) = area (bisection; the area rises with h).
    double height_of_area(const indenter::IndenterSurface &surface, const double area)
    {
      double lower = 0, upper = 1e-3;
      while (surface.projected_area(upper) < area && upper < 1e9)
        {
          lower = upper;
          upper *= 2;
        }
      for (int i = 0; i < 60; ++i)
        {
          const double middle = 0.5 * (lower + upper);
          (surface.projected_area(middle) < area ? lower : upper) = middle;
        }
      return upper;
    }

    // The smallest multiple of 4 elements of size `element` that spans `width`.
    unsigned int elements_spanning(const double width, const double element)
    {
      const double n = std::ceil(width / element * (1 - 1e-12));
      return 4 * static_cast<unsigned int>(std::ceil(n / 4));
    }
  } // namespace

  PatchExtent indenter_extent(const indenter::IndenterSurface &surface, const double height)
  {
    PatchExtent extent;
    const int   n_rays = 720;
    for (int i = 0; i < n_rays; ++i)
      {
        const double theta = 2 * std::numbers::pi * i / n_rays;
        const double r = boundary_radius(surface, height, theta);
        extent.x = std::max(extent.x, std::abs(r * std::cos(theta)));
        extent.y = std::max(extent.y, std::abs(r * std::sin(theta)));
      }
    return extent;
  }

  double refined_fraction(const PatchExtent &extent, const io::SpecimenParameters &specimen)
  {
    return std::max(extent.x / (specimen.refined_region[0] / 2),
                    extent.y / (specimen.refined_region[1] / 2));
  }

  std::optional<ContactPrediction> predict_contact(const io::Case                  &the_case,
                                                   const indenter::IndenterSurface &surface)
  {
    const io::LoadingParameters &loading = the_case.loading;
    const double                 ratio = contact_depth_ratio(the_case);
    const bool                   elastic = the_case.material.model == io::ModelKind::neo_hookean;
    ContactPrediction            at_depth;
    at_depth.depth = loading.max_depth;
    at_depth.extent = indenter_extent(surface, ratio * loading.max_depth);
    at_depth.basis = "the indenter's cross-section at h_c = " + short_number(ratio) + " x " +
                     (loading.control == io::Control::force ? "loading.max_depth" : "max_depth") +
                     " = " + short_number(ratio * loading.max_depth) + " um (" +
                     (elastic ? "elastic sink-in" : "pile-up allowance") + ")";
    if (loading.control != io::Control::force)
      return at_depth;

    const double hardness = estimated_hardness(the_case.material);
    if (!(hardness > 0))
      return std::nullopt;
    const double      area = loading.max_force / hardness;
    const double      height = height_of_area(surface, area);
    ContactPrediction at_force;
    at_force.extent = indenter_extent(surface, height);
    at_force.depth = height;
    std::ostringstream basis;
    basis << "the contact area F/H = " << short_number(loading.max_force) << " mN / "
          << short_number(hardness) << " GPa = " << short_number(area)
          << " um^2 at loading.max_force (H = 3 sigma_y, Tabor)";
    at_force.basis = basis.str();
    return refined_fraction(at_force.extent, the_case.specimen) <
                   refined_fraction(at_depth.extent, the_case.specimen)
               ? at_force
               : at_depth;
  }

  double predicted_contact_height(const io::Case                  &the_case,
                                  const indenter::IndenterSurface &surface)
  {
    const io::LoadingParameters &loading = the_case.loading;
    const double                 at_depth = contact_depth_ratio(the_case) * loading.max_depth;
    const double                 hardness = estimated_hardness(the_case.material);
    if (loading.control != io::Control::force || !(hardness > 0))
      return at_depth;
    return std::min(at_depth, height_of_area(surface, loading.max_force / hardness));
  }

  double contact_depth_ratio(const io::Case &the_case)
  {
    return the_case.material.model == io::ModelKind::neo_hookean
               ? guard::elastic_contact_depth_ratio
               : guard::pile_up_allowance;
  }

  double largest_depth_held(const io::Case &the_case, const indenter::IndenterSurface &surface)
  {
    double lower = 0, upper = the_case.loading.max_depth;
    for (int i = 0; i < 50; ++i)
      {
        const double middle = 0.5 * (lower + upper);
        const double fraction = refined_fraction(
            indenter_extent(surface, contact_depth_ratio(the_case) * middle), the_case.specimen);
        (fraction <= guard::refined_region_margin ? lower : upper) = middle;
      }
    return lower;
  }

  std::string enlargement_advice(const io::SpecimenParameters &specimen, const PatchExtent &needed)
  {
    const double element = specimen.refined_region[0] / specimen.contact_elements;
    const double width_x =
        std::max(specimen.refined_region[0], 2 * needed.x / guard::refined_region_margin);
    const double width_y =
        std::max(specimen.refined_region[1], 2 * needed.y / guard::refined_region_margin);
    const unsigned int n_x = elements_spanning(width_x, element);
    const double       new_x = n_x * element, new_y = elements_spanning(width_y, element) * element;
    std::ostringstream advice;
    advice << "specimen.refined_region: [" << short_number(new_x) << ", " << short_number(new_y)
           << ", " << short_number(specimen.refined_region[2])
           << "] and specimen.contact_elements: " << n_x << " (the same contact-element size "
           << short_number(element) << " um)";
    if (new_x > specimen.size[0] || new_y > specimen.size[1])
      {
        const double scale =
            std::max(new_x / specimen.refined_region[0], new_y / specimen.refined_region[1]);
        advice << " with specimen.size: [" << short_number(std::ceil(specimen.size[0] * scale))
               << ", " << short_number(std::ceil(specimen.size[1] * scale)) << ", "
               << short_number(specimen.size[2]) << "]";
      }
    return advice.str();
  }

  unsigned int contact_elements_for(const io::SpecimenParameters &specimen, const double radius,
                                    const double elements)
  {
    if (!(radius > 0))
      return specimen.contact_elements;
    return elements_spanning(elements * specimen.refined_region[0] / radius, 1.0);
  }

  std::string short_number(const double value)
  {
    std::ostringstream text;
    text << std::setprecision(4) << value;
    return text.str();
  }
} // namespace indentsim::mesh
