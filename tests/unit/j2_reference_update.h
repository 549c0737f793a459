// The J2 update of J2Plasticity solved the straightforward way: the return mapping as a
// 7-unknown local Newton in the full tensor eps_e = 1/2 log b_e and Delta gamma, its Jacobian and
// the consistent tangent by forward AD (Sacado) through the Pade tensor log and exp of
// TensorFunctions.h (no eigen-decomposition anywhere), the tangent by the implicit function
// theorem of ImplicitLocalProblem. Slow but independent of the principal-space update and its
// hand-derived tangent: the oracle against which the production update must agree to round-off
// (test_j2_fast_update.cc). Same model, same piecewise-linear segment walk. Units: GPa.
#pragma once

#include "materials/ImplicitLocalProblem.h"
#include "materials/J2Plasticity.h"
#include "materials/NeoHookean.h"
#include "materials/TensorFunctions.h"

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <type_traits>

namespace indentsim::testing::reference
{
  using namespace indentsim::materials;
  using dealii::Tensor;

  namespace j2_internal
  {
    inline const double sqrt_3_2 = std::sqrt(1.5);

    // Unknowns of the return mapping: eps_e (6, unrolled) and Delta gamma; parameters:
    // eps_e^tr (6, unrolled) and J.
    constexpr int n_unknowns = 7;
    constexpr int n_parameters = 7;
    constexpr int delta_gamma_index = 6;
    constexpr int J_index = 6;
    using ReturnMapping = ImplicitLocalProblem<n_unknowns, n_parameters>;

    // Forward-AD number over the nine components F_kL (index 3 k + L) for the tangent.
    using ADNumberF = Sacado::Fad::SFad<double, 9>;

    // Residual of the backward-Euler exponential-map return (see J2Plasticity.h), scaled to
    // strain units (the yield condition is divided by mu) so one tolerance fits both parts:
    //   R_eps = eps_e - eps_e^tr + Delta gamma N(eps_e),   N = sqrt(3/2) dev b_e / |dev b_e|,
    //   R_f   = (sqrt(3/2) |dev tau| / J^m - sigma_y(gamma_p,n + Delta gamma)) / mu,
    // using dev tau = mu dev b_e (eq. 3 with eq. 2) and b_e = exp(2 eps_e) (eq. 9). The flow
    // stress is the line sigma_y,n + H Delta gamma (a linear law, or one segment of a table),
    // or, when `smooth_law` is set, that law (power, Voce) with its value and slope: the
    // Jacobian and the sensitivity need first derivatives only.
    struct ReturnMappingResidual
    {
      double mu;
      double yield_stress_n;    // the line's sigma_y at gamma_p,n; the law's sigma_y(gamma_p,n)
      double hardening_modulus; // the line's slope H; the law's slope at gamma_p,n (initial guess)
      bool   cauchy;
      double gamma_p_n = 0.0;
      const IsotropicHardening *smooth_law = nullptr;

      template <typename Number>
      Number flow_stress(const Number &delta_gamma) const
      {
        if (smooth_law == nullptr)
          return yield_stress_n + hardening_modulus * delta_gamma;
        if constexpr (std::is_same_v<Number, double>)
          return smooth_law->flow_stress(gamma_p_n + delta_gamma);
        else
          {
            const auto value = smooth_law->evaluate(gamma_p_n + delta_gamma.val());
            return value.stress + value.slope * (delta_gamma - delta_gamma.val());
          }
      }

      template <typename Number>
      void operator()(const std::array<Number, n_unknowns>   &x,
                      const std::array<Number, n_parameters> &p,
                      std::array<Number, n_unknowns>         &R) const
      {
        using std::exp;
        // dev b_e = exp(2 tr(eps_e)/3) dev(exp(2 dev eps_e) - I), written with exp - I so that
        // the small deviatoric part keeps full relative accuracy (it sets N).
        const Number                          mean_eps_e = (x[0] + x[1] + x[2]) / 3.0;
        dealii::SymmetricTensor<2, 3, Number> two_dev_eps_e;
        for (unsigned int k = 0; k < 6; ++k)
          two_dev_eps_e.access_raw_entry(k) = 2.0 * (k < 3 ? x[k] - mean_eps_e : x[k]);
        const auto dev_b_e =
            scaled(exp(2.0 * mean_eps_e), deviator_symmetric(expm1_symmetric(two_dev_eps_e)));
        const Number norm_dev_b_e = norm_symmetric(dev_b_e);
        const Number flow_factor = (sqrt_3_2 * x[delta_gamma_index]) / norm_dev_b_e;
        for (unsigned int k = 0; k < 6; ++k)
          R[k] = x[k] - p[k] + flow_factor * dev_b_e.access_raw_entry(k);
        const Number equivalent_stress_over_mu =
            cauchy ? Number(sqrt_3_2 * norm_dev_b_e / p[J_index]) : Number(sqrt_3_2 * norm_dev_b_e);
        R[delta_gamma_index] =
            equivalent_stress_over_mu - flow_stress<Number>(x[delta_gamma_index]) / mu;
      }
    };

    // The return mapping's parameters eps_e^tr = 1/2 log b_e^tr (6, unrolled) and J; when the
    // tangent is wanted, also as forward-AD functions of the components of F.
    struct TrialParameters
    {
      ReturnMapping::Parameters           values;
      dealii::Tensor<2, 3, ADNumberF>     F_ad;
      std::array<ADNumberF, n_parameters> ad;
    };

    inline TrialParameters trial_parameters(const dealii::Tensor<2, 3>          &F,
                                            const dealii::SymmetricTensor<2, 3> &C_p_inverse_n,
                                            const dealii::SymmetricTensor<2, 3> &b_e_trial,
                                            const double J, const bool with_derivatives)
    {
      TrialParameters trial;
      if (with_derivatives)
        {
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int L = 0; L < 3; ++L)
              trial.F_ad[k][L] = ADNumberF(9, 3 * k + L, F[k][L]);
          const auto log_b_e_trial = log_spd(push_forward_symmetric(trial.F_ad, C_p_inverse_n));
          for (unsigned int k = 0; k < 6; ++k)
            trial.ad[k] = 0.5 * log_b_e_trial.access_raw_entry(k);
          trial.ad[J_index] = determinant_3x3(trial.F_ad);
          trial.ad[J_index].val() = J; // same value, without the cancellation of det F
          for (unsigned int a = 0; a < n_parameters; ++a)
            trial.values[a] = trial.ad[a].val();
        }
      else
        {
          const auto log_b_e_trial = log_spd(b_e_trial);
          for (unsigned int k = 0; k < 6; ++k)
            trial.values[k] = 0.5 * log_b_e_trial.access_raw_entry(k);
          trial.values[J_index] = J;
        }
      return trial;
    }

    enum class ReturnOutcome
    {
      plastic,          // Delta gamma > 0
      on_yield_surface, // Delta gamma = 0 to round-off: the elastic solution
      not_converged
    };

    // The local Newton of the return mapping. First initial guess: the radial return of the
    // Hencky approximation dev tau ~ 2 mu dev eps_e, for which
    // sigma_HMH = sqrt(3/2) 2 mu |dev eps_e| / J^m drops by 3 mu Delta gamma / J^m along N
    // (exact for small elastic strains, so Newton starts in its quadratic range; the
    // neo-Hookean f^tr would overshoot for large trial strains, where exp(2 eps) >> 1 + 2 eps,
    // and could land on the spurious reversed-flow root). Fallback: Newton from the trial state
    // itself (Delta gamma = 0).
    inline ReturnOutcome solve_return_mapping(const ReturnMappingResidual     &residual,
                                              const ReturnMapping::Parameters &parameters,
                                              const double J_m, ReturnMapping::Unknowns &unknowns)
    {
      const double mu = residual.mu, yield_stress_n = residual.yield_stress_n;
      const auto   set_hencky_guess = [&]() {
        const double                  mean = (parameters[0] + parameters[1] + parameters[2]) / 3.0;
        dealii::SymmetricTensor<2, 3> dev_eps_trial;
        for (unsigned int k = 0; k < 6; ++k)
          dev_eps_trial.access_raw_entry(k) = parameters[k] - (k < 3 ? mean : 0.0);
        const double norm_dev = norm_symmetric(dev_eps_trial);
        const double delta_gamma_0 =
            std::max(sqrt_3_2 * 2.0 * mu * norm_dev / J_m - yield_stress_n, 0.0) /
            (3.0 * mu / J_m + residual.hardening_modulus);
        for (unsigned int k = 0; k < 6; ++k)
          unknowns[k] = parameters[k] -
                        delta_gamma_0 * sqrt_3_2 * dev_eps_trial.access_raw_entry(k) / norm_dev;
        unknowns[delta_gamma_index] = delta_gamma_0;
      };
      const auto set_trial_guess = [&]() {
        for (unsigned int k = 0; k < 6; ++k)
          unknowns[k] = parameters[k];
        unknowns[delta_gamma_index] = 0.0;
      };

      LocalNewtonSettings settings;
      // Round-off of the residual is ~1e-16 of the largest strain involved.
      double strain_scale = yield_stress_n / mu;
      for (unsigned int k = 0; k < 6; ++k)
        strain_scale = std::max(strain_scale, std::abs(parameters[k]));
      settings.tolerance = 1e-14 * strain_scale;
      settings.stagnation_tolerance = 1e-11 * strain_scale;
      for (unsigned int attempt = 0; attempt < 2; ++attempt)
        {
          if (attempt == 0)
            set_hencky_guess();
          else
            set_trial_guess();
          const LocalNewtonResult newton =
              ReturnMapping::solve(residual, parameters, unknowns, settings);
          // Delta gamma > 0 is guaranteed for f^tr > 0 (KKT); anything else is a spurious root.
          if (newton.converged && unknowns[delta_gamma_index] > 0.0)
            return ReturnOutcome::plastic;
          // A trial state on the yield surface to round-off returns Delta gamma = 0
          // (+- round-off): that is the elastic solution, not a failure.
          if (newton.converged && std::abs(unknowns[delta_gamma_index]) <= 1e-10 * strain_scale)
            return ReturnOutcome::on_yield_surface;
        }
      return ReturnOutcome::not_converged;
    }

    // The return on a piecewise-linear law (linear, table), segment by segment. With segment k's
    // line sigma_k(gamma_p) in place of sigma_y, the yield residual
    //   g_k(Delta gamma) = sigma_HMH(Delta gamma) - sigma_k(gamma_p,n + Delta gamma)
    // decreases strictly (sigma_HMH falls along the return, the slope of sigma_k is >= 0), and
    // it equals the true residual g at the segment's ends. So if line k's root lands beyond the
    // segment's end, g > 0 there and the true root lies further on; if it lands before the
    // segment's start, the true root lies before it; otherwise it is the true root. The walk
    // starts at the segment where the Hencky estimate of the return (a scalar, piecewise-linear
    // equation solved here exactly) ends, and moves one segment at a time; each solve is the
    // smooth linear-hardening return, so a kink is never inside a Newton iteration. A root on a
    // kink to round-off (the walk turns back) is accepted where it is.
    inline ReturnOutcome solve_piecewise_linear_return(const IsotropicHardening        &law,
                                                       ReturnMappingResidual           &residual,
                                                       const ReturnMapping::Parameters &parameters,
                                                       const double                     J_m,
                                                       ReturnMapping::Unknowns         &unknowns)
    {
      const double       gamma_p_n = residual.gamma_p_n;
      const unsigned int first = law.segment(gamma_p_n), last = law.n_segments() - 1;
      const auto         use_segment = [&](const unsigned int k) {
        const IsotropicHardening::FlowStress line = law.segment_line(k, gamma_p_n);
        residual.yield_stress_n = line.stress;
        residual.hardening_modulus = line.slope;
      };
      if (first == last)
        {
          use_segment(first);
          return solve_return_mapping(residual, parameters, J_m, unknowns);
        }

      // Hencky estimate: sqrt(3/2) 2 mu |dev eps_e^tr| / J^m - 3 mu Delta gamma / J^m on line k.
      const double mean = (parameters[0] + parameters[1] + parameters[2]) / 3.0;
      double       norm_squared = 0.0;
      for (unsigned int k = 0; k < 6; ++k)
        {
          const double dev = parameters[k] - (k < 3 ? mean : 0.0);
          norm_squared += (k < 3 ? 1.0 : 2.0) * dev * dev;
        }
      const double trial_stress = sqrt_3_2 * 2.0 * residual.mu * std::sqrt(norm_squared) / J_m;
      unsigned int k = first;
      while (k < last)
        {
          const IsotropicHardening::FlowStress line = law.segment_line(k, gamma_p_n);
          const double                         delta_gamma =
              (trial_stress - line.stress) / (3.0 * residual.mu / J_m + line.slope);
          if (gamma_p_n + delta_gamma <= law.segment_end(k))
            break;
          ++k;
        }

      int previous_move = 0;
      for (unsigned int attempt = 0; attempt <= last - first + 1; ++attempt)
        {
          use_segment(k);
          const ReturnOutcome outcome = solve_return_mapping(residual, parameters, J_m, unknowns);
          if (outcome == ReturnOutcome::not_converged)
            return outcome;
          const double gamma_p = gamma_p_n + unknowns[delta_gamma_index];
          if (k < last && gamma_p > law.segment_end(k) && previous_move >= 0)
            {
              ++k;
              previous_move = 1;
            }
          else if (k > first && gamma_p < law.segment_start(k) && previous_move <= 0)
            {
              --k;
              previous_move = -1;
            }
          else
            return outcome;
        }
      return ReturnOutcome::not_converged;
    }

    // Consistent tangent: eps_e(F) through the implicit function theorem, then
    // P = tau(b_e) F^-T differentiated by forward AD over the components of F. Fills `response`
    // and returns b_e, or nothing if the local Jacobian is singular.
    inline std::optional<dealii::SymmetricTensor<2, 3>>
    stress_and_tangent(const NeoHookean &elasticity, const double J_minus_one,
                       const ReturnMappingResidual &residual, const TrialParameters &trial,
                       const ReturnMapping::Unknowns &unknowns, MaterialPointResponse &response)
    {
      ReturnMapping::Sensitivity dx_dp;
      if (!ReturnMapping::sensitivity(residual, trial.values, unknowns, dx_dp))
        return std::nullopt;
      const auto unknowns_ad = ReturnMapping::linearized_solution(unknowns, dx_dp, trial.ad);
      dealii::SymmetricTensor<2, 3, ADNumberF> two_eps_e_ad;
      for (unsigned int k = 0; k < 6; ++k)
        two_eps_e_ad.access_raw_entry(k) = 2.0 * unknowns_ad[k];
      const auto b_e_ad = exp_symmetric(two_eps_e_ad);

      // tau = mu (b_e - 1) + lambda/2 (J^2 - 1) 1 (eq. 3); the pressure value is taken from
      // J - 1, its derivative lambda J dJ/dF from AD.
      const double     mu = elasticity.shear_modulus();
      const ADNumberF &J_ad = trial.ad[J_index];
      ADNumberF        pressure_term = 0.5 * elasticity.lame_lambda() * (J_ad * J_ad - 1.0);
      pressure_term.val() = 0.5 * elasticity.lame_lambda() * J_minus_one * (J_minus_one + 2.0);
      dealii::Tensor<2, 3, ADNumberF> tau_ad;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            tau_ad[i][j] = mu * b_e_ad[i][j];
            if (i == j)
              tau_ad[i][j] += pressure_term - mu;
          }
      const auto F_inverse_ad = inverse_3x3(trial.F_ad);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J_col = 0; J_col < 3; ++J_col)
          {
            ADNumberF P_iJ = tau_ad[i][0] * F_inverse_ad[J_col][0];
            for (unsigned int m = 1; m < 3; ++m)
              P_iJ += tau_ad[i][m] * F_inverse_ad[J_col][m];
            response.P[i][J_col] = P_iJ.val();
            response.tau[i][J_col] = tau_ad[i][J_col].val();
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int L = 0; L < 3; ++L)
                response.dP_dF[i][J_col][k][L] = P_iJ.dx(3 * k + L);
          }
      dealii::SymmetricTensor<2, 3> b_e;
      for (unsigned int k = 0; k < 6; ++k)
        b_e.access_raw_entry(k) = b_e_ad.access_raw_entry(k).val();
      return b_e;
    }

    // tau(b_e) and P = tau F^-T without the tangent; returns b_e.
    inline dealii::SymmetricTensor<2, 3>
    stress(const NeoHookean &elasticity, const dealii::Tensor<2, 3> &F, const double J_minus_one,
           const ReturnMapping::Unknowns &unknowns, MaterialPointResponse &response)
    {
      dealii::SymmetricTensor<2, 3> two_eps_e;
      for (unsigned int k = 0; k < 6; ++k)
        two_eps_e.access_raw_entry(k) = 2.0 * unknowns[k];
      const dealii::SymmetricTensor<2, 3> b_e = exp_symmetric(two_eps_e);
      const dealii::SymmetricTensor<2, 3> tau = elasticity.kirchhoff_stress(b_e, J_minus_one);
      const dealii::Tensor<2, 3>          F_inverse = inverse_3x3(F);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J_col = 0; J_col < 3; ++J_col)
          {
            double P_iJ = 0.0;
            for (unsigned int m = 0; m < 3; ++m)
              P_iJ += tau[i][m] * F_inverse[J_col][m];
            response.P[i][J_col] = P_iJ;
            response.tau[i][J_col] = tau[i][J_col];
          }
      return b_e;
    }
  } // namespace j2_internal

  // J2Plasticity::update computed by the AD oracle: same arguments, same results to round-off.
  inline UpdateStatus update(const J2Plasticity &model, const Tensor<2, 3> &F,
                             std::span<const double> state_old, MaterialPointResponse &response,
                             std::span<double> state_new, const bool compute_tangent = true)
  {
    using namespace j2_internal;
    const NeoHookean         &elasticity = model.elastic_law();
    const IsotropicHardening &hardening = model.hardening_law();
    const YieldStressMeasure  measure = model.yield_stress_measure();
    const auto flow_stress = [&](const double gamma_p) { return hardening.flow_stress(gamma_p); };
    const auto plastic_metric_inverse = [](std::span<const double> state) {
      return J2Plasticity::plastic_metric_inverse(state);
    };
    constexpr unsigned int gamma_p_index = J2Plasticity::gamma_p_index;
    Assert(state_old.size() == J2Plasticity::n_state,
           dealii::ExcDimensionMismatch(state_old.size(), J2Plasticity::n_state));
    Assert(state_new.size() == J2Plasticity::n_state,
           dealii::ExcDimensionMismatch(state_new.size(), J2Plasticity::n_state));

    double J_minus_one = 0.0;
    if (!admissible_deformation(F, J_minus_one))
      return UpdateStatus::invalid_deformation;
    const double J = 1.0 + J_minus_one;
    const double mu = elasticity.shear_modulus();
    const bool   cauchy = (measure == YieldStressMeasure::cauchy);

    const dealii::SymmetricTensor<2, 3> C_p_inverse_n = plastic_metric_inverse(state_old);
    const double                        gamma_p_n = state_old[gamma_p_index];
    const double                        yield_stress_n = flow_stress(gamma_p_n);
    // Elastic step (KKT, eq. 8, with Delta gamma = 0): the neo-Hookean response in
    // b_e = F C_p^-1 F^T with the plastic state frozen.
    const auto elastic_step = [&]() {
      elasticity.elastic_response(F, C_p_inverse_n, J_minus_one, response, compute_tangent);
      std::copy(state_old.begin(), state_old.end(), state_new.begin());
      return UpdateStatus::success;
    };

    // Elastic predictor: tau(b_e^tr) directly, no logarithm needed (dev tau = mu dev b_e).
    const dealii::SymmetricTensor<2, 3> b_e_trial = push_forward_symmetric(F, C_p_inverse_n);
    const double norm_dev_b_e_trial = norm_symmetric(deviator_symmetric(b_e_trial));
    const double trial_yield_function =
        sqrt_3_2 * mu * norm_dev_b_e_trial / (cauchy ? J : 1.0) - yield_stress_n;
    if (trial_yield_function <= 0.0)
      return elastic_step();

    // Plastic corrector: the return mapping from eps_e^tr.
    const TrialParameters trial = trial_parameters(F, C_p_inverse_n, b_e_trial, J, compute_tangent);
    ReturnMappingResidual residual{mu, yield_stress_n, 0.0, cauchy, gamma_p_n};
    ReturnMapping::Unknowns unknowns;
    ReturnOutcome           outcome;
    if (hardening.piecewise_linear())
      outcome = solve_piecewise_linear_return(hardening, residual, trial.values, cauchy ? J : 1.0,
                                              unknowns);
    else
      {
        residual.hardening_modulus = hardening.slope(gamma_p_n);
        residual.smooth_law = &hardening;
        outcome = solve_return_mapping(residual, trial.values, cauchy ? J : 1.0, unknowns);
      }
    switch (outcome)
      {
      case ReturnOutcome::on_yield_surface:
        return elastic_step();
      case ReturnOutcome::not_converged:
        std::copy(state_old.begin(), state_old.end(), state_new.begin());
        return UpdateStatus::local_newton_failed;
      case ReturnOutcome::plastic:
        break;
      }

    std::optional<dealii::SymmetricTensor<2, 3>> b_e =
        compute_tangent
            ? stress_and_tangent(elasticity, J_minus_one, residual, trial, unknowns, response)
            : stress(elasticity, F, J_minus_one, unknowns, response);
    if (!b_e)
      {
        std::copy(state_old.begin(), state_old.end(), state_new.begin());
        return UpdateStatus::local_newton_failed;
      }

    // Updated plastic metric C_p^-1 = F^-1 b_e F^-T (eq. 9 pulled back) and gamma_p.
    const dealii::SymmetricTensor<2, 3> C_p_inverse = push_forward_symmetric(inverse_3x3(F), *b_e);
    for (unsigned int k = 0; k < 6; ++k)
      state_new[k] = C_p_inverse.access_raw_entry(k);
    state_new[gamma_p_index] = gamma_p_n + unknowns[delta_gamma_index];
    return UpdateStatus::success;
  }
} // namespace indentsim::testing::reference
