#include "materials/J2Plasticity.h"
#include "materials/J2PrincipalReturn.h"
#include "materials/TensorFunctions.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace indentsim::materials
{
  namespace
  {
    const double sqrt_3_2 = std::sqrt(1.5);

    using PrincipalMatrix = std::array<std::array<double, 3>, 3>;

    // The eigen-decomposition of the trial state, b_e^tr = sum_a lambda_a n_a (x) n_a: the
    // eigenvectors as the columns of Q (Q[i][a] = n_a,i), lambda_a - 1 (kept apart from the 1 so
    // that the small strains keep their relative accuracy) and t_a = 1/2 log lambda_a. deal.II's
    // Jacobi method: accurate to round-off of |b_e^tr - I| also for repeated eigenvalues (its
    // QL and hybrid methods are faster, the hybrid one is not accurate enough).
    struct TrialSpectrum
    {
      Tensor<2, 3>          Q;
      std::array<double, 3> lambda_minus_one;
      std::array<double, 3> log_strain;
    };

    TrialSpectrum trial_spectrum(const dealii::SymmetricTensor<2, 3> &b_e_trial)
    {
      dealii::SymmetricTensor<2, 3> b_minus_identity = b_e_trial;
      for (unsigned int k = 0; k < 3; ++k)
        b_minus_identity.access_raw_entry(k) -= 1.0;
      const auto eigensystem =
          dealii::eigenvectors(b_minus_identity, dealii::SymmetricTensorEigenvectorMethod::jacobi);
      TrialSpectrum spectrum;
      for (unsigned int a = 0; a < 3; ++a)
        {
          spectrum.lambda_minus_one[a] = eigensystem[a].first;
          spectrum.log_strain[a] = 0.5 * std::log1p(eigensystem[a].first);
          for (unsigned int i = 0; i < 3; ++i)
            spectrum.Q[i][a] = eigensystem[a].second[i];
        }
      return spectrum;
    }

    // (exp(2 delta) - 1) / delta and log(1 + x) / x, with their limits 2 and 1 at 0: quotients
    // of functions whose differences are computed without cancellation (expm1, log1p), so they
    // keep full accuracy however close the two eigenvalues behind delta and x are.
    double expm1_quotient(const double delta)
    {
      return delta == 0.0 ? 2.0 : std::expm1(2.0 * delta) / delta;
    }

    double log1p_quotient(const double x)
    {
      return x == 0.0 ? 1.0 : std::log1p(x) / x;
    }

    // The eigenvector-rotation part of the derivative of the isotropic function b_e(b_e^tr):
    // in the eigenbasis, d b_e,ab = theta_ab d b_e,ab^tr for a != b with the divided difference
    // theta_ab = (b_a - b_b) / (lambda_a - lambda_b) (Daleckii-Krein; Carlson & Hoger 1986,
    // Quart. Appl. Math. 44, 409; de Souza Neto, Peric & Owen 2008, appendix A). Differencing
    // b_a - b_b would lose all accuracy as the eigenvalues meet, which is the normal case here
    // (virgin material, the axis of symmetry, uniaxial states), so the quotient is factored into
    // parts that have none to lose: with
    // delta = e_a - e_b, the difference of the return equations R_a - R_b = 0 reads
    // delta + c_N (b_a - b_b) = t_a - t_b, and b_a - b_b = b_b (exp(2 delta) - 1), so
    //   theta_ab = b_b q_e / (1 + c_N b_b q_e) * q_l / (2 lambda_b),
    //   q_e = (exp(2 delta) - 1) / delta,   q_l = log(1 + x) / x,   x = (lambda_a - lambda_b) / lambda_b,
    // which is smooth and tends to the derivative limit as lambda_a -> lambda_b.
    PrincipalMatrix rotation_divided_differences(const TrialSpectrum         &spectrum,
                                                 const std::array<double, 3> &b,
                                                 const J2PrincipalReturn     &principal)
    {
      const double    c_N = principal.flow_factor();
      PrincipalMatrix theta{};
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int c = a + 1; c < 3; ++c)
          {
            const double delta = principal.elastic_log_strain(a) - principal.elastic_log_strain(c);
            const double lambda_c = 1.0 + spectrum.lambda_minus_one[c];
            const double x =
                (spectrum.lambda_minus_one[a] - spectrum.lambda_minus_one[c]) / lambda_c;
            const double b_q_e = b[c] * expm1_quotient(delta);
            theta[a][c] = theta[c][a] =
                b_q_e / (1.0 + c_N * b_q_e) * log1p_quotient(x) / (2.0 * lambda_c);
          }
      return theta;
    }

    // The principal values after the return: b_a = exp(2 e_a) and b_a - 1.
    struct PrincipalStretches
    {
      std::array<double, 3> b, b_minus_one;
    };

    PrincipalStretches principal_stretches(const J2PrincipalReturn &principal)
    {
      PrincipalStretches stretches;
      for (unsigned int a = 0; a < 3; ++a)
        {
          stretches.b_minus_one[a] = std::expm1(2.0 * principal.elastic_log_strain(a));
          stretches.b[a] = 1.0 + stretches.b_minus_one[a];
        }
      return stretches;
    }

    // Q diag(d) Q^T.
    dealii::SymmetricTensor<2, 3> spectral_sum(const Tensor<2, 3>          &Q,
                                               const std::array<double, 3> &d)
    {
      dealii::SymmetricTensor<2, 3> A;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          A[i][j] = Q[i][0] * d[0] * Q[j][0] + Q[i][1] * d[1] * Q[j][1] + Q[i][2] * d[2] * Q[j][2];
      return A;
    }

    // tau = mu (b_e - 1) + lambda/2 (J^2 - 1) 1 (eq. 3, with J^2 - 1 from J - 1) and
    // P = tau F^-T.
    void stress(const NeoHookean &elasticity, const Tensor<2, 3> &F_inverse,
                const double J_minus_one, const Tensor<2, 3> &Q,
                const PrincipalStretches &stretches, MaterialPointResponse &response)
    {
      const double pressure_term =
          0.5 * elasticity.lame_lambda() * J_minus_one * (J_minus_one + 2.0);
      const dealii::SymmetricTensor<2, 3> b_e_minus_identity =
          spectral_sum(Q, stretches.b_minus_one);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          response.tau[i][j] = elasticity.shear_modulus() * b_e_minus_identity[i][j] +
                               (i == j ? pressure_term : 0.0);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J_col = 0; J_col < 3; ++J_col)
          {
            double P_iJ = 0.0;
            for (unsigned int m = 0; m < 3; ++m)
              P_iJ += response.tau[i][m] * F_inverse[J_col][m];
            response.P[i][J_col] = P_iJ;
          }
    }

    // The consistent tangent dP/dF. b_e is an isotropic function of b_e^tr = F C_p,n^-1 F^T for
    // a given J (the return's second parameter). In the eigenbasis n_a of b_e^tr:
    //   d b_e,aa = sum_c (db_a/dlambda_c) d b_e,cc^tr + (db_a/dJ) dJ,
    //   d b_e,ab = theta_ab d b_e,ab^tr  (a != b),
    // with db_a/dlambda_c = 2 b_a (de_a/dt_c) (dt_c/dlambda_c) = b_a (de_a/dt_c) / lambda_c and
    // db_a/dJ = 2 b_a de_a/dJ from the principal return's sensitivity, and theta_ab from
    // rotation_divided_differences. For dF = e_k (x) e_L: d b_e^tr = e_k (x) G_L + G_L (x) e_k
    // with G = F C_p,n^-1, and dJ = J F^-1_Lk. Then
    //   dP_iJ/dF_kL = mu (d b_e F^-T)_iJ + lambda J dJ F^-1_Ji - P_iL F^-1_Jk
    // (tau = mu (b_e - 1) + lambda/2 (J^2 - 1) 1, d(F^-T) = -F^-T dF^T F^-T).
    void consistent_tangent(const NeoHookean &elasticity, const Tensor<2, 3> &F,
                            const Tensor<2, 3> &F_inverse, const double J,
                            const dealii::SymmetricTensor<2, 3> &C_p_inverse_n,
                            const TrialSpectrum &spectrum, const PrincipalStretches &stretches,
                            const std::array<J2PrincipalReturn::Vector, 3> &de_dp,
                            const PrincipalMatrix &theta, MaterialPointResponse &response)
    {
      const Tensor<2, 3> &Q = spectrum.Q;
      const double        mu = elasticity.shear_modulus();
      const double        lambda_J = elasticity.lame_lambda() * J;

      PrincipalMatrix       db_dlambda;
      std::array<double, 3> db_dJ;
      for (unsigned int a = 0; a < 3; ++a)
        {
          for (unsigned int c = 0; c < 3; ++c)
            db_dlambda[a][c] = stretches.b[a] * de_dp[a][c] / (1.0 + spectrum.lambda_minus_one[c]);
          db_dJ[a] = 2.0 * stretches.b[a] * de_dp[a][3];
        }

      // G' = Q^T F C_p,n^-1 and W = Q^T F^-T: the factors of d b_e^tr and of F^-T in the
      // eigenbasis.
      Tensor<2, 3> G_eigen, W;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int L = 0; L < 3; ++L)
          {
            double G_aL = 0.0, W_aL = 0.0;
            for (unsigned int p = 0; p < 3; ++p)
              {
                double G_pL = 0.0;
                for (unsigned int q = 0; q < 3; ++q)
                  G_pL += F[p][q] * C_p_inverse_n[q][L];
                G_aL += Q[p][a] * G_pL;
                W_aL += Q[p][a] * F_inverse[L][p];
              }
            G_eigen[a][L] = G_aL;
            W[a][L] = W_aL;
          }

      for (unsigned int k = 0; k < 3; ++k)
        for (unsigned int L = 0; L < 3; ++L)
          {
            const double dJ = J * F_inverse[L][k];
            // d b_e^tr and d b_e in the eigenbasis.
            Tensor<2, 3> db_trial, db;
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int c = 0; c < 3; ++c)
                db_trial[a][c] = Q[k][a] * G_eigen[c][L] + G_eigen[a][L] * Q[k][c];
            for (unsigned int a = 0; a < 3; ++a)
              {
                double db_aa = db_dJ[a] * dJ;
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    db_aa += db_dlambda[a][c] * db_trial[c][c];
                    if (c != a)
                      db[a][c] = theta[a][c] * db_trial[a][c];
                  }
                db[a][a] = db_aa;
              }
            // mu Q db W, then the pressure and the F^-T terms.
            const Tensor<2, 3> db_W = db * W;
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int J_col = 0; J_col < 3; ++J_col)
                {
                  double Q_db_W = 0.0;
                  for (unsigned int a = 0; a < 3; ++a)
                    Q_db_W += Q[i][a] * db_W[a][J_col];
                  response.dP_dF[i][J_col][k][L] = mu * Q_db_W +
                                                   lambda_J * dJ * F_inverse[J_col][i] -
                                                   response.P[i][L] * F_inverse[J_col][k];
                }
          }
    }
  } // namespace

  J2Plasticity::J2Plasticity(const double young_modulus, const double poisson_ratio,
                             const double yield_stress, const double hardening_modulus,
                             const YieldStressMeasure yield_stress_measure)
    : J2Plasticity(young_modulus, poisson_ratio,
                   IsotropicHardening::linear(yield_stress, hardening_modulus),
                   yield_stress_measure)
  {
  }

  J2Plasticity::J2Plasticity(const double young_modulus, const double poisson_ratio,
                             IsotropicHardening       hardening_law,
                             const YieldStressMeasure yield_stress_measure)
    : elasticity(young_modulus, poisson_ratio)
    , hardening(std::move(hardening_law))
    , measure(yield_stress_measure)
  {
  }

  void J2Plasticity::initial_state(std::span<double> state) const
  {
    Assert(state.size() == n_state, dealii::ExcDimensionMismatch(state.size(), n_state));
    for (unsigned int k = 0; k < 6; ++k)
      state[k] = (k < 3 ? 1.0 : 0.0);
    state[gamma_p_index] = 0.0;
  }

  dealii::SymmetricTensor<2, 3> J2Plasticity::plastic_metric_inverse(std::span<const double> state)
  {
    dealii::SymmetricTensor<2, 3> C_p_inverse;
    for (unsigned int k = 0; k < 6; ++k)
      C_p_inverse.access_raw_entry(k) = state[k];
    return C_p_inverse;
  }

  double J2Plasticity::yield_function(const Tensor<2, 3> &tau, const double J,
                                      const double gamma_p) const
  {
    const double mean = (tau[0][0] + tau[1][1] + tau[2][2]) / 3.0;
    double       norm_squared = 0.0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        norm_squared += std::pow(tau[i][j] - (i == j ? mean : 0.0), 2);
    const double sigma_HMH =
        sqrt_3_2 * std::sqrt(norm_squared) / (measure == YieldStressMeasure::cauchy ? J : 1.0);
    return sigma_HMH - flow_stress(gamma_p);
  }

  UpdateStatus J2Plasticity::update(const Tensor<2, 3> &F, std::span<const double> state_old,
                                    MaterialPointResponse &response, std::span<double> state_new,
                                    const bool compute_tangent) const
  {
    Assert(state_old.size() == n_state, dealii::ExcDimensionMismatch(state_old.size(), n_state));
    Assert(state_new.size() == n_state, dealii::ExcDimensionMismatch(state_new.size(), n_state));

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
    const auto failed_step = [&]() {
      std::copy(state_old.begin(), state_old.end(), state_new.begin());
      return UpdateStatus::local_newton_failed;
    };

    // Elastic predictor: tau(b_e^tr) directly, no logarithm needed (dev tau = mu dev b_e).
    const dealii::SymmetricTensor<2, 3> b_e_trial = push_forward_symmetric(F, C_p_inverse_n);
    const double norm_dev_b_e_trial = norm_symmetric(deviator_symmetric(b_e_trial));
    const double trial_yield_function =
        sqrt_3_2 * mu * norm_dev_b_e_trial / (cauchy ? J : 1.0) - yield_stress_n;
    if (trial_yield_function <= 0.0)
      return elastic_step();

    // Plastic corrector: the return mapping in the eigenbasis of b_e^tr (J2PrincipalReturn.h).
    const TrialSpectrum spectrum = trial_spectrum(b_e_trial);
    J2PrincipalReturn   principal(hardening, mu, gamma_p_n, spectrum.log_strain, J, cauchy);
    switch (principal.solve())
      {
      case J2PrincipalReturn::Outcome::on_yield_surface:
        return elastic_step();
      case J2PrincipalReturn::Outcome::not_converged:
        return failed_step();
      case J2PrincipalReturn::Outcome::plastic:
        break;
      }

    const PrincipalStretches stretches = principal_stretches(principal);
    const Tensor<2, 3>       F_inverse = inverse_3x3(F);
    stress(elasticity, F_inverse, J_minus_one, spectrum.Q, stretches, response);
    if (compute_tangent)
      {
        std::array<J2PrincipalReturn::Vector, 3> de_dp;
        if (!principal.sensitivity(de_dp))
          return failed_step();
        consistent_tangent(elasticity, F, F_inverse, J, C_p_inverse_n, spectrum, stretches, de_dp,
                           rotation_divided_differences(spectrum, stretches.b, principal),
                           response);
      }

    // Updated plastic metric C_p^-1 = F^-1 b_e F^-T (eq. 9 pulled back) and gamma_p.
    const dealii::SymmetricTensor<2, 3> C_p_inverse =
        push_forward_symmetric(F_inverse, spectral_sum(spectrum.Q, stretches.b));
    for (unsigned int k = 0; k < 6; ++k)
      state_new[k] = C_p_inverse.access_raw_entry(k);
    state_new[gamma_p_index] = gamma_p_n + principal.delta_gamma();
    return UpdateStatus::success;
  }
} // namespace indentsim::materials
