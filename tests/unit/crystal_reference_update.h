// The crystal-plasticity update of CrystalPlasticity solved the straightforward way: the full
// 19-unknown local Newton (E_e, Delta lambda / tau0, tau_c^r / tau0) with its Jacobian and the
// consistent tangent by forward AD (Sacado) through everything, the matrix exponential included.
// Slow but independent of the hand-derived Jacobian: the oracle against which the fast update
// must agree to round-off. Units: GPa.
#pragma once

#include "materials/CrystalPlasticity.h"
#include "materials/ImplicitLocalProblem.h"
#include "materials/NeoHookean.h"
#include "materials/TensorFunctions.h"

#include <Sacado.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

namespace indentsim::testing::reference
{
  using namespace indentsim::materials;
  using dealii::Tensor;

  namespace internal
  {
    template <typename Number>
    using Matrix = std::array<std::array<Number, 3>, 3>;

    // Unrolled symmetric storage (deal.II's order): 00, 11, 22, 01, 02, 12.
    constexpr unsigned int sym_i[6] = {0, 1, 2, 0, 0, 1};
    constexpr unsigned int sym_j[6] = {0, 1, 2, 1, 2, 2};

    // The scalar type of a product: the AD type if either factor is one (never a Sacado
    // expression-template type, which decltype(a * b) would give).
    template <typename NumberA, typename NumberB>
    struct ProductType
    {
      using type = NumberA;
    };
    template <typename NumberB>
    struct ProductType<double, NumberB>
    {
      using type = NumberB;
    };

    template <typename Number>
    Matrix<Number> identity_matrix()
    {
      Matrix<Number> I;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          I[i][j] = (i == j ? 1.0 : 0.0);
      return I;
    }

    template <typename NumberA, typename NumberB>
    auto multiply(const Matrix<NumberA> &A, const Matrix<NumberB> &B)
    {
      using Number = typename ProductType<NumberA, NumberB>::type;
      Matrix<Number> C;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            Number sum = A[i][0] * B[0][j];
            sum += A[i][1] * B[1][j];
            sum += A[i][2] * B[2][j];
            C[i][j] = sum;
          }
      return C;
    }

    // A^T B
    template <typename NumberA, typename NumberB>
    auto multiply_transposed_first(const Matrix<NumberA> &A, const Matrix<NumberB> &B)
    {
      using Number = typename ProductType<NumberA, NumberB>::type;
      Matrix<Number> C;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            Number sum = A[0][i] * B[0][j];
            sum += A[1][i] * B[1][j];
            sum += A[2][i] * B[2][j];
            C[i][j] = sum;
          }
      return C;
    }

    // A B^T
    template <typename NumberA, typename NumberB>
    auto multiply_transposed_second(const Matrix<NumberA> &A, const Matrix<NumberB> &B)
    {
      using Number = typename ProductType<NumberA, NumberB>::type;
      Matrix<Number> C;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            Number sum = A[i][0] * B[j][0];
            sum += A[i][1] * B[j][1];
            sum += A[i][2] * B[j][2];
            C[i][j] = sum;
          }
      return C;
    }

    Matrix<double> to_matrix(const Tensor<2, 3> &T)
    {
      Matrix<double> M;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          M[i][j] = T[i][j];
      return M;
    }

    // x^e for a non-negative integer e by binary powering (AD-safe at x = 0, unlike pow).
    template <typename Number>
    Number integer_power(Number x, unsigned int e)
    {
      Number result = 1.0;
      while (true)
        {
          if (e & 1u)
            result *= x;
          e >>= 1;
          if (e == 0)
            return result;
          x *= x;
        }
    }

    template <typename Number>
    Number real_power(const Number &x, const double e)
    {
      using std::pow;
      if (e >= 0.0 && e <= 256.0 && e == std::floor(e))
        return integer_power(x, static_cast<unsigned int>(e));
      return pow(x, e);
    }

    // exp(X) of a general 3x3 matrix by scaling and squaring of its Taylor series: X is scaled
    // by 2^-s until its Frobenius norm is <= 1/4, the series is summed until the next term is
    // below 1e-17 (one more term than the value needs, so that derivatives carried by AD
    // numbers are as accurate as the value), then squared s times.
    template <typename Number>
    Matrix<Number> exp_matrix(const Matrix<Number> &X)
    {
      double norm_squared = 0.0;
      for (const auto &row : X)
        for (const auto &a : row)
          norm_squared += scalar_value(a) * scalar_value(a);
      double       norm = std::sqrt(norm_squared);
      unsigned int n_squarings = 0;
      while (norm > 0.25 && n_squarings < 60)
        {
          norm *= 0.5;
          ++n_squarings;
        }
      const double   scale = std::ldexp(1.0, -static_cast<int>(n_squarings));
      Matrix<Number> Y = X;
      for (auto &row : Y)
        for (auto &a : row)
          a *= scale;

      Matrix<Number> result = identity_matrix<Number>();
      Matrix<Number> term = Y;
      double         bound = norm; // norm^k / k!, bounds |term_k|
      for (unsigned int k = 1; k <= 30; ++k)
        {
          if (k > 1)
            {
              term = multiply(term, Y);
              for (auto &row : term)
                for (auto &a : row)
                  a /= double(k);
              bound *= norm / k;
            }
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              result[i][j] += term[i][j];
          if (bound * norm / (k + 1) < 1e-17 && k >= 2)
            break;
          if (norm == 0.0)
            break;
        }
      for (unsigned int s = 0; s < n_squarings; ++s)
        result = multiply(result, result);
      return result;
    }

    // Everything that follows from the elastic strain, the critical shears and the multiplier:
    // second Piola-Kirchhoff stress in the lattice frame S_e = L^e : E_e (eq. 11), resolved
    // shears from the Mandel stress M_e = C_e S_e (eq. 10), Phi (eq. 14) and the slip
    // increments of the flow rule (eq. 15, directions normalised by Phi, see the header).
    struct SlipLawData
    {
      double                                      C11, C12, C44;
      double                                      n;
      double                                      tau0;
      const std::array<std::array<double, 3>, 3> *schmid; // n_slip Schmid tensors
    };

    template <int n_slip, typename Number>
    struct SlipResponse
    {
      Matrix<Number>             S_e;
      std::array<Number, n_slip> ratio; // tau^r / tau_c^r
      Number                     Phi;
      std::array<Number, n_slip> delta_gamma; // Delta gamma^r
    };

    template <int n_slip, typename Number>
    void slip_response(const SlipLawData            &law,
                       const Number                 *E_e,           // 6, unrolled
                       const Number                 *tau_c_scaled,  // n_slip, tau_c / tau0
                       const Number                 &lambda_scaled, // Delta lambda / tau0
                       SlipResponse<n_slip, Number> &out)
    {
      Matrix<Number> E;
      for (unsigned int k = 0; k < 6; ++k)
        {
          E[sym_i[k]][sym_j[k]] = E_e[k];
          E[sym_j[k]][sym_i[k]] = E_e[k];
        }
      // Cubic St-Venant-Kirchhoff in the lattice frame (Voigt: C11, C12, C44; engineering
      // shear strains 2 E_ij).
      const Number trace_E = E[0][0] + E[1][1] + E[2][2];
      for (unsigned int i = 0; i < 3; ++i)
        {
          out.S_e[i][i] = (law.C11 - law.C12) * E[i][i] + law.C12 * trace_E;
          for (unsigned int j = i + 1; j < 3; ++j)
            {
              out.S_e[i][j] = 2.0 * law.C44 * E[i][j];
              out.S_e[j][i] = out.S_e[i][j];
            }
        }
      Matrix<Number> C_e = E;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          C_e[i][j] = 2.0 * E[i][j] + (i == j ? 1.0 : 0.0);
      const Matrix<Number> M_e = multiply(C_e, out.S_e);

      unsigned int largest = 0;
      for (int r = 0; r < n_slip; ++r)
        {
          Number tau = M_e[0][0] * law.schmid[r][0][0];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              if (i + j > 0)
                tau += M_e[i][j] * law.schmid[r][i][j];
          out.ratio[r] = tau / (law.tau0 * tau_c_scaled[r]);
          if (std::abs(scalar_value(out.ratio[r])) > std::abs(scalar_value(out.ratio[largest])))
            largest = r;
        }

      // Phi = |rho_max| (sum (rho_r / rho_max)^2n)^(1/2n), safe from overflow.
      const double largest_value = scalar_value(out.ratio[largest]);
      if (largest_value == 0.0)
        {
          out.Phi = 0.0;
          for (int r = 0; r < n_slip; ++r)
            out.delta_gamma[r] = 0.0;
          return;
        }
      const Number abs_largest =
          largest_value > 0 ? out.ratio[largest] : Number(-out.ratio[largest]);
      Number sum = 0.0;
      for (int r = 0; r < n_slip; ++r)
        {
          const Number relative = out.ratio[r] / abs_largest;
          sum += real_power(Number(relative * relative), law.n);
        }
      using std::pow;
      out.Phi = abs_largest * pow(sum, 1.0 / (2.0 * law.n));
      for (int r = 0; r < n_slip; ++r)
        {
          const Number direction = out.ratio[r] / out.Phi;
          out.delta_gamma[r] = lambda_scaled / tau_c_scaled[r] * direction *
                               real_power(Number(direction * direction), law.n - 1.0);
        }
    }

    // Hbar = (tau_c(Gamma_n + dGamma) - tau_c(Gamma_n)) / dGamma for the extended Voce law:
    //   Hbar = theta1 (1 - e_n e^-x) + (tau1 + theta1 Gamma_n) e_n k phi(x),
    //   k = theta0 / tau1, e_n = exp(-k Gamma_n), x = k dGamma, phi(x) = (1 - e^-x) / x;
    // Hbar -> h(Gamma_n) as dGamma -> 0 (phi by its series for small x).
    template <typename Number>
    Number voce_secant_modulus(const ExtendedVoceHardening &law, const double Gamma_n,
                               const Number &delta_Gamma)
    {
      using std::exp;
      if (law.theta0 == 0.0 || law.tau1 == 0.0)
        return Number(0.0);
      const double k = law.theta0 / law.tau1;
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
      return law.theta1 * (1.0 - e_n * exp(-x)) + (law.tau1 + law.theta1 * Gamma_n) * e_n * k * phi;
    }

    // The local problem of one increment: unknowns E_e (6), Delta lambda / tau0, tau_c^r / tau0;
    // parameters C_e^tr (6, unrolled). All residuals in strain units (stresses divided by C44).
    template <int n_slip>
    struct CrystalResidual
    {
      static constexpr int n_unknowns = 7 + n_slip;
      static constexpr int n_parameters = 6;
      static constexpr int lambda_index = 6;
      static constexpr int tau_c_index = 7;

      SlipLawData                  law;
      const ExtendedVoceHardening *hardening;
      double                       Gamma_n;
      const double                *tau_c_n; // n_slip [GPa]

      template <typename Number>
      void operator()(const std::array<Number, n_unknowns>   &x,
                      const std::array<Number, n_parameters> &p,
                      std::array<Number, n_unknowns>         &R) const
      {
        SlipResponse<n_slip, Number> slip;
        slip_response<n_slip, Number>(law, &x[0], &x[tau_c_index], x[lambda_index], slip);

        // A = exp(-Delta L_p), Delta L_p = sum_r Delta gamma^r m_0^r (x) n_0^r (eqs 12-13).
        Matrix<Number> minus_delta_L_p;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              Number sum = 0.0;
              for (int r = 0; r < n_slip; ++r)
                if (law.schmid[r][i][j] != 0.0)
                  sum -= slip.delta_gamma[r] * law.schmid[r][i][j];
              minus_delta_L_p[i][j] = sum;
            }
        const Matrix<Number> A = exp_matrix(minus_delta_L_p);
        Matrix<Number>       C_e_trial;
        for (unsigned int k = 0; k < 6; ++k)
          {
            C_e_trial[sym_i[k]][sym_j[k]] = p[k];
            C_e_trial[sym_j[k]][sym_i[k]] = p[k];
          }
        const auto C_e = multiply_transposed_first(A, multiply(C_e_trial, A));
        for (unsigned int k = 0; k < 6; ++k)
          R[k] = x[k] - 0.5 * (C_e[sym_i[k]][sym_j[k]] - (k < 3 ? 1.0 : 0.0));

        R[lambda_index] = (slip.Phi - 1.0) * (law.tau0 / law.C44);

        Number                     delta_Gamma = 0.0;
        std::array<Number, n_slip> abs_delta_gamma;
        for (int r = 0; r < n_slip; ++r)
          {
            abs_delta_gamma[r] = scalar_value(slip.delta_gamma[r]) >= 0
                                     ? slip.delta_gamma[r]
                                     : Number(-slip.delta_gamma[r]);
            delta_Gamma += abs_delta_gamma[r];
          }
        const Number H_bar = voce_secant_modulus(*hardening, Gamma_n, delta_Gamma);
        const double q = hardening->q;
        for (int r = 0; r < n_slip; ++r)
          R[tau_c_index + r] = (law.tau0 * x[tau_c_index + r] - tau_c_n[r] -
                                H_bar * (q * delta_Gamma + (1.0 - q) * abs_delta_gamma[r])) /
                               law.C44;
      }
    };

    using ADNumberF = Sacado::Fad::SFad<double, 9>;

    // P = F_e S_e F_p^-T and its AD derivatives, with F_e = F F_p^-1.
    template <typename Number, typename NumberP>
    void write_response(const Matrix<Number> &F_e, const Matrix<Number> &S_e,
                        const Matrix<NumberP> &F_p_inverse, const Tensor<2, 3> &F,
                        MaterialPointResponse &response, const bool with_tangent)
    {
      const auto P = multiply_transposed_second(multiply(F_e, S_e), F_p_inverse);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J = 0; J < 3; ++J)
          {
            response.P[i][J] = scalar_value(P[i][J]);
            if constexpr (!std::is_same_v<Number, double>)
              if (with_tangent)
                for (unsigned int k = 0; k < 3; ++k)
                  for (unsigned int L = 0; L < 3; ++L)
                    response.dP_dF[i][J][k][L] = P[i][J].dx(3 * k + L);
          }
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            double sum = 0.0;
            for (unsigned int m = 0; m < 3; ++m)
              sum += response.P[i][m] * F[j][m];
            response.tau[i][j] = sum;
          }
    }
  } // namespace internal

  using namespace internal;

  // CrystalPlasticity::update by forward AD, the model's data read through its accessors.
  inline UpdateStatus update(const CrystalPlasticity &model, const Tensor<2, 3> &F,
                             std::span<const double> state_old, MaterialPointResponse &response,
                             std::span<double> state_new, const bool compute_tangent)
  {
    constexpr int n_slip = 12;
    // The reference covers the paper's model: cubic elasticity, one hardening law.
    const LatticeElasticity     &elastic = model.elastic_constants();
    const ExtendedVoceHardening &hardening = model.hardening_law().laws.front();
    const struct
    {
      double C11, C12, C44;
    } elasticity{elastic.normal[0][0], elastic.normal[0][1], elastic.shear[2]};
    const double                n = model.yield_exponent();
    std::vector<Matrix<double>> schmid;
    for (unsigned int r = 0; r < n_slip; ++r)
      schmid.push_back(to_matrix(model.slip_systems().schmid_tensor(r)));
    const auto plastic_deformation = [](std::span<const double> state) {
      return CrystalPlasticity::plastic_deformation(state);
    };
    using Residual = CrystalResidual<n_slip>;
    using LocalProblem = ImplicitLocalProblem<Residual::n_unknowns, Residual::n_parameters>;

    double J_minus_one = 0.0;
    if (!admissible_deformation(F, J_minus_one))
      return UpdateStatus::invalid_deformation;

    const Matrix<double> F_matrix = to_matrix(F);
    const Matrix<double> F_p_n_inverse = to_matrix(inverse_3x3(plastic_deformation(state_old)));
    const double        *tau_c_n = &state_old[9];
    const double         Gamma_n = state_old[9 + n_slip];
    const SlipLawData    law{elasticity.C11, elasticity.C12, elasticity.C44, n,
                          hardening.tau0, schmid.data()};

    // Elastic trial: C_e^tr = F_p,n^-T C F_p,n^-1 and E_e^tr.
    const Matrix<double>              F_e_trial = multiply(F_matrix, F_p_n_inverse);
    const auto                        C_e_trial = multiply_transposed_first(F_e_trial, F_e_trial);
    typename LocalProblem::Parameters parameters;
    std::array<double, 6>             E_trial;
    for (unsigned int k = 0; k < 6; ++k)
      {
        parameters[k] = C_e_trial[sym_i[k]][sym_j[k]];
        E_trial[k] = 0.5 * (parameters[k] - (k < 3 ? 1.0 : 0.0));
      }
    std::array<double, n_slip> tau_c_n_scaled;
    for (int r = 0; r < n_slip; ++r)
      tau_c_n_scaled[r] = tau_c_n[r] / hardening.tau0;

    SlipResponse<n_slip, double> trial;
    slip_response<n_slip, double>(law, E_trial.data(), tau_c_n_scaled.data(), 0.0, trial);
    if (!std::isfinite(trial.Phi))
      return UpdateStatus::invalid_deformation;

    const auto elastic_step = [&]() {
      if (compute_tangent)
        {
          Matrix<ADNumberF> F_ad;
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int L = 0; L < 3; ++L)
              F_ad[k][L] = ADNumberF(9, 3 * k + L, F[k][L]);
          const auto               F_e = multiply(F_ad, F_p_n_inverse);
          const auto               C_e = multiply_transposed_first(F_e, F_e);
          std::array<ADNumberF, 6> E;
          for (unsigned int k = 0; k < 6; ++k)
            E[k] = 0.5 * (C_e[sym_i[k]][sym_j[k]] - (k < 3 ? 1.0 : 0.0));
          // E's values from the trial (same numbers; C - I formed once).
          std::array<ADNumberF, n_slip> unit;
          for (auto &u : unit)
            u = 1.0;
          SlipResponse<n_slip, ADNumberF> slip;
          slip_response<n_slip, ADNumberF>(law, E.data(), unit.data(), ADNumberF(0.0), slip);
          write_response(F_e, slip.S_e, F_p_n_inverse, F, response, true);
        }
      else
        write_response(F_e_trial, trial.S_e, F_p_n_inverse, F, response, false);
      std::copy(state_old.begin(), state_old.end(), state_new.begin());
      return UpdateStatus::success;
    };

    // KKT (eq. 8): no plastic flow while Phi <= 1.
    if (trial.Phi <= 1.0)
      return elastic_step();

    // Plastic corrector: the local Newton from the elastic trial.
    const Residual                  residual{law, &hardening, Gamma_n, tau_c_n};
    typename LocalProblem::Unknowns unknowns;
    double                          strain_scale = hardening.tau0 / elasticity.C44;
    for (unsigned int k = 0; k < 6; ++k)
      strain_scale = std::max(strain_scale, std::abs(E_trial[k]));
    LocalNewtonSettings settings;
    settings.max_iterations = 50;
    settings.max_line_search_steps = 20;
    // Forming A^T C_e^tr A near the identity leaves round-off ~1e-16 in E_e whatever its size.
    settings.tolerance = std::max(1e-13 * strain_scale, 2e-15);
    settings.stagnation_tolerance = std::max(1e-10 * strain_scale, 1e-13);

    for (unsigned int k = 0; k < 6; ++k)
      unknowns[k] = E_trial[k];
    unknowns[Residual::lambda_index] = 0.0;
    for (int r = 0; r < n_slip; ++r)
      unknowns[Residual::tau_c_index + r] = tau_c_n_scaled[r];
    const LocalNewtonResult newton = LocalProblem::solve(residual, parameters, unknowns, settings);
    const double            lambda_scaled = unknowns[Residual::lambda_index];
    if (!newton.converged || !(lambda_scaled >= 0.0))
      {
        // A trial state on the yield surface to round-off returns Delta lambda = 0 (+- round-off).
        if (newton.converged && std::abs(lambda_scaled) <= 1e-12 * strain_scale)
          return elastic_step();
        std::copy(state_old.begin(), state_old.end(), state_new.begin());
        return UpdateStatus::local_newton_failed;
      }

    // Converged slip increments and the new plastic state.
    SlipResponse<n_slip, double> slip;
    slip_response<n_slip, double>(law, &unknowns[0], &unknowns[Residual::tau_c_index],
                                  unknowns[Residual::lambda_index], slip);
    Matrix<double> delta_L_p{};
    double         delta_Gamma = 0.0;
    for (int r = 0; r < n_slip; ++r)
      {
        delta_Gamma += std::abs(slip.delta_gamma[r]);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            delta_L_p[i][j] += slip.delta_gamma[r] * schmid[r][i][j];
      }
    Matrix<double> minus_delta_L_p = delta_L_p;
    for (auto &row : minus_delta_L_p)
      for (auto &a : row)
        a = -a;
    const Matrix<double> F_p_new =
        multiply(exp_matrix(delta_L_p), to_matrix(plastic_deformation(state_old)));
    const Matrix<double> A = exp_matrix(minus_delta_L_p);
    const Matrix<double> F_p_new_inverse = multiply(F_p_n_inverse, A);

    if (compute_tangent)
      {
        typename LocalProblem::Sensitivity dx_dp;
        if (!LocalProblem::sensitivity(residual, parameters, unknowns, dx_dp))
          {
            std::copy(state_old.begin(), state_old.end(), state_new.begin());
            return UpdateStatus::local_newton_failed;
          }
        Matrix<ADNumberF> F_ad;
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            F_ad[k][L] = ADNumberF(9, 3 * k + L, F[k][L]);
        const auto F_e_trial_ad = multiply(F_ad, F_p_n_inverse);
        const auto C_e_trial_ad = multiply_transposed_first(F_e_trial_ad, F_e_trial_ad);
        std::array<ADNumberF, 6> parameters_ad;
        for (unsigned int k = 0; k < 6; ++k)
          parameters_ad[k] = C_e_trial_ad[sym_i[k]][sym_j[k]];
        const auto x_ad = LocalProblem::linearized_solution(unknowns, dx_dp, parameters_ad);
        SlipResponse<n_slip, ADNumberF> slip_ad;
        slip_response<n_slip, ADNumberF>(law, &x_ad[0], &x_ad[Residual::tau_c_index],
                                         x_ad[Residual::lambda_index], slip_ad);
        Matrix<ADNumberF> minus_delta_L_p_ad;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              ADNumberF sum = 0.0;
              for (int r = 0; r < n_slip; ++r)
                if (schmid[r][i][j] != 0.0)
                  sum -= slip_ad.delta_gamma[r] * schmid[r][i][j];
              minus_delta_L_p_ad[i][j] = sum;
            }
        const auto A_ad = exp_matrix(minus_delta_L_p_ad);
        const auto F_p_inverse_ad = multiply(F_p_n_inverse, A_ad);
        const auto F_e_ad = multiply(F_e_trial_ad, A_ad);
        write_response(F_e_ad, slip_ad.S_e, F_p_inverse_ad, F, response, true);
      }
    else
      write_response(multiply(F_e_trial, A), slip.S_e, F_p_new_inverse, F, response, false);

    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        state_new[3 * i + j] = F_p_new[i][j];
    for (int r = 0; r < n_slip; ++r)
      state_new[9 + r] = hardening.tau0 * unknowns[Residual::tau_c_index + r];
    state_new[9 + n_slip] = Gamma_n + delta_Gamma;
    for (const double v : state_new)
      if (!std::isfinite(v))
        {
          std::copy(state_old.begin(), state_old.end(), state_new.begin());
          return UpdateStatus::local_newton_failed;
        }
    return UpdateStatus::success;
  }
} // namespace indentsim::testing::reference
