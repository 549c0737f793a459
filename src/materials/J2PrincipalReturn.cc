#include "materials/J2PrincipalReturn.h"
#include "materials/ImplicitLocalProblem.h"

#include <algorithm>
#include <cmath>

namespace indentsim::materials
{
  namespace
  {
    const double sqrt_3_2 = std::sqrt(1.5);
    using PrincipalNewton = ImplicitLocalProblem<4, 4>;
  } // namespace

  J2PrincipalReturn::J2PrincipalReturn(const IsotropicHardening &law, const double mu,
                                       const double                 gamma_p_n,
                                       const std::array<double, 3> &trial_log_strain,
                                       const double J, const bool cauchy)
    : law(law)
    , mu(mu)
    , gamma_p_n(gamma_p_n)
    , t(trial_log_strain)
    , J(J)
    , J_m(cauchy ? J : 1.0)
    , cauchy(cauchy)
    , smooth(!law.piecewise_linear())
  {
  }

  IsotropicHardening::FlowStress J2PrincipalReturn::flow_stress(const double delta_gamma) const
  {
    if (smooth)
      return law.evaluate(gamma_p_n + delta_gamma);
    return {line.stress + line.slope * delta_gamma, line.slope};
  }

  J2PrincipalReturn::DeviatoricPart J2PrincipalReturn::deviatoric_part(const Vector &x_trial)
  {
    // D_a = exp(2 mean e) (E_a - mean E), E_a = exp(2 (e_a - mean e)) - 1: written with expm1 so
    // that the small deviatoric part keeps full relative accuracy (it sets N).
    const double          mean_e = (x_trial[0] + x_trial[1] + x_trial[2]) / 3.0;
    std::array<double, 3> E;
    for (unsigned int a = 0; a < 3; ++a)
      E[a] = std::expm1(2.0 * (x_trial[a] - mean_e));
    const double   mean_E = (E[0] + E[1] + E[2]) / 3.0;
    const double   volumetric_factor = std::exp(2.0 * mean_e);
    DeviatoricPart part;
    for (unsigned int a = 0; a < 3; ++a)
      {
        part.D[a] = volumetric_factor * (E[a] - mean_E);
        part.b[a] = volumetric_factor * (1.0 + E[a]);
      }
    part.norm = std::sqrt(part.D[0] * part.D[0] + part.D[1] * part.D[1] + part.D[2] * part.D[2]);
    return part;
  }

  void J2PrincipalReturn::evaluate(const Vector &x_trial, Vector &R, Matrix *dR_dx) const
  {
    const auto [D, b, norm_D] = deviatoric_part(x_trial);
    const double delta_gamma = x_trial[3];
    const double c_N = sqrt_3_2 * delta_gamma / norm_D;
    for (unsigned int a = 0; a < 3; ++a)
      R[a] = x_trial[a] - t[a] + c_N * D[a];
    const IsotropicHardening::FlowStress sigma_y = flow_stress(delta_gamma);
    R[3] = sqrt_3_2 * norm_D / J_m - sigma_y.stress / mu;
    if (dR_dx == nullptr)
      return;

    Matrix &K = *dR_dx;
    for (unsigned int c = 0; c < 3; ++c)
      {
        const double two_b_c = 2.0 * b[c];
        const double D_c_over_norm_squared = D[c] / (norm_D * norm_D);
        for (unsigned int a = 0; a < 3; ++a)
          K[a][c] =
              (a == c ? 1.0 : 0.0) +
              c_N * two_b_c * ((a == c ? 1.0 : 0.0) - 1.0 / 3.0 - D[a] * D_c_over_norm_squared);
        K[3][c] = sqrt_3_2 * two_b_c * D[c] / (norm_D * J_m);
      }
    for (unsigned int a = 0; a < 3; ++a)
      K[a][3] = sqrt_3_2 * D[a] / norm_D;
    K[3][3] = -sigma_y.slope / mu;
  }

  double J2PrincipalReturn::flow_factor() const
  {
    return sqrt_3_2 * x[3] / deviatoric_part(x).norm;
  }

  // First initial guess: the radial return of the Hencky approximation dev tau ~ 2 mu dev eps_e,
  // for which sigma_HMH = sqrt(3/2) 2 mu |dev eps_e| / J^m drops by 3 mu Delta gamma / J^m along
  // N (exact for small elastic strains, so Newton starts in its quadratic range; the neo-Hookean
  // f^tr would overshoot for large trial strains, where exp(2 eps) >> 1 + 2 eps, and could land
  // on the spurious reversed-flow root). Fallback: Newton from the trial state itself
  // (Delta gamma = 0).
  J2PrincipalReturn::Outcome J2PrincipalReturn::solve_with_current_law()
  {
    const IsotropicHardening::FlowStress at_start = flow_stress(0.0);
    const double                         mean_t = (t[0] + t[1] + t[2]) / 3.0;
    std::array<double, 3>                dev_t;
    for (unsigned int a = 0; a < 3; ++a)
      dev_t[a] = t[a] - mean_t;
    const double norm_dev_t =
        std::sqrt(dev_t[0] * dev_t[0] + dev_t[1] * dev_t[1] + dev_t[2] * dev_t[2]);
    const auto set_hencky_guess = [&]() {
      const double delta_gamma_0 =
          std::max(sqrt_3_2 * 2.0 * mu * norm_dev_t / J_m - at_start.stress, 0.0) /
          (3.0 * mu / J_m + at_start.slope);
      for (unsigned int a = 0; a < 3; ++a)
        x[a] = t[a] - delta_gamma_0 * sqrt_3_2 * dev_t[a] / norm_dev_t;
      x[3] = delta_gamma_0;
    };
    const auto set_trial_guess = [&]() {
      for (unsigned int a = 0; a < 3; ++a)
        x[a] = t[a];
      x[3] = 0.0;
    };

    LocalNewtonSettings settings;
    // Round-off of the residual is ~1e-16 of the largest strain involved.
    double strain_scale = at_start.stress / mu;
    for (unsigned int a = 0; a < 3; ++a)
      strain_scale = std::max(strain_scale, std::abs(t[a]));
    settings.tolerance = 1e-14 * strain_scale;
    settings.stagnation_tolerance = 1e-11 * strain_scale;
    const auto evaluate_for_newton = [this](const Vector &x_trial, Vector &R, Matrix *dR_dx) {
      evaluate(x_trial, R, dR_dx);
    };
    Matrix jacobian;
    for (unsigned int attempt = 0; attempt < 2; ++attempt)
      {
        if (attempt == 0)
          set_hencky_guess();
        else
          set_trial_guess();
        const LocalNewtonResult newton =
            PrincipalNewton::solve_with_jacobian(evaluate_for_newton, x, jacobian, settings);
        // Delta gamma > 0 is guaranteed for f^tr > 0 (KKT); anything else is a spurious root.
        if (newton.converged && x[3] > 0.0)
          return Outcome::plastic;
        // A trial state on the yield surface to round-off returns Delta gamma = 0
        // (+- round-off): that is the elastic solution, not a failure.
        if (newton.converged && std::abs(x[3]) <= 1e-10 * strain_scale)
          return Outcome::on_yield_surface;
      }
    return Outcome::not_converged;
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
  J2PrincipalReturn::Outcome J2PrincipalReturn::solve_piecewise_linear()
  {
    const unsigned int first = law.segment(gamma_p_n), last = law.n_segments() - 1;
    const auto use_segment = [&](const unsigned int k) { line = law.segment_line(k, gamma_p_n); };
    if (first == last)
      {
        use_segment(first);
        return solve_with_current_law();
      }

    // Hencky estimate: sqrt(3/2) 2 mu |dev t| / J^m - 3 mu Delta gamma / J^m on line k.
    const double mean_t = (t[0] + t[1] + t[2]) / 3.0;
    double       norm_squared = 0.0;
    for (unsigned int a = 0; a < 3; ++a)
      norm_squared += (t[a] - mean_t) * (t[a] - mean_t);
    const double trial_stress = sqrt_3_2 * 2.0 * mu * std::sqrt(norm_squared) / J_m;
    unsigned int k = first;
    while (k < last)
      {
        const IsotropicHardening::FlowStress segment = law.segment_line(k, gamma_p_n);
        const double                         delta_gamma =
            (trial_stress - segment.stress) / (3.0 * mu / J_m + segment.slope);
        if (gamma_p_n + delta_gamma <= law.segment_end(k))
          break;
        ++k;
      }

    int previous_move = 0;
    for (unsigned int attempt = 0; attempt <= last - first + 1; ++attempt)
      {
        use_segment(k);
        const Outcome outcome = solve_with_current_law();
        if (outcome == Outcome::not_converged)
          return outcome;
        const double gamma_p = gamma_p_n + x[3];
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
    return Outcome::not_converged;
  }

  J2PrincipalReturn::Outcome J2PrincipalReturn::solve()
  {
    return smooth ? solve_with_current_law() : solve_piecewise_linear();
  }

  bool J2PrincipalReturn::sensitivity(std::array<Vector, 3> &de_dp) const
  {
    Vector R;
    Matrix dR_dx;
    evaluate(x, R, &dR_dx);
    // dx/dp = -(dR/dx)^-1 dR/dp with dR_a/dt_c = -delta_ac and dR_4/dJ the only nonzero
    // entries of dR/dp.
    const double dR4_dJ = cauchy ? -sqrt_3_2 * deviatoric_part(x).norm / (J * J) : 0.0;
    Matrix       dx_dp{};
    for (unsigned int a = 0; a < 3; ++a)
      dx_dp[a][a] = 1.0;
    dx_dp[3][3] = -dR4_dJ;
    if (!internal::solve_dense<4, 4>(dR_dx, dx_dp))
      return false;
    for (unsigned int a = 0; a < 3; ++a)
      de_dp[a] = dx_dp[a];
    return true;
  }
} // namespace indentsim::materials
