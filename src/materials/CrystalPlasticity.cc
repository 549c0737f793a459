#include <materials/CrystalPlasticity.h>
#include <materials/ImplicitLocalProblem.h>
#include <materials/NeoHookean.h>
#include <materials/TensorFunctions.h>

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace indentsim::materials
{
  namespace
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
    // Scaling and squaring: Y = 2^-s X with |Y| <= 1/4 (Frobenius), so that the Taylor series
    // of exp(Y) converges in a few terms; exp(X) = exp(Y)^(2^s).
    Matrix<double> scaled_for_series(const Matrix<double> &X,
                                     double               &norm,
                                     unsigned int         &n_squarings)
    {
      double norm_squared = 0.0;
      for (const auto &row : X)
        for (const double a : row)
          norm_squared += a * a;
      norm = std::sqrt(norm_squared);
      n_squarings = 0;
      while (norm > 0.25 && n_squarings < 60)
        {
          norm *= 0.5;
          ++n_squarings;
        }
      const double   scale = std::ldexp(1.0, -static_cast<int>(n_squarings));
      Matrix<double> Y = X;
      for (auto &row : Y)
        for (auto &a : row)
          a *= scale;
      return Y;
    }

    constexpr unsigned int max_series_terms = 30;
    using SeriesTerms = std::array<Matrix<double>, max_series_terms + 1>;

    // The Taylor terms T_k = Y^k / k! of exp(Y) (|Y| = norm <= 1/4) until the next term is below
    // 1e-17, their sum in `sum`; returns the index K of the last term.
    unsigned int exp_series_terms(const Matrix<double> &Y,
                                  const double          norm,
                                  SeriesTerms          &terms,
                                  Matrix<double>       &sum)
    {
      terms[0] = identity_matrix<double>();
      sum = identity_matrix<double>();
      terms[1] = Y;
      unsigned int n_terms = 1;
      double       bound = norm; // norm^k / k!, bounds |T_k|
      for (unsigned int k = 1; k <= max_series_terms; ++k)
        {
          if (k > 1)
            {
              terms[k] = multiply(terms[k - 1], Y);
              for (auto &row : terms[k])
                for (auto &a : row)
                  a /= double(k);
              bound *= norm / k;
            }
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              sum[i][j] += terms[k][i][j];
          n_terms = k;
          if (bound * norm / (k + 1) < 1e-17 && k >= 2)
            break;
          if (norm == 0.0)
            break;
        }
      return n_terms;
    }

    Matrix<double> exp_matrix(const Matrix<double> &X)
    {
      double               norm = 0;
      unsigned int         n_squarings = 0;
      const Matrix<double> Y = scaled_for_series(X, norm, n_squarings);
      SeriesTerms          terms;
      Matrix<double>       result;
      exp_series_terms(Y, norm, terms, result);
      for (unsigned int s = 0; s < n_squarings; ++s)
        result = multiply(result, result);
      return result;
    }

    // exp(X) exactly as exp_matrix computes it (same scaling, terms and squarings, so the same
    // numbers) and its derivative dA/dX_ab. With the scaled Y = 2^-s X and the terms
    // T_j = Y^j / j! of the series A_Y = sum_{k<=K} T_k, the derivative of the truncated series is
    //   dA_Y/dY_ab = sum_{k=1..K} 1/k! sum_{j+m=k-1} Y^j e_a e_b^T Y^m
    //             = sum_j T_j e_a e_b^T G_j,   G_j = sum_{m<=K-1-j} j! m!/(j+m+1)! T_m,
    // then each squaring A <- A A carries dA <- dA A + A dA: the derivatives that forward AD
    // through exp_matrix gives, without carrying 9 derivatives through every product.
    void exp_matrix_and_derivative(const Matrix<double>          &X,
                                   Matrix<double>                &A,
                                   std::array<Matrix<double>, 9> &dA_dX)
    {
      double               norm = 0;
      unsigned int         n_squarings = 0;
      const Matrix<double> Y = scaled_for_series(X, norm, n_squarings);
      const double         scale = std::ldexp(1.0, -static_cast<int>(n_squarings)); // dY/dX

      SeriesTerms        terms; // T_0 .. T_K
      const unsigned int n_terms = exp_series_terms(Y, norm, terms, A);

      // beta(j, m) = j! m! / (j + m + 1)!
      std::array<Matrix<double>, max_series_terms> G; // G_j, j = 0 .. K-1
      for (unsigned int j = 0; j < n_terms; ++j)
        {
          G[j] = Matrix<double>{};
          double beta = 1.0 / (j + 1); // m = 0
          for (unsigned int m = 0; j + m + 1 <= n_terms; ++m)
            {
              for (unsigned int b = 0; b < 3; ++b)
                for (unsigned int l = 0; l < 3; ++l)
                  G[j][b][l] += beta * terms[m][b][l];
              beta *= double(m + 1) / double(j + m + 2);
            }
        }
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          {
            Matrix<double> &dA = dA_dX[3 * a + b];
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int l = 0; l < 3; ++l)
                {
                  double sum = 0.0;
                  for (unsigned int j = 0; j < n_terms; ++j)
                    sum += terms[j][i][a] * G[j][b][l];
                  dA[i][l] = sum * scale;
                }
          }
      for (unsigned int s = 0; s < n_squarings; ++s)
        {
          for (auto &dA : dA_dX)
            {
              const Matrix<double> left = multiply(dA, A), right = multiply(A, dA);
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  dA[i][j] = left[i][j] + right[i][j];
            }
          A = multiply(A, A);
        }
    }

    // Everything that follows from the elastic strain, the critical shears and the multiplier:
    // second Piola-Kirchhoff stress in the lattice frame S_e = L^e : E_e (eq. 11), resolved
    // shears from the Mandel stress M_e = C_e S_e (eq. 10), Phi (eq. 14) and the slip
    // increments of the flow rule (eq. 15, directions normalised by Phi, see the header).
    struct SlipLawData
    {
      double C11, C12, C44;
      double n;
      double tau0;
      const std::array<std::array<double, 3>, 3> *schmid; // n_slip Schmid tensors
    };

    template <int n_slip, typename Number>
    struct SlipResponse
    {
      Matrix<Number>               S_e;
      std::array<Number, n_slip>   ratio;       // tau^r / tau_c^r
      Number                       Phi;
      std::array<Number, n_slip>   delta_gamma; // Delta gamma^r
      std::array<Number, n_slip>   flow_power;  // (tau^r / (Phi tau_c^r))^(2n-2)
    };

    template <int n_slip, typename Number>
    void slip_response(const SlipLawData     &law,
                       const Number          *E_e,          // 6, unrolled
                       const Number          *tau_c_scaled, // n_slip, tau_c / tau0
                       const Number          &lambda_scaled, // Delta lambda / tau0
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
            out.delta_gamma[r] = out.flow_power[r] = 0.0;
          return;
        }
      const Number abs_largest = largest_value > 0 ? out.ratio[largest] : Number(-out.ratio[largest]);
      // (rho_r / Phi)^(2n-2) = (rho_r / rho_max)^(2n-2) sum^(-(n-1)/n): one power per system
      // serves Phi and the flow direction.
      Number sum = 0.0;
      for (int r = 0; r < n_slip; ++r)
        {
          const Number relative = out.ratio[r] / abs_largest;
          const Number relative_squared = relative * relative;
          out.flow_power[r] = real_power(relative_squared, law.n - 1.0);
          sum += relative_squared * out.flow_power[r];
        }
      using std::pow;
      out.Phi = abs_largest * pow(sum, 1.0 / (2.0 * law.n));
      const Number power_scale = pow(sum, (1.0 - law.n) / law.n);
      for (int r = 0; r < n_slip; ++r)
        {
          out.flow_power[r] *= power_scale;
          out.delta_gamma[r] = lambda_scaled / tau_c_scaled[r] * (out.ratio[r] / out.Phi) * out.flow_power[r];
        }
    }

    // Hbar = (tau_c(Gamma_n + dGamma) - tau_c(Gamma_n)) / dGamma for the extended Voce law:
    //   Hbar = theta1 (1 - e_n e^-x) + (tau1 + theta1 Gamma_n) e_n k phi(x),
    //   k = theta0 / tau1, e_n = exp(-k Gamma_n), x = k dGamma, phi(x) = (1 - e^-x) / x;
    // Hbar -> h(Gamma_n) as dGamma -> 0 (phi by its series for small x).
    template <typename Number>
    Number voce_secant_modulus(const ExtendedVoceHardening &law,
                               const double                 Gamma_n,
                               const Number                &delta_Gamma)
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

    // S = L^e : E (eq. 11), cubic St-Venant-Kirchhoff in the lattice frame.
    Matrix<double> elastic_stress(const SlipLawData &law, const Matrix<double> &E)
    {
      Matrix<double> S;
      const double   trace_E = E[0][0] + E[1][1] + E[2][2];
      for (unsigned int i = 0; i < 3; ++i)
        {
          S[i][i] = (law.C11 - law.C12) * E[i][i] + law.C12 * trace_E;
          for (unsigned int j = i + 1; j < 3; ++j)
            {
              S[i][j] = 2.0 * law.C44 * E[i][j];
              S[j][i] = S[i][j];
            }
        }
      return S;
    }

    // The starting point of the local Newton from a hint state (F_p, tau_c, Gamma) of the same
    // increment, written into x (unknowns as CrystalLocalProblem: E_e (6), Delta lambda / tau0,
    // tau_c / tau0): E_e of the hint's F_p at the new F, C_e = (F F_p^-1)^T (F F_p^-1), its
    // tau_c, and Delta lambda from its Delta Gamma = Delta lambda sum_r |Delta gamma^r(lambda=1)|.
    // False when the hint is not plastic relative to state_old (Gamma_hint <= Gamma_n, e.g.
    // state_new == state_old at the start of an increment) or not usable (not finite, F_p far
    // from isochoric, tau_c <= 0).
    template <int n_slip>
    bool warm_start_guess(const SlipLawData              &law,
                          const Matrix<double>           &F,
                          std::span<const double>         state_old,
                          std::span<const double>         hint,
                          std::array<double, 7 + n_slip> &x)
    {
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
      const Matrix<double> F_e = multiply(F, to_matrix(inverse_3x3(F_p_hint)));
      const auto           C_e = multiply_transposed_first(F_e, F_e);
      for (unsigned int k = 0; k < 6; ++k)
        x[k] = 0.5 * (C_e[sym_i[k]][sym_j[k]] - (k < 3 ? 1.0 : 0.0));
      for (int r = 0; r < n_slip; ++r)
        {
          x[7 + r] = hint[9 + r] / law.tau0;
          if (!(x[7 + r] > 0.0) || !std::isfinite(x[7 + r]))
            return false;
        }
      SlipResponse<n_slip, double> unit;
      slip_response<n_slip, double>(law, x.data(), &x[7], 1.0, unit);
      double unit_Gamma = 0.0;
      for (int r = 0; r < n_slip; ++r)
        unit_Gamma += std::abs(unit.delta_gamma[r]);
      if (!(unit_Gamma > 0.0) || !std::isfinite(unit_Gamma))
        return false;
      x[6] = delta_Gamma / unit_Gamma;
      return true;
    }

    // A trial state is certainly elastic when Phi <= n_slip^(1/2n) max_r |rho_r| (eq. 14) is
    // below 1: most points of an indentation are, and the powers of Phi are then not needed.
    // S_e as slip_response computes it.
    template <int n_slip>
    bool certainly_elastic(const SlipLawData           &law,
                           const std::array<double, 6> &E_e,
                           const double                *tau_c_scaled,
                           const double                 bound_factor,
                           Matrix<double>              &S_e)
    {
      Matrix<double> E, C_e;
      for (unsigned int k = 0; k < 6; ++k)
        {
          E[sym_i[k]][sym_j[k]] = E_e[k];
          E[sym_j[k]][sym_i[k]] = E_e[k];
        }
      S_e = elastic_stress(law, E);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          C_e[i][j] = 2.0 * E[i][j] + (i == j ? 1.0 : 0.0);
      const Matrix<double> M_e = multiply(C_e, S_e);
      // |rho_r| < 1 / bound_factor, with a margin far above the round-off of rho_r
      const double limit = law.tau0 * (1.0 - 1e-10) / bound_factor;
      for (int r = 0; r < n_slip; ++r)
        {
          double tau = 0.0;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              tau += M_e[i][j] * law.schmid[r][i][j];
          if (!(std::abs(tau) < limit * tau_c_scaled[r]))
            return false;
        }
      return true;
    }

    // dP/dF of P = H S_e G^T (H = F G = F_e, G = F_p,n^-1), S_e = L^e : E_e,
    // E_e = 1/2 (H^T H - I). With the unrolled n^iJ_ab = dP_iJ/dS_ab = H_ia G_Jb (+ H_ib G_Ja for
    // a < b), dE_ab/dF_kL = w_ab n^kL_ab (w = 1 on the diagonal, 1/2 off it), and the cubic L^e,
    //   dP_iJ/dF_kL = (C11 - C12) sum_a n^iJ_aa n^kL_aa + C12 s^iJ s^kL
    //                 + C44 sum_(a<b) n^iJ_ab n^kL_ab + d_ik (G S_e G^T)_LJ,   s = sum_a n_aa,
    // symmetric in (iJ, kL) (hyperelasticity), so only half of it is formed.
    void elastic_tangent(const SlipLawData    &law,
                         const Matrix<double> &H,
                         const Matrix<double> &G,
                         const Matrix<double> &S_e,
                         Tensor<4, 3>         &dP_dF)
    {
      const Matrix<double>                  Q = multiply_transposed_second(multiply(G, S_e), G);
      std::array<std::array<double, 7>, 9> n_unrolled; // n_aa (3), n_ab (3), s
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J = 0; J < 3; ++J)
          {
            auto &v = n_unrolled[3 * i + J];
            for (unsigned int m = 0; m < 6; ++m)
              {
                const unsigned int a = sym_i[m], b = sym_j[m];
                v[m] = H[i][a] * G[J][b] + (m < 3 ? 0.0 : H[i][b] * G[J][a]);
              }
            v[6] = v[0] + v[1] + v[2];
          }
      const double normal = law.C11 - law.C12;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J = 0; J < 3; ++J)
          {
            const auto &u = n_unrolled[3 * i + J];
            for (unsigned int k = i; k < 3; ++k)
              for (unsigned int L = (k == i ? J : 0); L < 3; ++L)
                {
                  const auto &v = n_unrolled[3 * k + L];
                  double value = normal * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) +
                                 law.C12 * u[6] * v[6] + law.C44 * (u[3] * v[3] + u[4] * v[4] + u[5] * v[5]);
                  if (i == k)
                    value += Q[L][J];
                  dP_dF[i][J][k][L] = value;
                  dP_dF[k][L][i][J] = value;
                }
          }
    }

    // The local problem of one increment: unknowns x = (E_e (6), Delta lambda / tau0,
    // tau_c^r / tau0), residuals of the header in strain units (stresses divided by C44), and
    // their Jacobian written out by the chain rule in plain doubles (dexp(X)/dX from the series,
    // exp_matrix_and_derivative; the secant Hbar'(Delta Gamma) by one AD direction):
    //   dR_E/dx = I_E - 1/2 dC_e/dDelta gamma . dDelta gamma/dx,
    //   dC_e/dDelta gamma^r = -sum_ab dC_e/dX_ab (m_0^r (x) n_0^r)_ab, X = -Delta L_p,
    //   dDelta gamma^r = g_r/tau_c^r dlambda - lambda g_r/tau_c^r^2 dtau_c^r
    //                    + lambda w_r/(tau_c^r Phi) (drho_r - d_r dPhi),
    // with rho_r = tau^r/tau_c^r, d_r = rho_r/Phi, g_r = d_r^(2n-1) = dPhi/drho_r,
    // w_r = (2n-1) d_r^(2n-2) (all scaled by tau0 as the unknowns are).
    template <int n_slip>
    struct CrystalLocalProblem
    {
      static constexpr int n_unknowns = 7 + n_slip;
      static constexpr int lambda_index = 6;
      static constexpr int tau_c_index = 7;
      using Unknowns = std::array<double, n_unknowns>;
      using Jacobian = std::array<std::array<double, n_unknowns>, n_unknowns>;

      SlipLawData                  law;
      const ExtendedVoceHardening *hardening;
      double                       Gamma_n;
      const double                *tau_c_n; // n_slip [GPa]
      Matrix<double>               C_e_trial;

      // slip and A are written by every evaluation, the rest by those with a Jacobian; the
      // state update and the consistent tangent reuse them.
      SlipResponse<n_slip, double>                       slip;
      Matrix<double>                                     A;        // exp(-Delta L_p)
      std::array<Matrix<double>, 9>                      dA_dX;    // dA/dX_ab, row-major ab
      std::array<std::array<double, n_unknowns>, n_slip> ddelta_gamma_dx;
      // dR_tc/dtau_c = diag(tau_c_diagonal) - low_rank_P low_rank_Q^T (see solve_linearized).
      std::array<double, n_slip>                         tau_c_diagonal;
      std::array<std::array<double, 2>, n_slip>          low_rank_P, low_rank_Q;

      Matrix<double> minus_delta_L_p() const
      {
        Matrix<double> X;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              double sum = 0.0;
              for (int r = 0; r < n_slip; ++r)
                if (law.schmid[r][i][j] != 0.0)
                  sum -= slip.delta_gamma[r] * law.schmid[r][i][j];
              X[i][j] = sum;
            }
        return X;
      }

      void operator()(const Unknowns &x, Unknowns &R, Jacobian *jacobian)
      {
        slip_response<n_slip, double>(law, &x[0], &x[tau_c_index], x[lambda_index], slip);

        // A = exp(-Delta L_p) (eqs 12-13), with dA/dX when the Jacobian is wanted.
        const Matrix<double> X = minus_delta_L_p();
        Matrix<double>       C_e;
        std::array<std::array<double, 9>, 6> dC_e_dX; // unrolled C_e by X_ab
        if (jacobian)
          {
            exp_matrix_and_derivative(X, A, dA_dX);
            // dC_e/dX_ab = dA^T B + B^T dA, B = C_e^tr A
            const Matrix<double> B = multiply(C_e_trial, A);
            C_e = multiply_transposed_first(A, B);
            for (unsigned int ab = 0; ab < 9; ++ab)
              {
                const Matrix<double> dA_T_B = multiply_transposed_first(dA_dX[ab], B);
                for (unsigned int k = 0; k < 6; ++k)
                  dC_e_dX[k][ab] = dA_T_B[sym_i[k]][sym_j[k]] + dA_T_B[sym_j[k]][sym_i[k]];
              }
          }
        else
          {
            A = exp_matrix(X);
            C_e = multiply_transposed_first(A, multiply(C_e_trial, A));
          }
        for (unsigned int k = 0; k < 6; ++k)
          R[k] = x[k] - 0.5 * (C_e[sym_i[k]][sym_j[k]] - (k < 3 ? 1.0 : 0.0));

        R[lambda_index] = (slip.Phi - 1.0) * (law.tau0 / law.C44);

        // Secant hardening Hbar(Delta Gamma) and its derivative (one AD direction).
        double                   delta_Gamma = 0.0;
        std::array<double, n_slip> abs_delta_gamma;
        for (int r = 0; r < n_slip; ++r)
          {
            abs_delta_gamma[r] = slip.delta_gamma[r] >= 0 ? slip.delta_gamma[r] : -slip.delta_gamma[r];
            delta_Gamma += abs_delta_gamma[r];
          }
        using SecantDerivative = Sacado::Fad::SFad<double, 1>;
        const SecantDerivative H_bar_ad =
          voce_secant_modulus(*hardening, Gamma_n, SecantDerivative(1, 0, delta_Gamma));
        const double H_bar = H_bar_ad.val();
        const double q = hardening->q;
        for (int r = 0; r < n_slip; ++r)
          R[tau_c_index + r] = (law.tau0 * x[tau_c_index + r] - tau_c_n[r] -
                                H_bar * (q * delta_Gamma + (1.0 - q) * abs_delta_gamma[r])) /
                               law.C44;
        if (!jacobian)
          return;

        Jacobian &J = *jacobian;
        const double lambda = x[lambda_index];
        const double *tau_c = &x[tau_c_index];

        // drho_r/dE_k = (m_0^r (x) n_0^r) : dM_e/dE_k / (tau0 tau_c^r),
        // dM_e = 2 dE S_e + C_e (L^e : dE) (eq. 10).
        Matrix<double> C_e_of_E = identity_matrix<double>();
        for (unsigned int k = 0; k < 6; ++k)
          {
            C_e_of_E[sym_i[k]][sym_j[k]] += 2.0 * x[k];
            if (k >= 3)
              C_e_of_E[sym_j[k]][sym_i[k]] += 2.0 * x[k];
          }
        std::array<Matrix<double>, 6> dM_dE;
        for (unsigned int k = 0; k < 6; ++k)
          {
            Matrix<double> dE{};
            dE[sym_i[k]][sym_j[k]] = 1.0;
            dE[sym_j[k]][sym_i[k]] = 1.0;
            const Matrix<double> dS = elastic_stress(law, dE);
            const Matrix<double> first = multiply(dE, slip.S_e);
            const Matrix<double> second = multiply(C_e_of_E, dS);
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                dM_dE[k][i][j] = 2.0 * first[i][j] + second[i][j];
          }

        std::array<double, n_unknowns> dPhi_dx{};
        std::array<std::array<double, 6>, n_slip> drho_dE;
        std::array<double, n_slip> g, w, d;
        const bool yielding = slip.Phi != 0.0;
        for (int r = 0; r < n_slip; ++r)
          {
            const double scale = 1.0 / (law.tau0 * tau_c[r]);
            for (unsigned int k = 0; k < 6; ++k)
              {
                double sum = 0.0;
                for (unsigned int i = 0; i < 3; ++i)
                  for (unsigned int j = 0; j < 3; ++j)
                    sum += dM_dE[k][i][j] * law.schmid[r][i][j];
                drho_dE[r][k] = sum * scale;
              }
            if (yielding)
              {
                d[r] = slip.ratio[r] / slip.Phi;
                g[r] = d[r] * slip.flow_power[r];
                w[r] = (2.0 * law.n - 1.0) * slip.flow_power[r];
              }
            else
              d[r] = g[r] = w[r] = 0.0;
            for (unsigned int k = 0; k < 6; ++k)
              dPhi_dx[k] += g[r] * drho_dE[r][k];
            // drho_r/dtau_c^r = -rho_r / tau_c^r
            dPhi_dx[tau_c_index + r] = -g[r] * slip.ratio[r] / tau_c[r];
          }

        // dDelta gamma^r/dtau_c^s = delta_rs D_r + u_r v_s (the critical shear of the system
        // itself, and every tau_c through Phi).
        std::array<double, n_slip> D, u, v;
        for (int r = 0; r < n_slip; ++r)
          {
            auto        &row = ddelta_gamma_dx[r];
            const double c = yielding ? lambda * w[r] / (tau_c[r] * slip.Phi) : 0.0;
            for (unsigned int k = 0; k < 6; ++k)
              row[k] = c * (drho_dE[r][k] - d[r] * dPhi_dx[k]);
            row[lambda_index] = g[r] / tau_c[r];
            D[r] = -c * slip.ratio[r] / tau_c[r] - lambda * g[r] / (tau_c[r] * tau_c[r]);
            u[r] = c * d[r];
            v[r] = -dPhi_dx[tau_c_index + r];
          }
        for (int r = 0; r < n_slip; ++r)
          for (int s = 0; s < n_slip; ++s)
            ddelta_gamma_dx[r][tau_c_index + s] = u[r] * v[s] + (r == s ? D[r] : 0.0);

        // R_E rows: dR_E/dx = I_E - 1/2 dC_e/dDelta gamma dDelta gamma/dx.
        std::array<std::array<double, n_slip>, 6> dC_e_ddelta_gamma;
        for (unsigned int k = 0; k < 6; ++k)
          for (int r = 0; r < n_slip; ++r)
            {
              double sum = 0.0;
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  sum -= dC_e_dX[k][3 * a + b] * law.schmid[r][a][b];
              dC_e_ddelta_gamma[k][r] = sum;
            }
        for (unsigned int k = 0; k < 6; ++k)
          {
            auto  &row = J[k];
            double dC_e_u = 0.0;
            for (int j = 0; j < tau_c_index; ++j)
              row[j] = 0.0;
            for (int r = 0; r < n_slip; ++r)
              {
                const double dC = -0.5 * dC_e_ddelta_gamma[k][r];
                for (int j = 0; j < tau_c_index; ++j)
                  row[j] += dC * ddelta_gamma_dx[r][j];
                dC_e_u += dC * u[r];
              }
            row[k] += 1.0;
            for (int s = 0; s < n_slip; ++s)
              row[tau_c_index + s] = -0.5 * dC_e_ddelta_gamma[k][s] * D[s] + dC_e_u * v[s];
          }

        // R_f row.
        for (int j = 0; j < n_unknowns; ++j)
          J[lambda_index][j] = dPhi_dx[j] * (law.tau0 / law.C44);

        // R_tc rows: d(Hbar (q Delta Gamma + (1 - q) |Delta gamma^r|)), with
        // dR_tc^r/dtau_c^s = delta_rs (tau0 - b_r D_r)/C44 - (a_r e_s + b_r u_r v_s)/C44,
        // e = dDelta Gamma/dtau_c: diagonal minus rank 2, kept for solve_linearized.
        std::array<double, n_unknowns> ddelta_Gamma_dx{};
        double                         sign_u = 0.0;
        std::array<double, n_slip>     sign;
        for (int r = 0; r < n_slip; ++r)
          {
            sign[r] = slip.delta_gamma[r] >= 0 ? 1.0 : -1.0;
            for (int j = 0; j < tau_c_index; ++j)
              ddelta_Gamma_dx[j] += sign[r] * ddelta_gamma_dx[r][j];
            sign_u += sign[r] * u[r];
          }
        for (int s = 0; s < n_slip; ++s)
          ddelta_Gamma_dx[tau_c_index + s] = sign[s] * D[s] + sign_u * v[s];
        const double dH_bar = H_bar_ad.fastAccessDx(0);
        for (int r = 0; r < n_slip; ++r)
          {
            const double a = dH_bar * (q * delta_Gamma + (1.0 - q) * abs_delta_gamma[r]) + H_bar * q;
            const double b = H_bar * (1.0 - q) * sign[r];
            tau_c_diagonal[r] = (law.tau0 - b * D[r]) / law.C44;
            low_rank_P[r] = {{a / law.C44, b * u[r] / law.C44}};
            low_rank_Q[r] = {{ddelta_Gamma_dx[tau_c_index + r], v[r]}};
          }
        for (int r = 0; r < n_slip; ++r)
          {
            auto &row = J[tau_c_index + r];
            for (int j = 0; j < tau_c_index; ++j)
              row[j] = -(low_rank_P[r][0] * law.C44 * ddelta_Gamma_dx[j] +
                         (1.0 - q) * H_bar * sign[r] * ddelta_gamma_dx[r][j]) /
                       law.C44;
            for (int s = 0; s < n_slip; ++s)
              row[tau_c_index + s] =
                -(low_rank_P[r][0] * low_rank_Q[s][0] + low_rank_P[r][1] * low_rank_Q[s][1]) +
                (r == s ? tau_c_diagonal[r] : 0.0);
          }
      }

      // Solves J X = B, J from the last evaluation with a Jacobian, by eliminating the critical
      // shears: with y = (E_e, Delta lambda), t = tau_c,
      //   Z = J_tt^-1 [J_ty | B_t],  (J_yy - J_yt Z_y) X_y = B_y - J_yt Z_B,  X_t = Z_B - Z_y X_y,
      // where J_tt = D - P Q^T (diagonal plus rank 2, the latent hardening and the shared Phi)
      // is inverted by the Sherman-Morrison-Woodbury formula
      //   J_tt^-1 = D^-1 + D^-1 P (I - Q^T D^-1 P)^-1 Q^T D^-1.
      // That needs D and the 2x2 capacitance away from singular: for large increments with
      // q > 1, D_r = (tau0 - b_r D_r)/C44 can approach zero while J itself is regular, so those
      // cases fall back to the dense LU of J.
      template <int n_rhs>
      bool solve_linearized(const Jacobian &J, std::array<std::array<double, n_rhs>, n_unknowns> &B) const
      {
        constexpr int n_y = tau_c_index, n_columns = n_y + n_rhs;
        const auto    dense = [&]() {
          auto copy = J;
          return internal::solve_dense<n_unknowns, n_rhs>(copy, B);
        };
        const double diagonal_floor = 0.1 * law.tau0 / law.C44;
        for (int r = 0; r < n_slip; ++r)
          if (!(std::abs(tau_c_diagonal[r]) >= diagonal_floor))
            return dense();
        std::array<double, 2>                 capacitance_rows[2] = {{{1.0, 0.0}}, {{0.0, 1.0}}};
        for (int r = 0; r < n_slip; ++r)
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int j = 0; j < 2; ++j)
              capacitance_rows[i][j] -= low_rank_Q[r][i] * low_rank_P[r][j] / tau_c_diagonal[r];
        const double determinant = capacitance_rows[0][0] * capacitance_rows[1][1] -
                                   capacitance_rows[0][1] * capacitance_rows[1][0];
        if (!(std::abs(determinant) >= 1e-3))
          return dense();

        // Z = J_tt^-1 [J_ty | B_t]
        std::array<std::array<double, n_columns>, n_slip> Z;
        std::array<double, n_columns>                     W0{}, W1{};
        for (int r = 0; r < n_slip; ++r)
          {
            const double inverse_diagonal = 1.0 / tau_c_diagonal[r];
            for (int c = 0; c < n_columns; ++c)
              {
                Z[r][c] = (c < n_y ? J[n_y + r][c] : B[n_y + r][c - n_y]) * inverse_diagonal;
                W0[c] += low_rank_Q[r][0] * Z[r][c];
                W1[c] += low_rank_Q[r][1] * Z[r][c];
              }
          }
        for (int c = 0; c < n_columns; ++c)
          {
            const double k0 = (capacitance_rows[1][1] * W0[c] - capacitance_rows[0][1] * W1[c]) / determinant;
            const double k1 = (capacitance_rows[0][0] * W1[c] - capacitance_rows[1][0] * W0[c]) / determinant;
            W0[c] = k0;
            W1[c] = k1;
          }
        for (int r = 0; r < n_slip; ++r)
          {
            const double p0 = low_rank_P[r][0] / tau_c_diagonal[r],
                         p1 = low_rank_P[r][1] / tau_c_diagonal[r];
            for (int c = 0; c < n_columns; ++c)
              Z[r][c] += p0 * W0[c] + p1 * W1[c];
          }

        // Schur complement on y.
        std::array<std::array<double, n_y>, n_y>   schur;
        std::array<std::array<double, n_rhs>, n_y> X_y;
        for (int i = 0; i < n_y; ++i)
          {
            for (int c = 0; c < n_y; ++c)
              schur[i][c] = J[i][c];
            for (int c = 0; c < n_rhs; ++c)
              X_y[i][c] = B[i][c];
            for (int r = 0; r < n_slip; ++r)
              {
                const double J_yt = J[i][n_y + r];
                for (int c = 0; c < n_y; ++c)
                  schur[i][c] -= J_yt * Z[r][c];
                for (int c = 0; c < n_rhs; ++c)
                  X_y[i][c] -= J_yt * Z[r][n_y + c];
              }
          }
        if (!internal::solve_dense<n_y, n_rhs>(schur, X_y))
          return dense();
        for (int r = 0; r < n_slip; ++r)
          for (int c = 0; c < n_rhs; ++c)
            {
              double sum = Z[r][n_y + c];
              for (int j = 0; j < n_y; ++j)
                sum -= Z[r][j] * X_y[j][c];
              B[n_y + r][c] = sum;
            }
        for (int i = 0; i < n_y; ++i)
          B[i] = X_y[i];
        return true;
      }
    };

    // P = F_e S_e F_p^-T and the Kirchhoff stress tau = P F^T.
    void write_stress(const Matrix<double> &F_e,
                      const Matrix<double> &S_e,
                      const Matrix<double> &F_p_inverse,
                      const Tensor<2, 3>   &F,
                      MaterialPointResponse &response)
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
  } // namespace

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
    return theta1 + (theta0 - theta1 + theta0 * theta1 * Gamma / tau1) * std::exp(-theta0 * Gamma / tau1);
  }

  CrystalPlasticity::CrystalPlasticity(const SlipSystems           &slip_systems,
                                       const CubicElasticity       &elasticity,
                                       const ExtendedVoceHardening &hardening,
                                       const double                 yield_exponent_n)
    : systems(slip_systems)
    , n_systems(slip_systems.size())
    , elasticity(elasticity)
    , hardening(hardening)
    , n(yield_exponent_n)
  {
    const auto require = [](const bool ok, const std::string &message) {
      if (!ok)
        throw std::invalid_argument("CrystalPlasticity: " + message);
    };
    require(n_systems == 12,
            "the integrator is instantiated for 12 slip systems, got " + std::to_string(n_systems));
    require(elasticity.C44 > 0 && elasticity.C11 - elasticity.C12 > 0 &&
              elasticity.C11 + 2 * elasticity.C12 > 0,
            "cubic stiffness not positive definite (need C44 > 0, C11 > C12, C11 + 2 C12 > 0)");
    require(hardening.tau0 > 0 && std::isfinite(hardening.tau0), "tau0 must be positive");
    require(hardening.tau1 >= 0 && hardening.theta0 >= 0 && hardening.theta1 >= 0 &&
              hardening.q >= 0,
            "tau1, theta0, theta1 and q must be non-negative");
    require(!(hardening.tau1 == 0 && hardening.theta0 > 0),
            "tau1 must be positive when theta0 > 0 (the Voce term divides by tau1)");
    require(n >= 1 && n <= 50, "yield_exponent_n must lie in [1, 50]");
    for (unsigned int r = 0; r < n_systems; ++r)
      schmid.push_back(to_matrix(systems.schmid_tensor(r)));
    yield_bound_factor = std::pow(double(n_systems), 1.0 / (2.0 * n));
  }

  double CrystalPlasticity::reference_modulus() const
  {
    return (elasticity.C11 - elasticity.C12 + 3.0 * elasticity.C44) / 5.0;
  }

  void CrystalPlasticity::initial_state(std::span<double> state) const
  {
    oriented_initial_state(state, dealii::unit_symmetric_tensor<3>());
  }

  void CrystalPlasticity::oriented_initial_state(std::span<double>   state,
                                                 const Tensor<2, 3> &orientation) const
  {
    Assert(state.size() == n_state_variables(),
           dealii::ExcDimensionMismatch(state.size(), n_state_variables()));
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        state[3 * i + j] = orientation[i][j];
    for (unsigned int r = 0; r < n_systems; ++r)
      state[9 + r] = hardening.tau0;
    state[9 + n_systems] = 0.0;
  }

  Tensor<2, 3> CrystalPlasticity::plastic_deformation(std::span<const double> state)
  {
    Tensor<2, 3> F_p;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        F_p[i][j] = state[3 * i + j];
    return F_p;
  }

  std::vector<double> CrystalPlasticity::resolved_shear_stresses(const Tensor<2, 3>     &F,
                                                                 std::span<const double> state) const
  {
    const Matrix<double> F_e = multiply(to_matrix(F), to_matrix(inverse_3x3(plastic_deformation(state))));
    const auto           C_e = multiply_transposed_first(F_e, F_e);
    std::array<double, 6> E;
    for (unsigned int k = 0; k < 6; ++k)
      E[k] = 0.5 * (C_e[sym_i[k]][sym_j[k]] - (k < 3 ? 1.0 : 0.0));
    const SlipLawData       law{elasticity.C11, elasticity.C12, elasticity.C44, n, hardening.tau0,
                          schmid.data()};
    std::array<double, 12>  unit;
    unit.fill(1.0);
    SlipResponse<12, double> slip;
    slip_response<12, double>(law, E.data(), unit.data(), 0.0, slip);
    std::vector<double> tau(n_systems);
    for (unsigned int r = 0; r < n_systems; ++r)
      tau[r] = slip.ratio[r] * hardening.tau0;
    return tau;
  }

  double CrystalPlasticity::yield_function_value(const std::vector<double> &tau,
                                                 const std::vector<double> &tau_c) const
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

  UpdateStatus CrystalPlasticity::update(const Tensor<2, 3>     &F,
                                         std::span<const double> state_old,
                                         MaterialPointResponse  &response,
                                         std::span<double>       state_new,
                                         const bool              compute_tangent) const
  {
    Assert(state_old.size() == n_state_variables(),
           dealii::ExcDimensionMismatch(state_old.size(), n_state_variables()));
    Assert(state_new.size() == n_state_variables(),
           dealii::ExcDimensionMismatch(state_new.size(), n_state_variables()));
    return update_impl<12>(F, state_old, response, state_new, compute_tangent);
  }

  template <int n_slip>
  UpdateStatus CrystalPlasticity::update_impl(const Tensor<2, 3>     &F,
                                              std::span<const double> state_old,
                                              MaterialPointResponse  &response,
                                              std::span<double>       state_new,
                                              const bool              compute_tangent) const
  {
    using LocalProblem = CrystalLocalProblem<n_slip>;
    constexpr int n_unknowns = LocalProblem::n_unknowns;
    using Newton = ImplicitLocalProblem<n_unknowns, 6>;

    double J_minus_one = 0.0;
    if (!admissible_deformation(F, J_minus_one))
      return UpdateStatus::invalid_deformation;

    const Matrix<double> F_matrix = to_matrix(F);
    const Matrix<double> F_p_n_inverse = to_matrix(inverse_3x3(plastic_deformation(state_old)));
    const double        *tau_c_n = &state_old[9];
    const double         Gamma_n = state_old[9 + n_slip];
    const SlipLawData    law{elasticity.C11, elasticity.C12, elasticity.C44, n, hardening.tau0,
                          schmid.data()};

    // Elastic trial: C_e^tr = F_p,n^-T C F_p,n^-1 and E_e^tr.
    const Matrix<double> F_e_trial = multiply(F_matrix, F_p_n_inverse);
    const auto           C_e_trial = multiply_transposed_first(F_e_trial, F_e_trial);
    std::array<double, 6> E_trial;
    for (unsigned int k = 0; k < 6; ++k)
      E_trial[k] = 0.5 * (C_e_trial[sym_i[k]][sym_j[k]] - (k < 3 ? 1.0 : 0.0));
    std::array<double, n_slip> tau_c_n_scaled;
    for (int r = 0; r < n_slip; ++r)
      tau_c_n_scaled[r] = tau_c_n[r] / hardening.tau0;

    // Elastic step, P = F_e S_e F_p,n^-T with F_e = F F_p,n^-1.
    const auto elastic_step = [&](const Matrix<double> &S_e) {
      write_stress(F_e_trial, S_e, F_p_n_inverse, F, response);
      if (compute_tangent)
        elastic_tangent(law, F_e_trial, F_p_n_inverse, S_e, response.dP_dF);
      std::copy(state_old.begin(), state_old.end(), state_new.begin());
      return UpdateStatus::success;
    };

    Matrix<double> S_e_trial;
    if (certainly_elastic<n_slip>(law, E_trial, tau_c_n_scaled.data(), yield_bound_factor, S_e_trial))
      return elastic_step(S_e_trial);
    SlipResponse<n_slip, double> trial;
    slip_response<n_slip, double>(law, E_trial.data(), tau_c_n_scaled.data(), 0.0, trial);
    if (!std::isfinite(trial.Phi))
      return UpdateStatus::invalid_deformation;

    // KKT (eq. 8): no plastic flow while Phi <= 1.
    if (trial.Phi <= 1.0)
      return elastic_step(trial.S_e);

    // Plastic corrector: the local Newton from the elastic trial.
    LocalProblem problem; // the workspace members are written before they are read
    problem.law = law;
    problem.hardening = &hardening;
    problem.Gamma_n = Gamma_n;
    problem.tau_c_n = tau_c_n;
    problem.C_e_trial = C_e_trial;
    std::array<double, n_unknowns> unknowns;
    double strain_scale = hardening.tau0 / elasticity.C44;
    for (unsigned int k = 0; k < 6; ++k)
      strain_scale = std::max(strain_scale, std::abs(E_trial[k]));
    LocalNewtonSettings settings;
    settings.max_iterations = 50;
    settings.max_line_search_steps = 20;
    // Forming A^T C_e^tr A near the identity leaves round-off ~1e-16 in E_e whatever its size.
    settings.tolerance = std::max(1e-13 * strain_scale, 2e-15);
    settings.stagnation_tolerance = std::max(1e-10 * strain_scale, 1e-13);

    typename LocalProblem::Jacobian jacobian;
    LocalNewtonResult               newton;
    // Warm start from the hint in state_new (see MaterialModel::update): the previous global
    // Newton iterate of this increment, if it was plastic. Close to convergence of the global
    // Newton this takes 2-3 local iterations instead of 5 or more from the elastic trial
    // (crystal_24: 2.7 against 5.1 on average); a hint that does not converge to
    // Delta lambda > 0 is dropped and the Newton starts again from the trial.
    if (warm_start_guess<n_slip>(law, F_matrix, state_old, state_new, unknowns))
      {
        newton = Newton::solve_with_jacobian(problem, unknowns, jacobian, settings);
        if (!newton.converged || !(unknowns[LocalProblem::lambda_index] > 0.0))
          newton.converged = false;
      }
    if (!newton.converged)
      {
        for (unsigned int k = 0; k < 6; ++k)
          unknowns[k] = E_trial[k];
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
        std::copy(state_old.begin(), state_old.end(), state_new.begin());
        return UpdateStatus::local_newton_failed;
      }

    // The converged slip increments and A = exp(-Delta L_p) are those of the last evaluation;
    // the tangent needs the Jacobian there too.
    if (compute_tangent && !newton.jacobian_at_solution)
      {
        std::array<double, n_unknowns> residual;
        problem(unknowns, residual, &jacobian);
      }
    const SlipResponse<n_slip, double> &slip = problem.slip;
    const Matrix<double>               &A = problem.A;
    Matrix<double> delta_L_p{};
    double         delta_Gamma = 0.0;
    for (int r = 0; r < n_slip; ++r)
      {
        delta_Gamma += std::abs(slip.delta_gamma[r]);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            delta_L_p[i][j] += slip.delta_gamma[r] * schmid[r][i][j];
      }
    const Matrix<double> F_p_new = multiply(exp_matrix(delta_L_p), to_matrix(plastic_deformation(state_old)));
    const Matrix<double> F_p_new_inverse = multiply(F_p_n_inverse, A);
    const Matrix<double> F_e = multiply(F_e_trial, A);
    write_stress(F_e, slip.S_e, F_p_new_inverse, F, response);

    if (compute_tangent)
      {
        // Implicit function theorem: dx/dC_e^tr = -(dR/dx)^-1 dR/dC_e^tr, where only R_E depends
        // on C_e^tr: dR_E/dC_e^tr_m = -1/2 A^T U_m A (U_m the unit symmetric tensor of entry m).
        std::array<std::array<double, 6>, n_unknowns> dx_dp{};
        for (unsigned int m = 0; m < 6; ++m)
          {
            Matrix<double> U{};
            U[sym_i[m]][sym_j[m]] = 1.0;
            U[sym_j[m]][sym_i[m]] = 1.0;
            const auto AUA = multiply_transposed_first(A, multiply(U, A));
            for (unsigned int k = 0; k < 6; ++k)
              dx_dp[k][m] = 0.5 * AUA[sym_i[k]][sym_j[k]];
          }
        if (!problem.template solve_linearized<6>(jacobian, dx_dp))
          {
            std::copy(state_old.begin(), state_old.end(), state_new.begin());
            return UpdateStatus::local_newton_failed;
          }
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

        // P = F_e S_e F_p^-T with F_e = F G A, F_p^-1 = G A (G = F_p,n^-1):
        //   dP = (dF G A + F G dA) S_e F_p^-T + F_e (L^e : dE_e) F_p^-T + F_e S_e (G dA)^T.
        const Matrix<double> S_F_p_inverse_T = multiply_transposed_second(slip.S_e, F_p_new_inverse);
        const Matrix<double> F_e_S = multiply(F_e, slip.S_e);
        const Matrix<double> G_A = F_p_new_inverse;
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            {
              const auto &G_L = F_p_n_inverse[L]; // dF G has the single row k = G_L
              std::array<double, 6> dp;
              for (unsigned int m = 0; m < 6; ++m)
                {
                  const unsigned int i = sym_i[m], j = sym_j[m];
                  dp[m] = G_L[i] * F_e_trial[k][j] + F_e_trial[k][i] * G_L[j];
                }
              Matrix<double> dE;
              for (unsigned int m = 0; m < 6; ++m)
                {
                  double sum = 0.0;
                  for (unsigned int a = 0; a < 6; ++a)
                    sum += dx_dp[m][a] * dp[a];
                  dE[sym_i[m]][sym_j[m]] = sum;
                  dE[sym_j[m]][sym_i[m]] = sum;
                }
              // dX = -sum_r dDelta gamma^r m_0^r (x) n_0^r, dA = dA/dX : dX
              Matrix<double> dX{};
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
              Matrix<double> dA{};
              for (unsigned int ab = 0; ab < 9; ++ab)
                {
                  const double dX_ab = dX[ab / 3][ab % 3];
                  for (unsigned int i = 0; i < 3; ++i)
                    for (unsigned int j = 0; j < 3; ++j)
                      dA[i][j] += problem.dA_dX[ab][i][j] * dX_ab;
                }
              Matrix<double> dF_e = multiply(F_e_trial, dA);
              for (unsigned int j = 0; j < 3; ++j)
                for (unsigned int m = 0; m < 3; ++m)
                  dF_e[k][j] += G_L[m] * A[m][j];
              const auto dP_1 = multiply(dF_e, S_F_p_inverse_T);
              const auto dP_2 = multiply_transposed_second(multiply(F_e, elastic_stress(law, dE)), G_A);
              const auto dP_3 = multiply_transposed_second(F_e_S, multiply(F_p_n_inverse, dA));
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int J = 0; J < 3; ++J)
                  response.dP_dF[i][J][k][L] = dP_1[i][J] + dP_2[i][J] + dP_3[i][J];
            }
      }

    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        state_new[3 * i + j] = F_p_new[i][j];
    for (int r = 0; r < n_slip; ++r)
      state_new[9 + r] = hardening.tau0 * unknowns[LocalProblem::tau_c_index + r];
    state_new[9 + n_slip] = Gamma_n + delta_Gamma;
    for (const double v : state_new)
      if (!std::isfinite(v))
        {
          std::copy(state_old.begin(), state_old.end(), state_new.begin());
          return UpdateStatus::local_newton_failed;
        }
    return UpdateStatus::success;
  }
} // namespace indentsim::materials
