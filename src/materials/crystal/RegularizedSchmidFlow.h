// The regularized Schmid law (the paper's eqs 14-15), after Arminjon (1991) and Gambin (1991):
//   Phi(tau, tau_c) = (sum_r (tau^r / tau_c^r)^(2n))^(1/2n),  f = Phi - 1 (eq. 14),
// and the associated flow Delta gamma^r = Delta lambda dPhi/dtau^r
//   = Delta lambda / tau_c^r (tau^r / (Phi tau_c^r))^(2n-1) (eq. 15; at the solution Phi = 1).
// Dividing tau^r by Phi keeps Delta gamma the gradient of the degree-one homogeneous Phi, so its
// size does not explode as (tau/tau_c)^(2n-1) while a Newton iterates from an elastic trial far
// outside the yield surface.
//
// A flow rule for CrystalPlasticityModel (crystal/CrystalPlasticityModel.h) supplies, in stresses
// scaled by the initial critical shear (hats below, as the integrator's unknowns are):
//   evaluate(tau, tau_c, response)   Phi and its gradient N_r = dPhi/dtau^r (Delta gamma = lambda N),
//   linearize(response, tau_c, ...)  dN_r = a_r dtau^r + b_r dtau_c^r - u_r dPhi and dPhi/dtau_c:
//                                    the second derivatives, diagonal plus one rank-one term
//                                    along dPhi, the structure the integrator's solve exploits,
//   elastic_limit(n_slip)            a bound on max_r |tau^r / tau_c^r| below which Phi < 1,
//   value(tau, tau_c)                Phi for vectors of any length,
//   parameter_error()                nullptr, or what is wrong with the parameters.
#pragma once

#include <materials/crystal/SmallMatrix.h>

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
      std::array<double, n_slip> ratio;      // rho_r = tau^r / tau_c^r
      double                     Phi;
      std::array<double, n_slip> flow_power; // (rho_r / Phi)^(2n-2)
      std::array<double, n_slip> direction;  // N_r = dPhi/dtau^r = (rho_r / Phi)^(2n-1) / tau_c^r
    };

    // dN_r = diagonal_tau_r dtau^r + diagonal_tau_c_r dtau_c^r - coupling_r dPhi,
    // dPhi = sum_s N_s dtau^s + dPhi_dtau_c_s dtau_c^s.
    template <int n_slip>
    struct Linearization
    {
      std::array<double, n_slip> diagonal_tau, diagonal_tau_c, coupling, dPhi_dtau_c;
    };

    // Phi = |rho_max| (sum (rho_r / rho_max)^2n)^(1/2n), safe from overflow; one power per
    // system serves Phi and N: (rho_r / Phi)^(2n-2) = (rho_r / rho_max)^(2n-2) sum^(-(n-1)/n).
    template <int n_slip>
    void evaluate(const std::array<double, n_slip> &tau,
                  const double                     *tau_c,
                  Response<n_slip>                 &out) const
    {
      unsigned int largest = 0;
      for (int r = 0; r < n_slip; ++r)
        {
          out.ratio[r] = tau[r] / tau_c[r];
          if (std::abs(out.ratio[r]) > std::abs(out.ratio[largest]))
            largest = r;
        }
      const double abs_largest = std::abs(out.ratio[largest]);
      if (abs_largest == 0.0)
        {
          out.Phi = 0.0;
          out.flow_power.fill(0.0);
          out.direction.fill(0.0);
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
          out.direction[r] = 1.0 / tau_c[r] * (out.ratio[r] / out.Phi) * out.flow_power[r];
        }
    }

    // With d_r = rho_r / Phi, g_r = d_r^(2n-1), w_r = (2n-1) d_r^(2n-2) and N_r = g_r / tau_c^r:
    //   dN_r = w_r / (tau_c^r Phi) (drho_r - d_r dPhi) - g_r / tau_c^r^2 dtau_c^r,
    //   drho_r = dtau^r / tau_c^r - rho_r / tau_c^r dtau_c^r.
    template <int n_slip>
    void linearize(const Response<n_slip> &response,
                   const double           *tau_c,
                   Linearization<n_slip>  &out) const
    {
      for (int r = 0; r < n_slip; ++r)
        {
          if (response.Phi == 0.0)
            {
              out.diagonal_tau[r] = out.diagonal_tau_c[r] = out.coupling[r] = out.dPhi_dtau_c[r] = 0.0;
              continue;
            }
          const double d = response.ratio[r] / response.Phi;
          const double w = (2.0 * n - 1.0) * response.flow_power[r];
          const double c = w / (tau_c[r] * response.Phi);
          out.diagonal_tau[r] = c / tau_c[r];
          out.diagonal_tau_c[r] = -c * response.ratio[r] / tau_c[r] - response.direction[r] / tau_c[r];
          out.coupling[r] = c * d;
          out.dPhi_dtau_c[r] = -response.direction[r] * response.ratio[r];
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
