// The implementation of CrystalPlasticityModel (see its header), included by the translation
// units that instantiate it.
#pragma once

#include "materials/ImplicitLocalProblem.h"
#include "materials/NeoHookean.h"
#include "materials/TensorFunctions.h"
#include "materials/crystal/CrystalLocalProblem.h"
#include "materials/crystal/CrystalPlasticityModel.h"
#include "materials/crystal/MatrixExponential.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace indentsim::materials
{
  namespace crystal
  {
    // P = F_e S_e F_p^-T and the Kirchhoff stress tau = P F^T.
    inline void write_stress(const Matrix &F_e, const Matrix &S_e, const Matrix &F_p_inverse,
                             const Tensor<2, 3> &F, MaterialPointResponse &response)
    {
      const auto P = multiply_transposed_second(multiply(F_e, S_e), F_p_inverse);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J = 0; J < 3; ++J)
          response.P[i][J] = P[i][J];
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            double sum = 0.0;
            for (unsigned int m = 0; m < 3; ++m)
              sum += response.P[i][m] * F[j][m];
            response.tau[i][j] = sum;
          }
    }

    // The settings of the crystal's local Newton for strains of size strain_scale.
    inline LocalNewtonSettings local_newton_settings(const double strain_scale)
    {
      LocalNewtonSettings settings;
      settings.max_iterations = 50;
      settings.max_line_search_steps = 20;
      // Forming A^T C_e^tr A near the identity leaves round-off ~1e-16 in E_e whatever its size.
      settings.tolerance = std::max(1e-13 * strain_scale, 2e-15);
      settings.stagnation_tolerance = std::max(1e-10 * strain_scale, 1e-13);
      return settings;
    }

    // The unrolled elastic strain of F with plastic part F_p^-1 = G: E_e = 1/2 ((F G)^T F G - I).
    inline Symmetric elastic_strain(const Matrix &F, const Matrix &G)
    {
      const Matrix F_e = multiply(F, G);
      return green_lagrange_strain(multiply_transposed_first(F_e, F_e));
    }

    // The state at the converged plastic point: F_p = exp(Delta L_p) F_p,n (eq. 12), tau_c^r and
    // Gamma_n + sum_r |Delta gamma^r|. False if any entry is not finite.
    template <typename LocalProblem>
    bool store_plastic_state(const LocalProblem                    &problem,
                             const typename LocalProblem::Unknowns &unknowns,
                             std::span<const double> state_old, std::span<double> state_new)
    {
      constexpr int n_slip = LocalProblem::n_unknowns - 7;
      Matrix        delta_L_p = problem.minus_delta_L_p();
      for (auto &row : delta_L_p)
        for (double &a : row)
          a = -a;
      double delta_Gamma = 0.0;
      for (int r = 0; r < n_slip; ++r)
        delta_Gamma += std::abs(problem.slip.flow.delta_gamma[r]);
      Matrix F_p_n;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          F_p_n[i][j] = state_old[3 * i + j];
      const Matrix F_p_new = multiply(exp_matrix(delta_L_p), F_p_n);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          state_new[3 * i + j] = F_p_new[i][j];
      for (int r = 0; r < n_slip; ++r)
        state_new[9 + r] = problem.laws.stress_scale * unknowns[LocalProblem::tau_c_index + r];
      state_new[9 + n_slip] = state_old[9 + n_slip] + delta_Gamma;
      for (const double v : state_new)
        if (!std::isfinite(v))
          return false;
      return true;
    }
  } // namespace crystal

  template <typename Elasticity, typename FlowRule, typename Hardening>
  CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::CrystalPlasticityModel(
      const SlipSystems &slip_systems, const Elasticity &elasticity, const FlowRule &flow_rule,
      const Hardening &hardening)
    : systems(slip_systems)
    , n_systems(slip_systems.size())
    , elasticity(elasticity)
    , flow(flow_rule)
    , hardening(hardening)
  {
    const auto require = [](const char *error) {
      if (error)
        throw std::invalid_argument(std::string("CrystalPlasticity: ") + error);
    };
    if (std::find(slip_system_counts.begin(), slip_system_counts.end(), n_systems) ==
        slip_system_counts.end())
      {
        std::string counts;
        for (const unsigned int count : slip_system_counts)
          counts += (counts.empty() ? "" : ", ") + std::to_string(count);
        require(("the integrator is instantiated for " + counts + " slip systems, got " +
                 std::to_string(n_systems))
                    .c_str());
      }
    require(elasticity.parameter_error());
    require(hardening.parameter_error());
    require(flow_rule.parameter_error());
    for (unsigned int r = 0; r < n_systems; ++r)
      schmid.push_back(crystal::to_matrix(systems.schmid_tensor(r)));
    elastic_limit = flow.elastic_limit(n_systems);
  }

  template <typename Elasticity, typename FlowRule, typename Hardening>
  void CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::initial_state(
      std::span<double> state) const
  {
    oriented_initial_state(state, dealii::unit_symmetric_tensor<3>());
  }

  template <typename Elasticity, typename FlowRule, typename Hardening>
  void CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::oriented_initial_state(
      std::span<double> state, const Tensor<2, 3> &orientation) const
  {
    Assert(state.size() == n_state_variables(),
           dealii::ExcDimensionMismatch(state.size(), n_state_variables()));
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        state[3 * i + j] = orientation[i][j];
    for (unsigned int r = 0; r < n_systems; ++r)
      state[9 + r] = hardening.initial_critical_shear(r);
    state[9 + n_systems] = 0.0;
  }

  template <typename Elasticity, typename FlowRule, typename Hardening>
  Tensor<2, 3> CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::plastic_deformation(
      std::span<const double> state)
  {
    Tensor<2, 3> F_p;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        F_p[i][j] = state[3 * i + j];
    return F_p;
  }

  template <typename Elasticity, typename FlowRule, typename Hardening>
  std::vector<double>
  CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::resolved_shear_stresses(
      const Tensor<2, 3> &F, std::span<const double> state) const
  {
    using namespace crystal;
    const Symmetric E =
        elastic_strain(to_matrix(F), to_matrix(inverse_3x3(plastic_deformation(state))));
    const double                                       tau_ref = hardening.stress_scale();
    const CrystalLaws<Elasticity, FlowRule, Hardening> laws{
        &elasticity, &flow, &hardening, schmid.data(), tau_ref, elasticity.stiffness_scale()};
    Matrix              S_e;
    std::vector<double> tau(n_systems);
    resolved_shears(laws, E.data(), n_systems, S_e, tau.data());
    return tau;
  }

  template <typename Elasticity, typename FlowRule, typename Hardening>
  UpdateStatus CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::update(
      const Tensor<2, 3> &F, std::span<const double> state_old, MaterialPointResponse &response,
      std::span<double> state_new, const bool compute_tangent) const
  {
    Assert(state_old.size() == n_state_variables(),
           dealii::ExcDimensionMismatch(state_old.size(), n_state_variables()));
    Assert(state_new.size() == n_state_variables(),
           dealii::ExcDimensionMismatch(state_new.size(), n_state_variables()));
    return dispatch_update(std::make_index_sequence<slip_system_counts.size()>(), F, state_old,
                           response, state_new, compute_tangent);
  }

  template <typename Elasticity, typename FlowRule, typename Hardening>
  template <std::size_t... index>
  UpdateStatus CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::dispatch_update(
      std::index_sequence<index...>, const Tensor<2, 3> &F, std::span<const double> state_old,
      MaterialPointResponse &response, std::span<double> state_new,
      const bool compute_tangent) const
  {
    UpdateStatus status = UpdateStatus::invalid_deformation;
    ((n_systems == slip_system_counts[index] &&
      (status = update_impl<slip_system_counts[index]>(F, state_old, response, state_new,
                                                       compute_tangent),
       true)) ||
     ...);
    return status;
  }

  // The starting point of the local Newton from a hint state (F_p, tau_c, Gamma) of the same
  // increment, written into x: E_e of the hint's F_p at the new F, its tau_c, and Delta lambda
  // from its Delta Gamma = Delta lambda sum_r |Delta gamma^r(lambda = 1)|. False when the hint is
  // not plastic relative to state_old (Gamma_hint <= Gamma_n, e.g. state_new == state_old at the
  // start of an increment) or not usable (not finite, F_p far from isochoric, tau_c <= 0).
  template <typename Elasticity, typename FlowRule, typename Hardening>
  template <int n_slip>
  bool CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::warm_start_guess(
      const crystal::Matrix &F, std::span<const double> state_old, std::span<const double> hint,
      std::array<double, 7 + n_slip> &x) const
  {
    using namespace crystal;
    const double delta_Gamma = hint[9 + n_slip] - state_old[9 + n_slip];
    if (!(delta_Gamma > 0.0) || !std::isfinite(delta_Gamma))
      return false;
    Tensor<2, 3> F_p_hint;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          F_p_hint[i][j] = hint[3 * i + j];
          if (!std::isfinite(F_p_hint[i][j]))
            return false;
        }
    if (!(std::abs(dealii::determinant(F_p_hint) - 1.0) < 0.5))
      return false;
    const Symmetric E = elastic_strain(F, to_matrix(inverse_3x3(F_p_hint)));
    std::copy(E.begin(), E.end(), x.begin());
    const double tau_ref = hardening.stress_scale();
    for (int r = 0; r < n_slip; ++r)
      {
        x[7 + r] = hint[9 + r] / tau_ref;
        if (!(x[7 + r] > 0.0) || !std::isfinite(x[7 + r]))
          return false;
      }
    const CrystalLaws<Elasticity, FlowRule, Hardening> laws{
        &elasticity, &flow, &hardening, schmid.data(), tau_ref, elasticity.stiffness_scale()};
    SlipState<FlowRule, n_slip> unit;
    evaluate_slip<decltype(laws), FlowRule, n_slip>(laws, x.data(), &x[7], 1.0, unit);
    double unit_Gamma = 0.0;
    for (int r = 0; r < n_slip; ++r)
      unit_Gamma += std::abs(unit.flow.delta_gamma[r]);
    if (!(unit_Gamma > 0.0) || !std::isfinite(unit_Gamma))
      return false;
    x[6] = delta_Gamma / unit_Gamma;
    return true;
  }

  template <typename Elasticity, typename FlowRule, typename Hardening>
  template <int n_slip>
  UpdateStatus CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::update_impl(
      const Tensor<2, 3> &F, std::span<const double> state_old, MaterialPointResponse &response,
      std::span<double> state_new, const bool compute_tangent) const
  {
    using namespace crystal;
    using LocalProblem = CrystalLocalProblem<Elasticity, FlowRule, Hardening, n_slip>;
    constexpr int n_unknowns = LocalProblem::n_unknowns;
    using Newton = ImplicitLocalProblem<n_unknowns, 6>;

    double J_minus_one = 0.0;
    if (!admissible_deformation(F, J_minus_one))
      return UpdateStatus::invalid_deformation;

    const Matrix  F_matrix = to_matrix(F);
    const Matrix  F_p_n_inverse = to_matrix(inverse_3x3(plastic_deformation(state_old)));
    const double *tau_c_n = &state_old[9];
    const double  Gamma_n = state_old[9 + n_slip];
    const double  tau_ref = hardening.stress_scale();
    const typename LocalProblem::Laws laws{&elasticity,   &flow,   &hardening,
                                           schmid.data(), tau_ref, elasticity.stiffness_scale()};

    // Elastic trial: C_e^tr = F_p,n^-T C F_p,n^-1 and E_e^tr.
    const Matrix               F_e_trial = multiply(F_matrix, F_p_n_inverse);
    const Matrix               C_e_trial = multiply_transposed_first(F_e_trial, F_e_trial);
    const Symmetric            E_trial = green_lagrange_strain(C_e_trial);
    std::array<double, n_slip> tau_c_n_scaled;
    for (int r = 0; r < n_slip; ++r)
      tau_c_n_scaled[r] = tau_c_n[r] / tau_ref;

    // Elastic step, P = F_e S_e F_p,n^-T with F_e = F F_p,n^-1.
    const auto elastic_step = [&](const Matrix &S_e) {
      write_stress(F_e_trial, S_e, F_p_n_inverse, F, response);
      if (compute_tangent)
        elasticity.elastic_tangent(F_e_trial, F_p_n_inverse, S_e, response.dP_dF);
      std::copy(state_old.begin(), state_old.end(), state_new.begin());
      return UpdateStatus::success;
    };
    const auto failure = [&]() {
      std::copy(state_old.begin(), state_old.end(), state_new.begin());
      return UpdateStatus::local_newton_failed;
    };

    SlipState<FlowRule, n_slip> trial;
    resolved_shears(laws, E_trial.data(), n_slip, trial.S_e, trial.tau.data());
    bool certainly_elastic = true;
    for (int r = 0; r < n_slip && certainly_elastic; ++r)
      certainly_elastic = std::abs(trial.tau[r]) < tau_ref * elastic_limit * tau_c_n_scaled[r];
    if (certainly_elastic)
      return elastic_step(trial.S_e);
    flow.template evaluate<n_slip>(trial.tau, tau_c_n_scaled.data(), 0.0, tau_ref, trial.flow);
    if (!std::isfinite(trial.flow.Phi))
      return UpdateStatus::invalid_deformation;
    // KKT (eq. 8): no plastic flow while Phi <= 1.
    if (trial.flow.Phi <= 1.0)
      return elastic_step(trial.S_e);

    // Plastic corrector: the local Newton, from the hint or the elastic trial.
    LocalProblem problem; // the workspace members are written before they are read
    problem.laws = laws;
    problem.Gamma_n = Gamma_n;
    problem.tau_c_n = tau_c_n;
    problem.C_e_trial = C_e_trial;
    std::array<double, n_unknowns> unknowns;
    double                         strain_scale = tau_ref / elasticity.stiffness_scale();
    for (unsigned int k = 0; k < 6; ++k)
      strain_scale = std::max(strain_scale, std::abs(E_trial[k]));
    const LocalNewtonSettings settings = local_newton_settings(strain_scale);

    typename LocalProblem::Jacobian jacobian;
    LocalNewtonResult               newton;
    // Warm start from the hint in state_new (see MaterialModel::update): the previous global
    // Newton iterate of this increment, if it was plastic. Close to convergence of the global
    // Newton it needs fewer local iterations than the elastic trial; a hint that does not
    // converge to Delta lambda > 0 is dropped and the Newton starts again from the trial.
    if (warm_start_guess<n_slip>(F_matrix, state_old, state_new, unknowns))
      {
        newton = Newton::solve_with_jacobian(problem, unknowns, jacobian, settings);
        if (!newton.converged || !(unknowns[LocalProblem::lambda_index] > 0.0))
          newton.converged = false;
      }
    if (!newton.converged)
      {
        std::copy(E_trial.begin(), E_trial.end(), unknowns.begin());
        unknowns[LocalProblem::lambda_index] = 0.0;
        for (int r = 0; r < n_slip; ++r)
          unknowns[LocalProblem::tau_c_index + r] = tau_c_n_scaled[r];
        newton = Newton::solve_with_jacobian(problem, unknowns, jacobian, settings);
      }
    const double lambda_scaled = unknowns[LocalProblem::lambda_index];
    if (!newton.converged || !(lambda_scaled >= 0.0))
      {
        // A trial state on the yield surface to round-off returns Delta lambda = 0 (+- round-off).
        if (newton.converged && std::abs(lambda_scaled) <= 1e-12 * strain_scale)
          return elastic_step(trial.S_e);
        return failure();
      }

    // The converged slip increments and A = exp(-Delta L_p) are those of the last evaluation;
    // the tangent needs the Jacobian there too.
    if (compute_tangent && !newton.jacobian_at_solution)
      {
        std::array<double, n_unknowns> residual;
        problem(unknowns, residual, &jacobian);
      }
    const Matrix F_p_new_inverse = multiply(F_p_n_inverse, problem.A);
    const Matrix F_e = multiply(F_e_trial, problem.A);
    write_stress(F_e, problem.slip.S_e, F_p_new_inverse, F, response);
    if (compute_tangent && !plastic_tangent(problem, jacobian, F_e_trial, F_e, F_p_n_inverse,
                                            F_p_new_inverse, response.dP_dF))
      return failure();

    if (!crystal::store_plastic_state(problem, unknowns, state_old, state_new))
      return failure();
    return UpdateStatus::success;
  }

  // dP/dF at a converged plastic state. Implicit function theorem: dx/dC_e^tr =
  // -(dR/dx)^-1 dR/dC_e^tr, where only R_E depends on C_e^tr: dR_E/dC_e^tr_m = -1/2 A^T U_m A
  // (U_m the unit symmetric tensor of entry m). Then, with F_e = F G A and F_p^-1 = G A
  // (G = F_p,n^-1), P = F_e S_e F_p^-T gives
  //   dP = (dF G A + F G dA) S_e F_p^-T + F_e (L^e : dE_e) F_p^-T + F_e S_e (G dA)^T,
  // with F_e_trial = F G and G_A = G A = F_p^-1.
  template <typename Elasticity, typename FlowRule, typename Hardening>
  template <typename LocalProblem>
  bool CrystalPlasticityModel<Elasticity, FlowRule, Hardening>::plastic_tangent(
      LocalProblem &problem, const typename LocalProblem::Jacobian &jacobian,
      const crystal::Matrix &F_e_trial, const crystal::Matrix &F_e,
      const crystal::Matrix &F_p_n_inverse, const crystal::Matrix &G_A, Tensor<4, 3> &dP_dF) const
  {
    using namespace crystal;
    constexpr int n_unknowns = LocalProblem::n_unknowns;
    constexpr int n_slip = n_unknowns - 7;
    const Matrix &A = problem.A;

    std::array<std::array<double, 6>, n_unknowns> dx_dp{};
    for (unsigned int m = 0; m < 6; ++m)
      {
        Matrix U{};
        U[sym_i[m]][sym_j[m]] = 1.0;
        U[sym_j[m]][sym_i[m]] = 1.0;
        const auto AUA = multiply_transposed_first(A, multiply(U, A));
        for (unsigned int k = 0; k < 6; ++k)
          dx_dp[k][m] = 0.5 * AUA[sym_i[k]][sym_j[k]];
      }
    if (!problem.template solve_linearized<6>(jacobian, dx_dp))
      return false;
    // dDelta gamma/dC_e^tr
    std::array<std::array<double, 6>, n_slip> ddelta_gamma_dp;
    for (int r = 0; r < n_slip; ++r)
      for (unsigned int m = 0; m < 6; ++m)
        {
          double sum = 0.0;
          for (int j = 0; j < n_unknowns; ++j)
            sum += problem.ddelta_gamma_dx[r][j] * dx_dp[j][m];
          ddelta_gamma_dp[r][m] = sum;
        }

    const Matrix &S_e = problem.slip.S_e;
    const Matrix  S_F_p_inverse_T = multiply_transposed_second(S_e, G_A);
    const Matrix  F_e_S = multiply(F_e, S_e);
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int L = 0; L < 3; ++L)
        {
          const auto &G_L = F_p_n_inverse[L]; // dF G has the single row k = G_L
          Symmetric   dp;                     // dC_e^tr/dF_kL
          for (unsigned int m = 0; m < 6; ++m)
            {
              const unsigned int i = sym_i[m], j = sym_j[m];
              dp[m] = G_L[i] * F_e_trial[k][j] + F_e_trial[k][i] * G_L[j];
            }
          Matrix dE;
          for (unsigned int m = 0; m < 6; ++m)
            {
              double sum = 0.0;
              for (unsigned int a = 0; a < 6; ++a)
                sum += dx_dp[m][a] * dp[a];
              dE[sym_i[m]][sym_j[m]] = sum;
              dE[sym_j[m]][sym_i[m]] = sum;
            }
          // dX = -sum_r dDelta gamma^r m_0^r (x) n_0^r, dA = dA/dX : dX
          Matrix dX{};
          for (int r = 0; r < n_slip; ++r)
            {
              double d_gamma = 0.0;
              for (unsigned int a = 0; a < 6; ++a)
                d_gamma += ddelta_gamma_dp[r][a] * dp[a];
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  if (schmid[r][i][j] != 0.0)
                    dX[i][j] -= d_gamma * schmid[r][i][j];
            }
          Matrix dA{};
          for (unsigned int ab = 0; ab < 9; ++ab)
            {
              const double dX_ab = dX[ab / 3][ab % 3];
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  dA[i][j] += problem.dA_dX[ab][i][j] * dX_ab;
            }
          Matrix dF_e = multiply(F_e_trial, dA);
          for (unsigned int j = 0; j < 3; ++j)
            for (unsigned int m = 0; m < 3; ++m)
              dF_e[k][j] += G_L[m] * A[m][j];
          const auto dP_1 = multiply(dF_e, S_F_p_inverse_T);
          const auto dP_2 = multiply_transposed_second(multiply(F_e, elasticity.stress(dE)), G_A);
          const auto dP_3 = multiply_transposed_second(F_e_S, multiply(F_p_n_inverse, dA));
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int J = 0; J < 3; ++J)
              dP_dF[i][J][k][L] = dP_1[i][J] + dP_2[i][J] + dP_3[i][J];
        }
    return true;
  }
} // namespace indentsim::materials
