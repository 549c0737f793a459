#include "materials/MaterialFactory.h"
#include "materials/CrystalPlasticity.h"
#include "materials/J2Plasticity.h"
#include "materials/NeoHookean.h"
#include "materials/crystal/Orientation.h"

#include <stdexcept>

namespace indentsim::materials
{
  std::unique_ptr<MaterialModel> create_material(const io::MaterialParameters &parameters)
  {
    if (parameters.model == io::ModelKind::neo_hookean)
      return std::make_unique<NeoHookean>(parameters.young_modulus, parameters.poisson_ratio);

    if (parameters.model == io::ModelKind::j2)
      {
        YieldStressMeasure measure;
        if (parameters.yield_stress_measure == io::YieldStressMeasure::cauchy)
          measure = YieldStressMeasure::cauchy;
        else if (parameters.yield_stress_measure == io::YieldStressMeasure::kirchhoff)
          measure = YieldStressMeasure::kirchhoff;
        else
          throw std::invalid_argument("material.yield_stress_measure = \"" +
                                      to_string(parameters.yield_stress_measure) +
                                      "\" is not supported; allowed: cauchy, kirchhoff");
        return std::make_unique<J2Plasticity>(parameters.young_modulus, parameters.poisson_ratio,
                                              create_hardening_law(parameters), measure);
      }

    if (parameters.model == io::ModelKind::crystal)
      {
        const auto &p = parameters;
        return std::make_unique<CrystalPlasticity>(
            slip_systems(to_string(p.lattice), p.slip_families, p.c_over_a),
            p.lattice == io::Lattice::hcp
                ? LatticeElasticity::hexagonal(p.C11, p.C12, p.C13, p.C33, p.C44)
                : LatticeElasticity::cubic(p.C11, p.C12, p.C44),
            ExtendedVoceHardening{p.tau0, p.tau1, p.theta0, p.theta1, p.q}, p.yield_exponent_n);
      }

    throw std::invalid_argument("material.model = \"" + to_string(parameters.model) +
                                "\" is not supported; allowed: neo_hookean, j2, crystal");
  }

  IsotropicHardening create_hardening_law(const io::MaterialParameters &parameters)
  {
    const auto &p = parameters;
    if (p.hardening_law == io::HardeningLaw::linear)
      return IsotropicHardening::linear(p.yield_stress, p.hardening_modulus);
    if (p.hardening_law == io::HardeningLaw::power)
      return IsotropicHardening::power(p.yield_stress, p.young_modulus, p.hardening_exponent);
    if (p.hardening_law == io::HardeningLaw::voce)
      return IsotropicHardening::voce(p.yield_stress, p.hardening_saturation, p.hardening_rate,
                                      p.hardening_modulus);
    if (p.hardening_law == io::HardeningLaw::table)
      return IsotropicHardening::table(p.hardening_plastic_strain, p.hardening_stress);
    throw std::invalid_argument("material.hardening.law = \"" + to_string(p.hardening_law) +
                                "\" is not supported; allowed: linear, power, voce, table");
  }

  dealii::Tensor<2, 3> create_orientation(const io::OrientationParameters &orientation)
  {
    if (orientation.kind == io::OrientationKind::euler_bunge_deg)
      return bunge_rotation(orientation.euler_bunge_deg);
    if (orientation.kind == io::OrientationKind::surface_normal)
      return rotation_from_surface_normal(orientation.surface_normal,
                                          orientation.reference_direction);
    throw std::invalid_argument("material.orientation: kind \"" + to_string(orientation.kind) +
                                "\" is not supported; allowed: euler_bunge_deg, surface_normal");
  }
} // namespace indentsim::materials
