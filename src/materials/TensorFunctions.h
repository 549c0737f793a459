// Functions of 3x3 tensors used by the constitutive models, written once for any scalar type
// `Number` (double, or Sacado forward-AD numbers such as Sacado::Fad::SFad<double, n>), so that
// a model's consistent tangent can be obtained by automatic differentiation through them.
//
// The exponential and the logarithm of a symmetric tensor are the ones of the exponential-map
// return (paper eq. 9: b_e = exp(2 eps_e), eps_e = 1/2 log b_e). They deliberately avoid any
// eigen-decomposition: a spectral formula branches on (nearly) repeated eigenvalues, and its
// derivative is then wrong or ill-conditioned exactly where plasticity likes to live (uniaxial
// and equibiaxial states). Instead only sums, products of commuting symmetric tensors and
// inverses are used, so the derivative of every step is exact and finite:
//   exp (and exp - I): scaling and squaring with a diagonal Pade approximant (Higham 2005),
//   log: inverse scaling and squaring, i.e. Denman-Beavers square roots until the argument is
//        close to the identity, then the Gauss-Legendre form of the diagonal Pade approximant
//        of log(1 + x) (Higham 2001, Cheng et al. 2001).
// Branch decisions (how many squarings/roots, which Pade degree) are taken on the values only,
// and every branch approximates the same analytic function to about one unit in the last
// place, so values and derivatives are continuous to that accuracy. The degree thresholds
// below bound the relative error of the scalar approximant by 2^-53 and the error of its
// derivative by 2^-51; for a symmetric argument that is the error of the tensor function up to
// round-off in the few inverses.
//
// Symmetric tensors are dealii::SymmetricTensor<2, 3, Number>, used as storage only: the
// arithmetic is done here through access_raw_entry() because deal.II's tensor operators are
// not defined for Sacado's SFad type (deal.II's ProductType knows only DFad). The unrolled
// order is deal.II's: 00, 11, 22, 01, 02, 12.
#pragma once

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <type_traits>

namespace indentsim::materials
{
  // The double value of a scalar that may be an AD number (also nested ones); used for
  // decisions that must not depend on derivatives.
  template <typename Number>
  inline double scalar_value(const Number &x)
  {
    if constexpr (std::is_arithmetic_v<Number>)
      return static_cast<double>(x);
    else
      return scalar_value(x.val());
  }

  namespace internal
  {
    // Unrolled index of (i, j) in a dealii::SymmetricTensor<2, 3>.
    inline constexpr unsigned int symmetric_index[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};

    // Nodes t_j and weights w_j of the m-point Gauss-Legendre rule on [0, 1]; the rule applied
    // to log(I + X) = int_0^1 X (I + t X)^-1 dt is the [m/m] Pade approximant.
    struct GaussLegendreRule
    {
      unsigned int n_points;
      double       theta; // largest admissible |eigenvalue of X| for full double accuracy
      double       nodes[8];
      double       weights[8];
    };

    // clang-format off
    inline constexpr GaussLegendreRule log_pade_rules[] = {
      {3,
       0.0075,
       {0.11270166537925831148, 0.5, 0.88729833462074168852},
       {0.27777777777777777778, 0.44444444444444444444, 0.27777777777777777778}},
      {4,
       0.0343,
       {0.069431844202973712388, 0.3300094782075718676, 0.6699905217924281324,
        0.93056815579702628761},
       {0.17392742256872692869, 0.32607257743127307131, 0.32607257743127307131,
        0.17392742256872692869}},
      {5,
       0.0844,
       {0.046910077030668003601, 0.23076534494715845448, 0.5, 0.76923465505284154552,
        0.9530899229693319964},
       {0.11846344252809454376, 0.23931433524968323402, 0.28444444444444444444,
        0.23931433524968323402, 0.11846344252809454376}},
      {6,
       0.1514,
       {0.033765242898423986094, 0.16939530676686774317, 0.38069040695840154568,
        0.61930959304159845432, 0.83060469323313225683, 0.96623475710157601391},
       {0.08566224618958517252, 0.18038078652406930378, 0.23395696728634552369,
        0.23395696728634552369, 0.18038078652406930378, 0.08566224618958517252}},
      {7,
       0.2263,
       {0.025446043828620737737, 0.12923440720030278007, 0.29707742431130141655, 0.5,
        0.70292257568869858345, 0.87076559279969721993, 0.97455395617137926226},
       {0.064742483084434846635, 0.13985269574463833395, 0.19091502525255947248,
        0.20897959183673469388, 0.19091502525255947248, 0.13985269574463833395,
        0.064742483084434846635}},
      {8,
       0.3019,
       {0.019855071751231884158, 0.1016667612931866302, 0.23723379504183550709,
        0.40828267875217509753, 0.59171732124782490247, 0.76276620495816449291,
        0.8983332387068133698, 0.98014492824876811584},
       {0.050614268145188129576, 0.11119051722668723527, 0.15685332293894364367,
        0.18134189168918099148, 0.18134189168918099148, 0.15685332293894364367,
        0.11119051722668723527, 0.050614268145188129576}}};
    // clang-format on

    // Largest admissible |eigenvalue of X| for the [m/m] Pade approximant of exp(X), m = 3..7,
    // to full double accuracy (value and derivative).
    inline constexpr double exp_pade_theta[] = {0.0136, 0.0771, 0.2290, 0.4893, 0.8614};
  } // namespace internal

  // ---------------------------------------------------------------------------------------
  // Elementary operations on symmetric tensors (storage-only use of SymmetricTensor).

  template <typename Number>
  inline dealii::SymmetricTensor<2, 3, Number> identity_symmetric()
  {
    dealii::SymmetricTensor<2, 3, Number> I;
    for (unsigned int k = 0; k < 6; ++k)
      I.access_raw_entry(k) = Number(k < 3 ? 1.0 : 0.0);
    return I;
  }

  template <typename Number>
  inline Number trace_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    return A.access_raw_entry(0) + A.access_raw_entry(1) + A.access_raw_entry(2);
  }

  // alpha A + beta B
  template <typename Number, typename Scalar1, typename Scalar2>
  inline dealii::SymmetricTensor<2, 3, Number>
  linear_combination(const Scalar1 &alpha, const dealii::SymmetricTensor<2, 3, Number> &A,
                     const Scalar2 &beta, const dealii::SymmetricTensor<2, 3, Number> &B)
  {
    dealii::SymmetricTensor<2, 3, Number> C;
    for (unsigned int k = 0; k < 6; ++k)
      C.access_raw_entry(k) = alpha * A.access_raw_entry(k) + beta * B.access_raw_entry(k);
    return C;
  }

  // alpha A
  template <typename Number, typename Scalar>
  inline dealii::SymmetricTensor<2, 3, Number>
  scaled(const Scalar &alpha, const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    dealii::SymmetricTensor<2, 3, Number> C;
    for (unsigned int k = 0; k < 6; ++k)
      C.access_raw_entry(k) = alpha * A.access_raw_entry(k);
    return C;
  }

  // A + alpha I
  template <typename Number, typename Scalar>
  inline dealii::SymmetricTensor<2, 3, Number>
  plus_identity(const dealii::SymmetricTensor<2, 3, Number> &A, const Scalar &alpha)
  {
    dealii::SymmetricTensor<2, 3, Number> C = A;
    for (unsigned int k = 0; k < 3; ++k)
      C.access_raw_entry(k) += alpha;
    return C;
  }

  // dev A = A - tr(A)/3 I
  template <typename Number>
  inline dealii::SymmetricTensor<2, 3, Number>
  deviator_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    const Number mean = trace_symmetric(A) / 3.0;
    return plus_identity(A, -mean);
  }

  // Frobenius norm |A| = sqrt(A : A), off-diagonal entries counted twice.
  template <typename Number>
  inline Number norm_squared_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    Number sum = A.access_raw_entry(0) * A.access_raw_entry(0);
    for (unsigned int k = 1; k < 3; ++k)
      sum += A.access_raw_entry(k) * A.access_raw_entry(k);
    for (unsigned int k = 3; k < 6; ++k)
      sum += 2.0 * A.access_raw_entry(k) * A.access_raw_entry(k);
    return sum;
  }

  template <typename Number>
  inline Number norm_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    using std::sqrt;
    return sqrt(norm_squared_symmetric(A));
  }

  template <typename Number>
  inline Number determinant_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    const Number &a = A.access_raw_entry(0), &b = A.access_raw_entry(1), &c = A.access_raw_entry(2),
                 &d = A.access_raw_entry(3), &e = A.access_raw_entry(4), &f = A.access_raw_entry(5);
    return a * (b * c - f * f) + d * (e * f - d * c) + e * (d * f - b * e);
  }

  // Inverse by cofactors (the caller guarantees det A != 0).
  template <typename Number>
  inline dealii::SymmetricTensor<2, 3, Number>
  inverse_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    const Number &a = A.access_raw_entry(0), &b = A.access_raw_entry(1), &c = A.access_raw_entry(2),
                 &d = A.access_raw_entry(3), &e = A.access_raw_entry(4), &f = A.access_raw_entry(5);
    dealii::SymmetricTensor<2, 3, Number> C;
    C.access_raw_entry(0) = b * c - f * f;
    C.access_raw_entry(1) = a * c - e * e;
    C.access_raw_entry(2) = a * b - d * d;
    C.access_raw_entry(3) = e * f - d * c;
    C.access_raw_entry(4) = d * f - b * e;
    C.access_raw_entry(5) = d * e - a * f;
    const Number det =
        a * C.access_raw_entry(0) + d * C.access_raw_entry(3) + e * C.access_raw_entry(4);
    const Number inverse_det = 1.0 / det;
    for (unsigned int k = 0; k < 6; ++k)
      C.access_raw_entry(k) *= inverse_det;
    return C;
  }

  // Symmetric part of A B, i.e. (A B + B A)/2. For commuting A and B (functions of one
  // tensor, as in every Pade or Newton step below) this is the product itself, and it keeps
  // the result (and its derivative in any symmetric direction) exactly symmetric.
  template <typename Number>
  inline dealii::SymmetricTensor<2, 3, Number>
  commuting_product(const dealii::SymmetricTensor<2, 3, Number> &A,
                    const dealii::SymmetricTensor<2, 3, Number> &B)
  {
    using internal::symmetric_index;
    dealii::SymmetricTensor<2, 3, Number> C;
    for (unsigned int k = 0; k < 6; ++k)
      {
        const unsigned int i = (k < 3 ? k : (k == 5 ? 1 : 0));
        const unsigned int j = (k < 3 ? k : (k == 3 ? 1 : 2));
        Number             sum =
            A.access_raw_entry(symmetric_index[i][0]) * B.access_raw_entry(symmetric_index[0][j]);
        for (unsigned int m = 1; m < 3; ++m)
          sum +=
              A.access_raw_entry(symmetric_index[i][m]) * B.access_raw_entry(symmetric_index[m][j]);
        if (k >= 3)
          {
            // (B A)_ij = (A B)_ji
            for (unsigned int m = 0; m < 3; ++m)
              sum += A.access_raw_entry(symmetric_index[j][m]) *
                     B.access_raw_entry(symmetric_index[m][i]);
            sum *= 0.5;
          }
        C.access_raw_entry(k) = sum;
      }
    return C;
  }

  // ---------------------------------------------------------------------------------------
  // General (unsymmetric) 3x3 tensors, for F and its inverse under AD.

  template <typename Number>
  inline Number determinant_3x3(const dealii::Tensor<2, 3, Number> &F)
  {
    return F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
           F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
           F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
  }

  template <typename Number>
  inline dealii::Tensor<2, 3, Number> inverse_3x3(const dealii::Tensor<2, 3, Number> &F)
  {
    dealii::Tensor<2, 3, Number> C; // transposed cofactor matrix
    C[0][0] = F[1][1] * F[2][2] - F[1][2] * F[2][1];
    C[0][1] = F[0][2] * F[2][1] - F[0][1] * F[2][2];
    C[0][2] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
    C[1][0] = F[1][2] * F[2][0] - F[1][0] * F[2][2];
    C[1][1] = F[0][0] * F[2][2] - F[0][2] * F[2][0];
    C[1][2] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
    C[2][0] = F[1][0] * F[2][1] - F[1][1] * F[2][0];
    C[2][1] = F[0][1] * F[2][0] - F[0][0] * F[2][1];
    C[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
    const Number inverse_det = 1.0 / (F[0][0] * C[0][0] + F[0][1] * C[1][0] + F[0][2] * C[2][0]);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        C[i][j] *= inverse_det;
    return C;
  }

  // det F - 1 without the cancellation of computing det F first: with H = F - I,
  // det(I + H) - 1 = tr H + (tr(H)^2 - tr(H^2))/2 + det H. Keeps the pressure of nearly
  // undeformed material accurate to relative round-off (libCEED's "J - 1" advice).
  inline double determinant_minus_one(const dealii::Tensor<2, 3> &F)
  {
    dealii::Tensor<2, 3> H = F;
    for (unsigned int i = 0; i < 3; ++i)
      H[i][i] -= 1.0;
    const double trace_H = H[0][0] + H[1][1] + H[2][2];
    double       trace_H2 = 0.0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        trace_H2 += H[i][j] * H[j][i];
    return trace_H + 0.5 * (trace_H * trace_H - trace_H2) + determinant_3x3(H);
  }

  // b = F A F^T for symmetric A (A = I gives the left Cauchy-Green tensor).
  template <typename Number, typename NumberA>
  inline dealii::SymmetricTensor<2, 3, Number>
  push_forward_symmetric(const dealii::Tensor<2, 3, Number>           &F,
                         const dealii::SymmetricTensor<2, 3, NumberA> &A)
  {
    using internal::symmetric_index;
    // G = F A
    dealii::Tensor<2, 3, Number> G;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          Number sum = F[i][0] * A.access_raw_entry(symmetric_index[0][j]);
          for (unsigned int m = 1; m < 3; ++m)
            sum += F[i][m] * A.access_raw_entry(symmetric_index[m][j]);
          G[i][j] = sum;
        }
    dealii::SymmetricTensor<2, 3, Number> b;
    for (unsigned int k = 0; k < 6; ++k)
      {
        const auto ij = dealii::SymmetricTensor<2, 3, double>::unrolled_to_component_indices(k);
        const auto i = ij[0], j = ij[1];
        Number     sum = G[i][0] * F[j][0];
        for (unsigned int m = 1; m < 3; ++m)
          sum += G[i][m] * F[j][m];
        b.access_raw_entry(k) = sum;
      }
    return b;
  }

  // ---------------------------------------------------------------------------------------
  // Exponential and logarithm.

  namespace internal
  {
    // Even and odd parts V, U of the numerator of the [m/m] Pade approximant of exp(X):
    // r_m(X) = q_m(X)^-1 p_m(X) with p_m = V + U, q_m = V - U. Costs floor(m/2) + 1 products.
    template <typename Number>
    void pade_exp_parts(const dealii::SymmetricTensor<2, 3, Number> &X, const unsigned int m,
                        dealii::SymmetricTensor<2, 3, Number> &V,
                        dealii::SymmetricTensor<2, 3, Number> &U)
    {
      Assert(m >= 3 && m <= 7, dealii::ExcIndexRange(m, 3, 8));
      // c_j = (2m - j)! m! / ((2m)! j! (m - j)!), built by the recursion c_j/c_{j-1}.
      double c[8];
      c[0] = 1.0;
      for (unsigned int j = 1; j <= m; ++j)
        c[j] = c[j - 1] * double(m - j + 1) / double(j * (2 * m - j + 1));

      const auto X2 = commuting_product(X, X);
      auto       power = X2;                                 // X^(2i)
      V = plus_identity(scaled(c[2], X2), c[0]);             // even part of p_m
      auto U_over_X = plus_identity(scaled(c[3], X2), c[1]); // odd part of p_m, over X
      for (unsigned int j = 4; j <= m; j += 2)
        {
          power = commuting_product(power, X2); // X^j
          V = linear_combination(1.0, V, c[j], power);
          if (j + 1 <= m)
            U_over_X = linear_combination(1.0, U_over_X, c[j + 1], power);
        }
      U = commuting_product(X, U_over_X);
    }

    // Pade degree m and number of squarings s for exp(X): the smallest m with |X| <= theta_m,
    // else m = 7 and X scaled by 2^-s.
    inline void exp_degree_and_squarings(const double norm_X, unsigned int &degree,
                                         unsigned int &n_squarings)
    {
      degree = 7;
      n_squarings = 0;
      for (unsigned int m = 3; m <= 7; ++m)
        if (norm_X <= exp_pade_theta[m - 3])
          {
            degree = m;
            return;
          }
      // A non-finite argument just propagates to the result; beyond 2^64 exp overflows anyway.
      if (std::isfinite(norm_X))
        n_squarings = static_cast<unsigned int>(
            std::min(64.0, std::ceil(std::log2(norm_X / exp_pade_theta[4]))));
    }

    // Gauss-Legendre / Pade approximation of log(I + X) for small X.
    template <typename Number>
    dealii::SymmetricTensor<2, 3, Number>
    pade_log_one_plus(const dealii::SymmetricTensor<2, 3, Number> &X, const GaussLegendreRule &rule)
    {
      dealii::SymmetricTensor<2, 3, Number> L;
      for (unsigned int k = 0; k < 6; ++k)
        L.access_raw_entry(k) = Number(0.0);
      for (unsigned int q = 0; q < rule.n_points; ++q)
        {
          const auto M = inverse_symmetric(plus_identity(scaled(rule.nodes[q], X), 1.0));
          L = linear_combination(1.0, L, rule.weights[q], commuting_product(X, M));
        }
      return L;
    }
  } // namespace internal

  // Principal square root of an SPD tensor by the Denman-Beavers iteration
  // Y <- (Y + Z^-1)/2, Z <- (Z + Y^-1)/2 from Y = A, Z = I (Y -> A^1/2, Z -> A^-1/2). It is
  // Newton's method in a stable coupled form; its derivative converges one iteration behind its
  // value, so one more iteration is taken after the value has converged.
  template <typename Number>
  dealii::SymmetricTensor<2, 3, Number> sqrt_spd(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    auto Y = A;
    auto Z = identity_symmetric<Number>();
    bool value_converged = false;
    for (unsigned int iteration = 0; iteration < 60; ++iteration)
      {
        const auto Y_inverse = inverse_symmetric(Y);
        const auto Y_new = linear_combination(0.5, Y, 0.5, inverse_symmetric(Z));
        Z = linear_combination(0.5, Z, 0.5, Y_inverse);
        double step = 0.0, size = 0.0;
        for (unsigned int k = 0; k < 6; ++k)
          {
            const double y = scalar_value(Y_new.access_raw_entry(k));
            step += (k < 3 ? 1.0 : 2.0) * std::pow(y - scalar_value(Y.access_raw_entry(k)), 2);
            size += (k < 3 ? 1.0 : 2.0) * y * y;
          }
        Y = Y_new;
        if (value_converged)
          break;
        // Quadratic convergence: a step of 1e-9 leaves an error of order 1e-18.
        if (step <= 1e-18 * size)
          value_converged = true;
      }
    return Y;
  }

  // exp(A) for symmetric A: exp(A) = exp(tr A / 3) exp(dev A); the deviatoric part is scaled by
  // 2^-s until a Pade approximant of degree <= 7 is accurate, then squared s times.
  template <typename Number>
  dealii::SymmetricTensor<2, 3, Number>
  exp_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    using std::exp;
    const Number mean = trace_symmetric(A) / 3.0;
    auto         X = plus_identity(A, -mean);
    unsigned int degree, n_squarings;
    internal::exp_degree_and_squarings(std::sqrt(scalar_value(norm_squared_symmetric(X))), degree,
                                       n_squarings);
    if (n_squarings > 0)
      X = scaled(std::ldexp(1.0, -static_cast<int>(n_squarings)), X);

    dealii::SymmetricTensor<2, 3, Number> V, U;
    internal::pade_exp_parts(X, degree, V, U);
    auto E = commuting_product(inverse_symmetric(linear_combination(1.0, V, -1.0, U)),
                               linear_combination(1.0, V, 1.0, U));
    for (unsigned int s = 0; s < n_squarings; ++s)
      E = commuting_product(E, E);
    return scaled(exp(mean), E);
  }

  // exp(A) - I for symmetric A, without the cancellation of forming exp(A) first, so that
  // small results (e.g. dev b_e = dev(exp(2 eps_e) - I) at elastic strains ~1e-3) keep full
  // relative accuracy: r_m - I = 2 (V - U)^-1 U for the Pade approximant, and
  // exp(2Y) - I = (exp(Y) - I)(exp(Y) - I + 2 I) for each squaring.
  template <typename Number>
  dealii::SymmetricTensor<2, 3, Number>
  expm1_symmetric(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    unsigned int degree, n_squarings;
    internal::exp_degree_and_squarings(std::sqrt(scalar_value(norm_squared_symmetric(A))), degree,
                                       n_squarings);
    const auto X = n_squarings > 0 ? scaled(std::ldexp(1.0, -static_cast<int>(n_squarings)), A) : A;

    dealii::SymmetricTensor<2, 3, Number> V, U;
    internal::pade_exp_parts(X, degree, V, U);
    auto E =
        commuting_product(inverse_symmetric(linear_combination(1.0, V, -1.0, U)), scaled(2.0, U));
    for (unsigned int s = 0; s < n_squarings; ++s)
      E = commuting_product(E, plus_identity(E, 2.0));
    return E;
  }

  // log(A) for symmetric positive definite A (inverse scaling and squaring). The volumetric
  // part is split off exactly, log A = (ln det A)/3 I + log(A / det(A)^(1/3)), so the trace of
  // the result is ln det A to round-off; the unimodular remainder is square-rooted k times
  // until |A_k - I| <= 0.30, and log A_k is approximated by the smallest adequate Pade degree.
  template <typename Number>
  dealii::SymmetricTensor<2, 3, Number> log_spd(const dealii::SymmetricTensor<2, 3, Number> &A)
  {
    using std::exp;
    using std::log;
    const Number log_scale = log(determinant_symmetric(A)) / 3.0;
    auto         A_k = scaled(exp(-log_scale), A);

    constexpr unsigned int n_rules = std::size(internal::log_pade_rules);
    const double           theta_max = internal::log_pade_rules[n_rules - 1].theta;
    unsigned int           n_roots = 0;
    double norm_X = std::sqrt(scalar_value(norm_squared_symmetric(plus_identity(A_k, -1.0))));
    while (norm_X > theta_max && n_roots < 40)
      {
        A_k = sqrt_spd(A_k);
        ++n_roots;
        norm_X = std::sqrt(scalar_value(norm_squared_symmetric(plus_identity(A_k, -1.0))));
      }

    unsigned int rule = n_rules - 1;
    for (unsigned int r = 0; r < n_rules; ++r)
      if (norm_X <= internal::log_pade_rules[r].theta)
        {
          rule = r;
          break;
        }
    const auto L =
        internal::pade_log_one_plus(plus_identity(A_k, -1.0), internal::log_pade_rules[rule]);
    return plus_identity(scaled(std::ldexp(1.0, static_cast<int>(n_roots)), L), log_scale);
  }
} // namespace indentsim::materials
