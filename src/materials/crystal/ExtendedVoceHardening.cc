#include "materials/crystal/ExtendedVoceHardening.h"

#include <cmath>

namespace indentsim::materials
{
  double ExtendedVoceHardening::critical_shear(const double Gamma) const
  {
    if (theta0 == 0.0 || tau1 == 0.0)
      return tau0;
    return tau0 + (tau1 + theta1 * Gamma) * (-std::expm1(-theta0 * Gamma / tau1));
  }

  double ExtendedVoceHardening::hardening_rate(const double Gamma) const
  {
    if (theta0 == 0.0 || tau1 == 0.0)
      return 0.0;
    return theta1 +
           (theta0 - theta1 + theta0 * theta1 * Gamma / tau1) * std::exp(-theta0 * Gamma / tau1);
  }

  const char *ExtendedVoceHardening::parameter_error() const
  {
    if (!(tau0 > 0 && std::isfinite(tau0)))
      return "tau0 must be positive";
    if (!(tau1 >= 0 && theta0 >= 0 && theta1 >= 0 && q >= 0))
      return "tau1, theta0, theta1 and q must be non-negative";
    if (tau1 == 0 && theta0 > 0)
      return "tau1 must be positive when theta0 > 0 (the Voce term divides by tau1)";
    return nullptr;
  }
} // namespace indentsim::materials
