// Builds the constitutive model named in the case file (the `material` block of io::Case).
#pragma once

#include <io/Case.h>
#include <materials/MaterialModel.h>

#include <memory>

namespace indentsim::materials
{
  // model "neo_hookean" -> NeoHookean(E, nu);
  // model "j2"          -> J2Plasticity(E, nu, sigma_y0, H, yield_stress_measure), with
  //                        yield_stress_measure "cauchy" (the paper's eq. 4) or "kirchhoff".
  // Throws std::invalid_argument naming the key, the value and what is allowed.
  std::unique_ptr<MaterialModel> create_material(const io::MaterialParameters &parameters);
} // namespace indentsim::materials
