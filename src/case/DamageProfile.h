// Depth-graded materials from a damage profile (material.damage_profile), and the depth-graded
// material of either form (layers or profile) as the mesh, the material factory and the
// outputs see it. Units: depth um, dose dpa, stresses GPa, defect density 1/um^3.
//
// The dose d(z) at depth z below the undeformed surface is linear between the profile's
// points, the first point's dose above it, and 0 below the last point (the substrate: the
// material block itself). The strength it gives:
//   j2, form saturation:  Delta sigma_y = Delta sigma_sat (1 - exp(-d/d0))^p,
//   j2, form table:       Delta sigma_y piecewise linear in d, the last value beyond the table,
// added to the yield stress (for a hardening table, to every stress of the table: the curve is
// shifted, not scaled);
//   crystal, dispersed_barrier (the dispersed-barrier hardening of irradiation defects):
//     N(d) = N_sat (1 - exp(-d/d0)),   tau_irr,0 = alpha_f mu b sqrt(N(d) D),
// each slip family f with its own barrier strength alpha_f, into material.hardening.tau_irr
// (softened by slip, ExtendedVoceHardening.h).
//
// The profile is sampled in slabs of `resolution` from the surface to its last depth: each
// slab is one material of a LayeredMaterial, its strength evaluated at the slab's centre;
// neighbouring slabs of equal strength are merged.
#pragma once

#include "case/MaterialParameters.h"

#include <string>
#include <vector>

namespace indentsim::io
{
  // d(z) [dpa].
  double dose_at(const DamageProfileParameters &profile, double depth);
  // Delta sigma_y(d) [GPa] of the j2 forms (saturation, table).
  double yield_stress_increment(const DamageProfileParameters &profile, double dose);
  // N(d) [1/um^3] and tau_irr,0 = alpha mu b sqrt(N D) [GPa] of dispersed_barrier.
  double defect_density(const DamageProfileParameters &profile, double dose);
  double barrier_shear(const DamageProfileParameters &profile, double alpha, double dose);

  // The dose's peak and the width of the depth range where the dose is at least half of it
  // [um] (the full width at half maximum of the damage peak; its outer points interpolated).
  double peak_dose(const DamageProfileParameters &profile);
  double peak_width(const DamageProfileParameters &profile);

  // The depth below which the material block itself holds: the layers' total thickness or the
  // profile's last depth [um]; 0 for a homogeneous material.
  double graded_depth(const MaterialParameters &material);
  // The thinnest feature the mesh must resolve across: the thinnest layer, or the damage
  // peak's width [um]; 0 for a homogeneous material.
  double graded_feature(const MaterialParameters &material);

  // One material of a depth-graded specimen, from the surface down.
  struct DepthSlab
  {
    double             thickness; // [um]
    MaterialParameters material;  // homogeneous (no layers, no profile)
  };
  // The slabs of either form: the layers as layer_materials reads them (`source` names the case
  // in its messages), or the profile's sampling slabs; empty for a homogeneous material.
  std::vector<DepthSlab> depth_slabs(const MaterialParameters &material, const std::string &source);
} // namespace indentsim::io
