// The regularized Schmid law (the paper's eqs 14-15), after Arminjon (1991) and Gambin (1991):
//   Phi(tau, tau_c) = (sum_r (tau^r / tau_c^r)^(2n))^(1/2n),  f = Phi - 1 (eq. 14),
// and the associated flow Delta gamma^r = Delta lambda dPhi/dtau^r
//   = Delta lambda / tau_c^r (tau^r / (Phi tau_c^r))^(2n-1) (eq. 15; at the solution Phi = 1).
// Dividing tau^r by Phi keeps Delta gamma the gradient of the degree-one homogeneous Phi, so its
// size does not explode as (tau/tau_c)^(2n-1) while a Newton iterates from an elastic trial far
// outside the yield surface.
//
// A flow rule for CrystalPlasticityModel (crystal/CrystalPlasticityModel.h) supplies, with the
// resolved shears tau^r in GPa and the critical shears and the multiplier in units of a stress
// scale tau_ref (as the integrator's unknowns are):
//   evaluate(tau, tau_c, lambda, tau_ref, response)
//                                    rho_r = tau^r / tau_c^r, Phi and Delta gamma^r,
//   linearize(response, tau_c, lambda, linearization)
//                                    the coefficients of
//                                    dDelta gamma^r = N_r dlambda + c_r (drho_r - d_r dPhi) + D_r dtau_c^r,
//                                    dPhi = sum_s g_s drho_s, where the first drho_r is taken at
//                                    fixed tau_c (D_r holds the rest) and dPhi is complete: each
//                                    system's own ratio plus one coupling through Phi, the
//                                    structure the integrator's solve exploits,
//   elastic_limit(n_slip)            a bound on max_r |rho_r| below which Phi < 1,
//   value(tau, tau_c)                Phi for vectors of any length,
//   parameter_error()                nullptr, or what is wrong with the parameters.
#pragma once

#include "materials/crystal/SmallMatrix.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace indentsim::materials
{
  struct RegularizedSchmidFlow
  {
    double n = 10.0; // yield exponent (the surface uses 2n)

    template <int n_slip>
    struct Response
    {
      std::array<double, n_slip> ratio; // rho_r = tau^r / tau_c^r
      double                     Phi;
      std::array<double, n_slip> flow_power;  // (rho_r / Phi)^(2n-2)
      std::array<double, n_slip> delta_gamma; // Delta gamma^r
    };

    // The coefficients of dDelta gamma^r (see the header).
    template <int n_slip>
    struct Linearization
    {
      std::array<double, n_slip> dPhi_dratio;    // g_r
      std::array<double, n_slip> relative_ratio; // d_r
      std::array<double, n_slip> ratio_rate;     // c_r
      std::array<double, n_slip> tau_c_rate;     // D_r
      std::array<double, n_slip> lambda_rate;    // N_r
    };

    // Phi = |rho_max| (sum (rho_r / rho_max)^2n)^(1/2n), safe from overflow; one power per
    // system serves Phi and the flow direction: (rho_r / Phi)^(2n-2) = (rho_r / rho_max)^(2n-2)
    // sum^(-(n-1)/n), and Delta gamma^r = lambda / tau_c^r (rho_r / Phi)^(2n-1).
    template <int n_slip>
    void evaluate(const std::array<double, n_slip> &tau, const double *tau_c, const double lambda,
                  const double tau_ref, Response<n_slip> &out) const
    {
      unsigned int largest = 0;
      for (int r = 0; r < n_slip; ++r)
        {
          out.ratio[r] = tau[r] / (tau_ref * tau_c[r]);
          if (std::abs(out.ratio[r]) > std::abs(out.ratio[largest]))
            largest = r;
        }
      const double abs_largest = std::abs(out.ratio[largest]);
      if (abs_largest == 0.0)
        {
          out.Phi = 0.0;
          out.flow_power.fill(0.0);
          out.delta_gamma.fill(0.0);
          return;
        }
      double sum = 0.0;
      for (int r = 0; r < n_slip; ++r)
        {
          const double relative = out.ratio[r] / abs_largest;
          const double relative_squared = relative * relative;
          out.flow_power[r] = crystal::real_power(relative_squared, n - 1.0);
          sum += relative_squared * out.flow_power[r];
        }
      out.Phi = abs_largest * std::pow(sum, 1.0 / (2.0 * n));
      const double power_scale = std::pow(sum, (1.0 - n) / n);
      for (int r = 0; r < n_slip; ++r)
        {
          out.flow_power[r] *= power_scale;
          out.delta_gamma[r] = lambda / tau_c[r] * (out.ratio[r] / out.Phi) * out.flow_power[r];
        }
    }

    // With d_r = rho_r / Phi, g_r = d_r^(2n-1) = dPhi/drho_r and w_r = (2n-1) d_r^(2n-2):
    //   dDelta gamma^r = g_r / tau_c^r dlambda - lambda g_r / tau_c^r^2 dtau_c^r
    //                    + lambda w_r / (tau_c^r Phi) (drho_r - d_r dPhi),
    // and the tau_c part of drho_r, -rho_r / tau_c^r dtau_c^r, moved into D_r.
    template <int n_slip>
    void linearize(const Response<n_slip> &response, const double *tau_c, const double lambda,
                   Linearization<n_slip> &out) const
    {
      const bool yielding = response.Phi != 0.0;
      for (int r = 0; r < n_slip; ++r)
        {
          double d = 0.0, g = 0.0, w = 0.0;
          if (yielding)
            {
              d = response.ratio[r] / response.Phi;
              g = d * response.flow_power[r];
              w = (2.0 * n - 1.0) * response.flow_power[r];
            }
          const double c = yielding ? lambda * w / (tau_c[r] * response.Phi) : 0.0;
          out.dPhi_dratio[r] = g;
          out.relative_ratio[r] = d;
          out.ratio_rate[r] = c;
          out.tau_c_rate[r] =
              -c * response.ratio[r] / tau_c[r] - lambda * g / (tau_c[r] * tau_c[r]);
          out.lambda_rate[r] = g / tau_c[r];
        }
    }

    // A trial is certainly elastic while every |rho_r| is below this bound, since
    // Phi <= n_slip^(1/2n) max_r |rho_r| (eq. 14); the margin lies far above the round-off of rho_r.
    double elastic_limit(const unsigned int n_slip) const
    {
      return (1.0 - 1e-10) / std::pow(double(n_slip), 1.0 / (2.0 * n));
    }

    // Phi for resolved and critical shears of any length (in any one unit).
    double value(const std::vector<double> &tau, const std::vector<double> &tau_c) const
    {
      double largest = 0.0;
      for (unsigned int r = 0; r < tau.size(); ++r)
        largest = std::max(largest, std::abs(tau[r] / tau_c[r]));
      if (largest == 0.0)
        return 0.0;
      double sum = 0.0;
      for (unsigned int r = 0; r < tau.size(); ++r)
        sum += std::pow(std::abs(tau[r] / tau_c[r]) / largest, 2.0 * n);
      return largest * std::pow(sum, 1.0 / (2.0 * n));
    }

    const char *parameter_error() const
    {
      if (!(n >= 1 && n <= 50))
        return "yield_exponent_n must lie in [1, 50]";
      return nullptr;
    }
  };
} // namespace indentsim::materials
