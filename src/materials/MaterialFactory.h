// Builds the constitutive model named in the case file (the `material` block of io::Case).
#pragma once

#include "case/MaterialParameters.h"
#include "materials/IsotropicHardening.h"
#include "materials/MaterialModel.h"

#include <memory>

namespace indentsim::materials
{
  // model neo_hookean -> NeoHookean(E, nu);
  // model j2          -> J2Plasticity(E, nu, create_hardening_law, yield_stress_measure), with
  //                      yield_stress_measure cauchy (the paper's eq. 4) or kirchhoff.
  // model crystal     -> CrystalPlasticity (lattice, C11, C12, C44, tau0, tau1, theta0, theta1,
  //                      q, yield_exponent_n); the orientation enters each point's state.
  // With material.layers: a LayeredMaterial of one such model per layer (io::layer_materials)
  // over the model of the block itself (the substrate).
  // Throws std::invalid_argument naming the key, the value and what is allowed.
  std::unique_ptr<MaterialModel> create_material(const io::MaterialParameters &parameters);

  // The J2 hardening law of material.hardening.law: linear (sigma_y0 = yield_stress,
  // hardening_modulus), power (yield_stress, young_modulus, exponent), voce (yield_stress,
  // saturation, rate, modulus) or table (the two lists; sigma_y0 is the first stress, which the
  // case validator requires to equal yield_stress). Throws InvalidHardeningParameter, or
  // std::invalid_argument for an unknown law.
  IsotropicHardening create_hardening_law(const io::MaterialParameters &parameters);

  // The lattice orientation g (v_crystal = g v_sample, see Orientation.h) of material.orientation;
  // the lattice (and c/a for hcp) says how its Miller or Miller-Bravais indices become
  // crystal-frame vectors. Throws std::invalid_argument, the message starting with the key
  // (surface_normal or reference_direction), for indices that name no plane or direction and
  // for a reference direction outside the plane.
  dealii::Tensor<2, 3> create_orientation(const io::MaterialParameters &material);
} // namespace indentsim::materials
