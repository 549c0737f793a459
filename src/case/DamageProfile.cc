// Depth-graded materials from a damage profile (see DamageProfile.h).
#include "case/DamageProfile.h"

#include "io/LinearInterpolation.h"

#include "case/MaterialLayers.h"

#include <algorithm>
#include <cmath>

namespace indentsim::io
{
  namespace
  {
    // The material of a slab at dose d: the block without its layers and profile, its
    // strength raised by the profile's law.
    MaterialParameters slab_material(const MaterialParameters &material, const double dose)
    {
      MaterialParameters slab = material;
      slab.layers.clear();
      slab.damage_profile = {};
      const DamageProfileParameters &profile = material.damage_profile;
      if (material.model == ModelKind::crystal)
        {
          slab.tau_irr = barrier_shear(profile, material.barrier_strength, dose);
          for (FamilyHardening &block : slab.family_hardening)
            block.tau_irr = barrier_shear(profile, block.barrier_strength, dose);
          return slab;
        }
      const double increment = yield_stress_increment(profile, dose);
      slab.yield_stress += increment;
      for (double &stress : slab.hardening_stress)
        stress += increment;
      return slab;
    }
  } // namespace

  double dose_at(const DamageProfileParameters &profile, const double depth)
  {
    if (profile.depth.empty() || depth > profile.depth.back())
      return 0.0;
    return io::interpolate_clamped(profile.depth, profile.dpa, depth);
  }

  double yield_stress_increment(const DamageProfileParameters &profile, const double dose)
  {
    if (profile.law == DamageLaw::table)
      return profile.table_dpa.empty()
                 ? 0.0
                 : io::interpolate_clamped(profile.table_dpa, profile.table_delta_yield_stress,
                                           dose);
    return profile.saturation_increment *
           std::pow(-std::expm1(-dose / profile.saturation_dose), profile.exponent);
  }

  double defect_density(const DamageProfileParameters &profile, const double dose)
  {
    return profile.saturation_density * -std::expm1(-dose / profile.saturation_dose);
  }

  double barrier_shear(const DamageProfileParameters &profile, const double alpha,
                       const double dose)
  {
    return alpha * profile.shear_modulus * profile.burgers_vector *
           std::sqrt(defect_density(profile, dose) * profile.defect_size);
  }

  double peak_dose(const DamageProfileParameters &profile)
  {
    return profile.dpa.empty() ? 0.0 : *std::max_element(profile.dpa.begin(), profile.dpa.end());
  }

  double peak_width(const DamageProfileParameters &profile)
  {
    const double half = 0.5 * peak_dose(profile);
    if (!(half > 0))
      return 0.0;
    const std::vector<double> &z = profile.depth, &d = profile.dpa;
    std::size_t                first = 0, last = d.size() - 1;
    while (d[first] < half)
      ++first;
    while (d[last] < half)
      --last;
    // Where the dose crosses half of its peak, between the points around first and last.
    const double top = first == 0
                           ? 0.0
                           : z[first - 1] + (half - d[first - 1]) / (d[first] - d[first - 1]) *
                                                (z[first] - z[first - 1]);
    const double bottom =
        last + 1 == d.size()
            ? z[last]
            : z[last] + (d[last] - half) / (d[last] - d[last + 1]) * (z[last + 1] - z[last]);
    return bottom - top;
  }

  double graded_depth(const MaterialParameters &material)
  {
    if (!material.layers.empty())
      return layered_depth(material.layers);
    return material.damage_profile.depth.empty() ? 0.0 : material.damage_profile.depth.back();
  }

  double graded_feature(const MaterialParameters &material)
  {
    if (!material.layers.empty())
      {
        double thinnest = 0;
        for (const MaterialLayer &layer : material.layers)
          if (layer.thickness > 0 && (thinnest == 0 || layer.thickness < thinnest))
            thinnest = layer.thickness;
        return thinnest;
      }
    return peak_width(material.damage_profile);
  }

  std::vector<DepthSlab> depth_slabs(const MaterialParameters &material, const std::string &source)
  {
    std::vector<DepthSlab> slabs;
    if (!material.layers.empty())
      {
        const std::vector<MaterialParameters> blocks = layer_materials(material, source);
        for (std::size_t i = 0; i < blocks.size(); ++i)
          slabs.push_back({material.layers[i].thickness, blocks[i]});
        return slabs;
      }
    const DamageProfileParameters &profile = material.damage_profile;
    const double                   depth = graded_depth(material);
    if (!(depth > 0))
      return slabs;
    const double delta = profile.resolution;
    const auto   n = static_cast<std::size_t>(std::ceil(depth / delta - 1e-9));
    for (std::size_t k = 0; k < n; ++k)
      {
        const double       top = k * delta, bottom = std::min(depth, (k + 1) * delta);
        MaterialParameters slab = slab_material(material, dose_at(profile, 0.5 * (top + bottom)));
        if (!slabs.empty() && slabs.back().material == slab)
          slabs.back().thickness += bottom - top;
        else
          slabs.push_back({bottom - top, std::move(slab)});
      }
    return slabs;
  }
} // namespace indentsim::io
