// Extended Voce hardening per slip family (ExtendedVoceHardening.h gives the law and its secant
// integration): family f has its own tau0_f, tau1_f, theta0_f, theta1_f; all families harden with
// the total slip Gamma, and the latent ratios are the common q (h_rs = q + (1 - q) delta_rs):
//   Delta tau_c^r = Hbar_f(r) (q Delta Gamma + (1 - q) |Delta gamma^r|),
// or a matrix q_fg between families (h_rs = q_f(r)f(s) for r != s, 1 for r = s):
//   Delta tau_c^r = Hbar_f (sum_g q_fg Delta Gamma_g + (1 - q_ff) |Delta gamma^r|),  f = f(r),
// Delta Gamma_g the slip of family g's systems over the increment, Hbar_f the secant of family
// f's law, so that with q = 1 every system of family f has tau_c^r = tau_c,f(Gamma) exactly.
// One family (FCC, or a single block in the case file) is the paper's law. Each family's
// irradiation term tau_irr,f(Gamma) (ExtendedVoceHardening.h) adds to every system of the family.
//
// The hardening-law interface of CrystalPlasticityModel (crystal/CrystalPlasticityModel.h):
//   initial_critical_shear(r)    tau_c^r of the virgin state [GPa],
//   stress_scale()               the integrator's stress scale tau_ref: the smallest tau0 [GPa],
//   increment(Gamma_n, |Delta gamma|, Delta Gamma, out)
//                                Delta tau_c^r over the increment and its derivative in the form
//                                dDelta tau_c^r = a_r dDelta Gamma + b_r d|Delta gamma^r|,
//   parameter_error()            nullptr, or what is wrong with the parameters.
// Units: GPa.
#pragma once

#include "materials/crystal/ExtendedVoceHardening.h"

#include <Sacado.hpp>

#include <algorithm>
#include <array>
#include <tuple>
#include <utility>
#include <vector>

namespace indentsim::materials
{
  struct FamilyVoceHardening
  {
    std::vector<ExtendedVoceHardening> laws;    // per family; their own q is not used
    std::vector<unsigned int> family_of_system; // one per system (SlipSystems::family), or empty:
                                                // every system follows laws[0]
    double q = 1.4;                             // latent hardening ratio [-]
    // q_fg, laws.size() rows and columns; empty: q for every pair of systems.
    std::vector<std::vector<double>> latent_matrix;

    // One law for every system (with its q).
    FamilyVoceHardening(const ExtendedVoceHardening &law = ExtendedVoceHardening())
      : laws{law}
      , q(law.q)
    {
    }
    FamilyVoceHardening(std::vector<ExtendedVoceHardening> laws,
                        std::vector<unsigned int> family_of_system, const double q,
                        std::vector<std::vector<double>> latent_matrix = {})
      : laws(std::move(laws))
      , family_of_system(std::move(family_of_system))
      , q(q)
      , latent_matrix(std::move(latent_matrix))
    {
    }

    const ExtendedVoceHardening &law_of_system(const unsigned int r) const
    {
      return laws[family_of_system.empty() ? 0 : family_of_system[r]];
    }
    double initial_critical_shear(const unsigned int r) const
    {
      return law_of_system(r).tau0 + law_of_system(r).tau_irr;
    }
    double stress_scale() const
    {
      double smallest = laws.front().tau0;
      for (const ExtendedVoceHardening &law : laws)
        smallest = std::min(smallest, law.tau0);
      return smallest;
    }

    // Hbar_f and Hbar_f' (one forward-AD direction) per family, then each system's share.
    template <int n_slip>
    void increment(const double Gamma_n, const std::array<double, n_slip> &abs_delta_gamma,
                   const double delta_Gamma, HardeningIncrement<n_slip> &out) const
    {
      using SecantDerivative = Sacado::Fad::SFad<double, 1>;
      constexpr unsigned int           max_families = max_slip_families;
      std::array<double, max_families> H_bar, dH_bar, irradiation, dirradiation;
      for (unsigned int f = 0; f < laws.size(); ++f)
        {
          std::tie(irradiation[f], dirradiation[f]) =
              laws[f].irradiation_increment(Gamma_n, delta_Gamma);
          const SecantDerivative H =
              laws[f].secant_modulus(Gamma_n, SecantDerivative(1, 0, delta_Gamma));
          H_bar[f] = H.val();
          dH_bar[f] = H.fastAccessDx(0);
        }
      if (latent_matrix.empty())
        {
          for (int r = 0; r < n_slip; ++r)
            {
              const unsigned int f = family_of_system.empty() ? 0 : family_of_system[r];
              const double       latent_slip = q * delta_Gamma + (1.0 - q) * abs_delta_gamma[r];
              out.value[r] = H_bar[f] * latent_slip + irradiation[f];
              out.total_rate[r] = dH_bar[f] * latent_slip + H_bar[f] * q + dirradiation[f];
              out.own_rate[r] = H_bar[f] * (1.0 - q);
            }
          out.n_families = 0;
          return;
        }

      const unsigned int               n_families = laws.size();
      std::array<double, max_families> delta_Gamma_family{};
      for (int r = 0; r < n_slip; ++r)
        delta_Gamma_family[family_of_system[r]] += abs_delta_gamma[r];
      out.n_families = n_families;
      out.family_of_system = family_of_system.data();
      for (int r = 0; r < n_slip; ++r)
        {
          const unsigned int         f = family_of_system[r];
          const std::vector<double> &q_f = latent_matrix[f];
          double                     latent_slip = (1.0 - q_f[f]) * abs_delta_gamma[r];
          for (unsigned int g = 0; g < n_families; ++g)
            latent_slip += q_f[g] * delta_Gamma_family[g];
          out.value[r] = H_bar[f] * latent_slip + irradiation[f];
          out.total_rate[r] = dH_bar[f] * latent_slip + dirradiation[f];
          out.own_rate[r] = H_bar[f] * (1.0 - q_f[f]);
          for (unsigned int g = 0; g < n_families; ++g)
            out.family_rate[r][g] = H_bar[f] * q_f[g];
        }
    }

    const char *parameter_error() const
    {
      if (laws.empty() || laws.size() > max_slip_families)
        return "between 1 and 8 slip families need a hardening law";
      for (const unsigned int f : family_of_system)
        if (f >= laws.size())
          return "a slip system's family has no hardening law";
      if (!(q >= 0))
        return "the latent hardening ratio q must be non-negative";
      if (!latent_matrix.empty())
        {
          if (latent_matrix.size() != laws.size() || family_of_system.empty())
            return "the latent matrix needs one row per slip family and the systems' families";
          for (const std::vector<double> &row : latent_matrix)
            {
              if (row.size() != laws.size())
                return "the latent matrix needs one column per slip family";
              for (const double q_fg : row)
                if (!(q_fg >= 0))
                  return "the latent hardening ratios must be non-negative";
            }
        }
      for (const ExtendedVoceHardening &law : laws)
        if (const char *error = law.parameter_error())
          return error;
      return nullptr;
    }
  };
} // namespace indentsim::materials
