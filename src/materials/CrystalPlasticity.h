// The paper's crystal-plasticity model (section 2.2, eqs 10-15, Table 2), after Arminjon
// (1991), Gambin (1991) and Kowalczyk & Gambin (2004): CrystalPlasticityModel
// (crystal/CrystalPlasticityModel.h, the kinematics, the local integrator and the consistent
// tangent) with
//   cubic or hexagonal St-Venant-Kirchhoff elasticity in E_e (eq. 11,
//   crystal/LatticeElasticity.h),
//   the regularized Schmid law with associated flow (eqs 14-15, crystal/RegularizedSchmidFlow.h),
//   extended Voce hardening per slip family with latent hardening, integrated with its secant
//   over the increment (crystal/FamilyVoceHardening.h),
// on the slip systems of a lattice (crystal/SlipSystems.h: FCC, BCC and HCP families).
#pragma once

#include "materials/crystal/CrystalPlasticityModel.h"
#include "materials/crystal/FamilyVoceHardening.h"
#include "materials/crystal/LatticeElasticity.h"
#include "materials/crystal/RegularizedSchmidFlow.h"
#include "materials/crystal/SlipSystems.h"

namespace indentsim::materials
{
  extern template class CrystalPlasticityModel<LatticeElasticity, RegularizedSchmidFlow,
                                               FamilyVoceHardening>;

  class CrystalPlasticity
    : public CrystalPlasticityModel<LatticeElasticity, RegularizedSchmidFlow, FamilyVoceHardening>
  {
  public:
    // Throws std::invalid_argument for a non-positive-definite stiffness, tau0 <= 0,
    // negative hardening parameters, tau1 = 0 with theta0 > 0, q < 0 or n < 1.
    CrystalPlasticity(const SlipSystems &slip_systems, const LatticeElasticity &elasticity,
                      const FamilyVoceHardening &hardening, double yield_exponent_n)
      : CrystalPlasticityModel(slip_systems, elasticity, RegularizedSchmidFlow{yield_exponent_n},
                               hardening)
    {
    }

    double yield_exponent() const { return flow_rule().n; }
  };
} // namespace indentsim::materials
