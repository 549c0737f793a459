// Extended Voce hardening (Tome et al. 1984) with latent hardening, the paper's Table 2:
//   tau_c(Gamma) = tau0 + (tau1 + theta1 Gamma)(1 - exp(-theta0 Gamma / tau1)),
//   tau_c_dot^r = h(Gamma) sum_s h_rs |gamma_dot^s|,  h = dtau_c/dGamma,  h_rs = q + (1 - q) delta_rs,
//   Gamma = sum_r int |gamma_dot^r| dt.
// Over an increment the rate h is replaced by the secant
//   Hbar = (tau_c(Gamma_n + Delta Gamma) - tau_c(Gamma_n)) / Delta Gamma,
//   Delta tau_c^r = Hbar (q Delta Gamma + (1 - q) |Delta gamma^r|):
// exact whenever the slip rates keep their proportions during the increment (in particular for
// q = 1, where tau_c^r = tau_c(Gamma) exactly), so a monotonic single-crystal path does not
// depend on the step size.
//
// Irradiation defects add a term that slip sweeps out (the form used for ion-irradiated and
// helium-implanted tungsten): tau_c(Gamma) gains tau_irr(Gamma) = tau_irr,0 exp(-Gamma/gamma_0),
// a function of the total slip alone (no latent structure), integrated exactly:
//   Delta tau_irr = tau_irr(Gamma_n + Delta Gamma) - tau_irr(Gamma_n)  for every system.
//
// The law of one slip family; FamilyVoceHardening.h gives each family its own and is the
// hardening-law policy of CrystalPlasticityModel. HardeningIncrement is that interface's result.
#pragma once

#include "materials/TensorFunctions.h"

#include <array>
#include <utility>

namespace indentsim::materials
{
  // The most slip families a hardening law may distinguish (the largest lattice has 5).
  inline constexpr unsigned int max_slip_families = 8;

  // The hardening increment and its derivative, in the form
  //   dDelta tau_c^r = a_r dDelta Gamma + sum_g c_rg dDelta Gamma_g + b_r d|Delta gamma^r|,
  // Delta Gamma_g the slip of family g's systems (the c_rg part only with n_families > 0).
  template <int n_slip>
  struct HardeningIncrement
  {
    std::array<double, n_slip> value;          // Delta tau_c^r [GPa]
    std::array<double, n_slip> total_rate;     // a_r = dDelta tau_c^r / dDelta Gamma [GPa]
    std::array<double, n_slip> own_rate;       // b_r = dDelta tau_c^r / d|Delta gamma^r| [GPa]
    unsigned int               n_families = 0; // 0: no c_rg part
    const unsigned int        *family_of_system = nullptr; // g of each system (n_families > 0)
    std::array<std::array<double, max_slip_families>, n_slip> family_rate; // c_rg [GPa]
  };

  struct ExtendedVoceHardening
  {
    double tau0 = 0.12;           // initial critical resolved shear stress [GPa]
    double tau1 = 0.02;           // [GPa]
    double theta0 = 0.1;          // initial hardening rate [GPa]
    double theta1 = 0.006;        // asymptotic hardening rate [GPa]
    double q = 1.4;               // latent hardening ratio [-]
    double tau_irr = 0.0;         // tau_irr,0: the irradiation defects' initial share [GPa]
    double softening_slip = 0.05; // gamma_0: the slip that sweeps the defects out [-]

    // tau_c(Gamma), including tau_irr(Gamma) [GPa].
    double critical_shear(double Gamma) const;
    // h(Gamma) = dtau_c/dGamma [GPa].
    double hardening_rate(double Gamma) const;
    // tau_irr(Gamma_n + Delta Gamma) - tau_irr(Gamma_n) [GPa] and its derivative with respect to
    // Delta Gamma (<= 0: softening).
    std::pair<double, double> irradiation_increment(double Gamma_n, double delta_Gamma) const;

    // Hbar = theta1 (1 - e_n e^-x) + (tau1 + theta1 Gamma_n) e_n k phi(x),
    //   k = theta0 / tau1, e_n = exp(-k Gamma_n), x = k Delta Gamma, phi(x) = (1 - e^-x) / x;
    // Hbar -> h(Gamma_n) as Delta Gamma -> 0 (phi by its series for small x).
    template <typename Number>
    Number secant_modulus(double Gamma_n, const Number &delta_Gamma) const;

    const char *parameter_error() const;
  };

  template <typename Number>
  Number ExtendedVoceHardening::secant_modulus(const double  Gamma_n,
                                               const Number &delta_Gamma) const
  {
    using std::exp;
    if (theta0 == 0.0 || tau1 == 0.0)
      return Number(0.0);
    const double k = theta0 / tau1;
    const double e_n = std::exp(-k * Gamma_n);
    const Number x = k * delta_Gamma;
    Number       phi;
    if (scalar_value(x) < 0.1)
      {
        // sum_{j>=0} (-x)^j / (j+1)!, to j = 9 (error < 3e-17 for x < 0.1)
        phi = 1.0 / 3628800.0;
        for (int j = 8; j >= 0; --j)
          {
            double factorial = 1.0;
            for (int m = 2; m <= j + 1; ++m)
              factorial *= m;
            phi = 1.0 / factorial - x * phi;
          }
      }
    else
      phi = (1.0 - exp(-x)) / x;
    return theta1 * (1.0 - e_n * exp(-x)) + (tau1 + theta1 * Gamma_n) * e_n * k * phi;
  }
} // namespace indentsim::materials
