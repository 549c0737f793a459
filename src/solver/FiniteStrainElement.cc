#include "solver/FiniteStrainElement.h"

#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>

namespace indentsim::solver
{
  using namespace dealii;

  ElementScratch::ElementScratch(const unsigned int n_nodes, const unsigned int n_q_points)
    : n_nodes(n_nodes)
    , n_dofs(3 * n_nodes)
    , n_q_points(n_q_points)
    , grad(n_q_points, std::vector<Tensor<1, 3>>(n_nodes))
    , grad0(n_nodes)
    , JxW(n_q_points)
    , h(n_nodes)
    , h0(n_nodes)
    , Pg(n_nodes)
    , AFg(n_nodes)
    , FAg(n_nodes)
    , Ag(n_nodes)
    , c(3 * n_nodes)
    , beta(3 * n_nodes)
    , X(3 * n_nodes)
    , Y(3 * n_nodes)
    , K_symmetric(9 * n_nodes * n_nodes)
  {}

  Tensor<2, 3> deformation_gradient(const ElementScratch &s,
                                    const unsigned int    q,
                                    const Vector<double> &u_local)
  {
    const std::vector<Tensor<1, 3>> &g = q < s.n_q_points ? s.grad[q] : s.grad0;
    Tensor<2, 3>                     F = unit_symmetric_tensor<3>();
    for (unsigned int i = 0; i < s.n_nodes; ++i)
      for (unsigned int k = 0; k < 3; ++k)
        F[k] += u_local[3 * i + k] * g[i];
    return F;
  }

  namespace
  {
    // True if A_cJdL = A_dLcJ to round-off (1e-12 of the largest entry): a hyperelastic point
    // (every elastic step) has a major-symmetric tangent, a J2 point returning with the Cauchy
    // yield measure or a crystal point generally has not.
    bool has_major_symmetry(const Tensor<4, 3> &A)
    {
      double largest = 0, asymmetry = 0;
      for (unsigned int c = 0; c < 3; ++c)
        for (unsigned int J = 0; J < 3; ++J)
          for (unsigned int d = 0; d < 3; ++d)
            for (unsigned int L = 0; L < 3; ++L)
              {
                largest = std::max(largest, std::abs(A[c][J][d][L]));
                asymmetry = std::max(asymmetry, std::abs(A[c][J][d][L] - A[d][L][c][J]));
              }
      return asymmetry <= 1e-12 * largest;
    }
  } // namespace

  materials::UpdateStatus
  element_residual_and_tangent(const materials::MaterialModel &material,
                               const bool                      use_f_bar,
                               const Vector<double>           &u_local,
                               std::span<const double>         state_old,
                               std::span<double>               state_new,
                               ElementScratch                 &s,
                               Vector<double>                 &residual,
                               FullMatrix<double>             *tangent,
                               std::vector<Tensor<2, 3>>      *cauchy_stress)
  {
    const unsigned int n_nodes = s.n_nodes;
    const unsigned int n_state = material.n_state_variables();
    residual = 0;
    bool any_symmetric_point = false;
    if (tangent)
      {
        *tangent = 0;
        std::fill(s.K_symmetric.begin(), s.K_symmetric.end(), 0.0);
      }

    double J0 = 1;
    if (use_f_bar)
      {
        const Tensor<2, 3> F0 = deformation_gradient(s, s.n_q_points, u_local);
        J0 = determinant(F0);
        if (!(J0 > 0) || !std::isfinite(J0))
          return materials::UpdateStatus::invalid_deformation;
        const Tensor<2, 3> F0_inv_T = transpose(invert(F0));
        for (unsigned int i = 0; i < n_nodes; ++i)
          s.h0[i] = F0_inv_T * s.grad0[i]; // (F_0^-T g0_i)_c = tr(F_0^-1 G0_a)
      }

    materials::MaterialPointResponse response;
    for (unsigned int q = 0; q < s.n_q_points; ++q)
      {
        const std::vector<Tensor<1, 3>> &g = s.grad[q];
        const Tensor<2, 3>               F = deformation_gradient(s, q, u_local);
        const double                     J = determinant(F);
        if (!(J > 0) || !std::isfinite(J))
          return materials::UpdateStatus::invalid_deformation;

        const double       theta = use_f_bar ? std::cbrt(J0 / J) : 1.0;
        const Tensor<2, 3> F_bar = theta * F;

        const auto status = material.update(F_bar,
                                            state_old.subspan(q * n_state, n_state),
                                            response,
                                            state_new.subspan(q * n_state, n_state),
                                            tangent != nullptr);
        if (status != materials::UpdateStatus::success)
          return status;
        const Tensor<2, 3> &P = response.P;
        if (cauchy_stress)
          (*cauchy_stress)[q] = response.tau / determinant(F_bar);

        // c_a and beta_a = theta c_a / 3, so that B_a = theta G_a + beta_a F.
        if (use_f_bar)
          {
            const Tensor<2, 3> F_inv_T = transpose(invert(F));
            for (unsigned int i = 0; i < n_nodes; ++i)
              {
                s.h[i] = F_inv_T * g[i];
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    s.c[3 * i + c] = s.h0[i][c] - s.h[i][c];
                    s.beta[3 * i + c] = theta * s.c[3 * i + c] / 3.;
                  }
              }
          }
        else
          std::fill(s.beta.begin(), s.beta.end(), 0.0);

        // Residual P : B_a = theta (P g_i)_c + beta_a P : F.
        const double w = s.JxW[q];
        const double p = scalar_product(P, F);
        for (unsigned int i = 0; i < n_nodes; ++i)
          {
            s.Pg[i] = P * g[i];
            for (unsigned int c = 0; c < 3; ++c)
              residual[3 * i + c] += (theta * s.Pg[i][c] + s.beta[3 * i + c] * p) * w;
          }

        if (!tangent)
          continue;

        // Material part B_a : A : B_b with B_a = theta E_a + beta_a F, E_a = e_c (x) g_i:
        //   theta^2 g_iJ A_cJdL g_jL + theta beta_b (A:F g_i)_c + theta beta_a (F:A g_j)_d
        //   + beta_a beta_b F:A:F.
        const Tensor<4, 3> &A = response.dP_dF;
        for (unsigned int i = 0; i < n_nodes; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            for (unsigned int d = 0; d < 3; ++d)
              for (unsigned int L = 0; L < 3; ++L)
                s.Ag[i][c][d][L] =
                  g[i][0] * A[c][0][d][L] + g[i][1] * A[c][1][d][L] + g[i][2] * A[c][2][d][L];
        double FAF = 0;
        if (use_f_bar)
          {
            Tensor<2, 3> AF, FA; // (A:F)_cJ = A_cJdL F_dL, (F:A)_dL = F_cJ A_cJdL
            for (unsigned int c = 0; c < 3; ++c)
              for (unsigned int J_ = 0; J_ < 3; ++J_)
                for (unsigned int d = 0; d < 3; ++d)
                  for (unsigned int L = 0; L < 3; ++L)
                    {
                      AF[c][J_] += A[c][J_][d][L] * F[d][L];
                      FA[d][L] += F[c][J_] * A[c][J_][d][L];
                    }
            FAF = scalar_product(F, AF);
            for (unsigned int i = 0; i < n_nodes; ++i)
              {
                s.AFg[i] = AF * g[i];
                s.FAg[i] = FA * g[i];
              }
          }

        // Geometric part of F-bar: P : dB_a/du_b
        //   = theta/3 [c_b g_a + c_a g_b + p/3 c_a c_b + p d_ab],
        // with g_a = P : G_a = (P g_i)_c, p = P : F and
        //   d_ab = tr(F^-1 G_b F^-1 G_a) - tr(F_0^-1 G0_b F_0^-1 G0_a)
        //        = (F^-T g_i)_d (F^-T g_j)_c - (F_0^-T g0_i)_d (F_0^-T g0_j)_c.
        // All F-bar terms but d_ab are sums of products x_a y_b; they are gathered into
        // X_a . Y_b with four entries each:
        //   X_a = [theta (A:F g_i)_c + F:A:F beta_a, theta beta_a, geo (g_a + p/3 c_a), geo c_a],
        //   Y_b = [beta_b, (F:A g_j)_d, c_b, g_b],  geo = theta / 3.
        //
        // With a major-symmetric A every term is symmetric in (a, b) (then A:F = F:A), so a
        // symmetric point adds only the node blocks j >= i, into K_symmetric, mirrored after
        // the quadrature loop: 36 of the 64 blocks, most points of an indentation being elastic.
        const bool         symmetric_point = has_major_symmetry(A);
        any_symmetric_point = any_symmetric_point || symmetric_point;
        const unsigned int n_dofs = s.n_dofs;
        double *const      K = symmetric_point ? s.K_symmetric.data() : &(*tangent)(0, 0);
        const double weighted_theta2 = theta * theta * w;
        if (!use_f_bar)
          {
            for (unsigned int i = 0; i < n_nodes; ++i)
              for (unsigned int j = symmetric_point ? i : 0; j < n_nodes; ++j)
                for (unsigned int c = 0; c < 3; ++c)
                  for (unsigned int d = 0; d < 3; ++d)
                    K[(3 * i + c) * n_dofs + 3 * j + d] +=
                      weighted_theta2 * (s.Ag[i][c][d] * g[j]);
            continue;
          }
        const double geometric = theta / 3.;
        for (unsigned int i = 0; i < n_nodes; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            {
              const unsigned int a = 3 * i + c;
              s.X[a] = {{w * (theta * s.AFg[i][c] + FAF * s.beta[a]),
                         w * theta * s.beta[a],
                         w * geometric * (s.Pg[i][c] + p / 3. * s.c[a]),
                         w * geometric * s.c[a]}};
              s.Y[a] = {{s.beta[a], s.FAg[i][c], s.c[a], s.Pg[i][c]}};
            }
        const double weighted_geometric_p = w * geometric * p;
        for (unsigned int i = 0; i < n_nodes; ++i)
          for (unsigned int j = symmetric_point ? i : 0; j < n_nodes; ++j)
            for (unsigned int c = 0; c < 3; ++c)
              {
                const unsigned int a = 3 * i + c;
                const auto        &X = s.X[a];
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    const unsigned int b = 3 * j + d;
                    const auto        &Y = s.Y[b];
                    K[a * n_dofs + b] +=
                      weighted_theta2 * (s.Ag[i][c][d] * g[j]) + X[0] * Y[0] + X[1] * Y[1] +
                      X[2] * Y[2] + X[3] * Y[3] +
                      weighted_geometric_p *
                        (s.h[i][d] * s.h[j][c] - s.h0[i][d] * s.h0[j][c]);
                  }
              }
      }
    if (tangent && any_symmetric_point)
      {
        // The symmetric points' upper blocks, and their mirror images below the diagonal.
        const unsigned int n_dofs = s.n_dofs;
        for (unsigned int i = 0; i < n_nodes; ++i)
          for (unsigned int j = i; j < n_nodes; ++j)
            for (unsigned int c = 0; c < 3; ++c)
              for (unsigned int d = 0; d < 3; ++d)
                {
                  const unsigned int a = 3 * i + c, b = 3 * j + d;
                  const double       value = s.K_symmetric[a * n_dofs + b];
                  (*tangent)(a, b) += value;
                  if (j != i)
                    (*tangent)(b, a) += value;
                }
      }
    return materials::UpdateStatus::success;
  }
} // namespace indentsim::solver
