#include "materials/crystal/ExtendedVoceHardening.h"

#include <cmath>

namespace indentsim::materials
{
  double ExtendedVoceHardening::critical_shear(const double Gamma) const
  {
    const double irradiation = tau_irr * std::exp(-Gamma / softening_slip);
    if (theta0 == 0.0 || tau1 == 0.0)
      return tau0 + irradiation;
    return tau0 + (tau1 + theta1 * Gamma) * (-std::expm1(-theta0 * Gamma / tau1)) + irradiation;
  }

  double ExtendedVoceHardening::hardening_rate(const double Gamma) const
  {
    const double softening = -tau_irr / softening_slip * std::exp(-Gamma / softening_slip);
    if (theta0 == 0.0 || tau1 == 0.0)
      return softening;
    return theta1 +
           (theta0 - theta1 + theta0 * theta1 * Gamma / tau1) * std::exp(-theta0 * Gamma / tau1) +
           softening;
  }

  std::pair<double, double>
  ExtendedVoceHardening::irradiation_increment(const double Gamma_n, const double delta_Gamma) const
  {
    if (tau_irr == 0.0)
      return {0.0, 0.0};
    const double at_start = tau_irr * std::exp(-Gamma_n / softening_slip);
    return {at_start * std::expm1(-delta_Gamma / softening_slip),
            -at_start / softening_slip * std::exp(-delta_Gamma / softening_slip)};
  }

  const char *ExtendedVoceHardening::parameter_error() const
  {
    if (!(tau0 > 0 && std::isfinite(tau0)))
      return "tau0 must be positive";
    if (!(tau1 >= 0 && theta0 >= 0 && theta1 >= 0 && q >= 0))
      return "tau1, theta0, theta1 and q must be non-negative";
    if (!(tau_irr >= 0 && std::isfinite(tau_irr)))
      return "tau_irr must be finite and non-negative";
    if (!(softening_slip > 0 && std::isfinite(softening_slip)))
      return "the softening slip gamma_0 must be finite and positive";
    if (tau1 == 0 && theta0 > 0)
      return "tau1 must be positive when theta0 > 0 (the Voce term divides by tau1)";
    return nullptr;
  }
} // namespace indentsim::materials
