#include "fem/FiniteStrainElement.h"

#include "fem/TangentRow.h"

#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace indentsim::fem
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
    , c(3 * n_nodes)
    , beta(3 * n_nodes)
    , K_columns_by_component(9 * n_nodes * n_nodes)
  {
  }

  Tensor<2, 3> deformation_gradient(const ElementScratch &s, const unsigned int q,
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
    // One row segment K_a(d, j = 0..7) of the tangent over the eight nodes j.
    using tangent_row::load, tangent_row::Row, tangent_row::store;

    // Adds one quadrature point's tangent to K (24 x 24, row a = 3 i + c, column d 8 + j):
    //   K_a(dj) += sum_L P_adL g_jL                                    (material, theta^2 w)
    //             + sum_k X_ak Y_k(dj) + wp (h_id h_jc - h0_id h0_jc)   (F-bar)
    // Columns are ordered by component, so that a row segment over the eight nodes j is one
    // vector. For each d the vectors shared by all 24 rows (g_L, Y_k(d), h_c, h0_c: 15) stay in
    // registers (AVX-512 has 32) while the rows stream through: per row segment one load, one
    // store and 9 (12 with F-bar) fused multiply-adds. The clones are chosen at load time.
    [[gnu::target_clones("arch=x86-64-v4", "arch=haswell", "default")]] void
    add_point_tangent(const PointTangentTerms &t, double *__restrict K)
    {
      for (unsigned int d = 0; d < 3; ++d)
        {
          const Row g0 = load(t.gT[0]), g1 = load(t.gT[1]), g2 = load(t.gT[2]);
          if (!t.f_bar)
            {
              for (unsigned int a = 0; a < 24; ++a)
                {
                  double *row = K + a * 24 + d * 8;
                  store(row, load(row) + t.P[a][d][0] * g0 + t.P[a][d][1] * g1 + t.P[a][d][2] * g2);
                }
              continue;
            }
          const Row y0 = load(t.YT[0][d]), y1 = load(t.YT[1][d]), y2 = load(t.YT[2][d]),
                    y3 = load(t.YT[3][d]);
          const Row hc[3] = {load(t.hT[0]), load(t.hT[1]), load(t.hT[2])};
          const Row h0c[3] = {load(t.h0T[0]), load(t.h0T[1]), load(t.h0T[2])};
          for (unsigned int i = 0; i < 8; ++i)
            {
              const double gh = t.weighted_geometric_p * t.h[i][d],
                           gh0 = t.weighted_geometric_p * t.h0[i][d];
              for (unsigned int c = 0; c < 3; ++c)
                {
                  const unsigned int a = 3 * i + c;
                  double            *row = K + a * 24 + d * 8;
                  store(row, load(row) + t.P[a][d][0] * g0 + t.P[a][d][1] * g1 + t.P[a][d][2] * g2 +
                                 t.X[a][0] * y0 + t.X[a][1] * y1 + t.X[a][2] * y2 + t.X[a][3] * y3 +
                                 gh * hc[c] - gh0 * h0c[c]);
                }
            }
        }
    }
    // t.P[3 i + c][d][L] = scale sum_J g_iJ A_cJdL: for each row a nine contiguous values,
    // a combination of the three nine-value blocks A_cJ.. (vectorized over them).
    [[gnu::target_clones("arch=x86-64-v4", "arch=haswell", "default")]] void
    material_rows(const Tensor<4, 3> &A, const double scale, PointTangentTerms &t)
    {
      double blocks[3][3][9]; // scale A_cJdL as [c][J][3 d + L]
      for (unsigned int c = 0; c < 3; ++c)
        for (unsigned int J = 0; J < 3; ++J)
          for (unsigned int d = 0; d < 3; ++d)
            for (unsigned int L = 0; L < 3; ++L)
              blocks[c][J][3 * d + L] = scale * A[c][J][d][L];
      for (unsigned int i = 0; i < 8; ++i)
        {
          const double g0 = t.gT[0][i], g1 = t.gT[1][i], g2 = t.gT[2][i];
          for (unsigned int c = 0; c < 3; ++c)
            {
              double *__restrict row = &t.P[3 * i + c][0][0];
              for (unsigned int k = 0; k < 9; ++k)
                row[k] = g0 * blocks[c][0][k] + g1 * blocks[c][1][k] + g2 * blocks[c][2][k];
            }
        }
    }
  } // namespace

  materials::UpdateStatus
  element_residual_and_tangent(const materials::MaterialModel &material, const bool use_f_bar,
                               const Vector<double> &u_local, std::span<const double> state_old,
                               std::span<double> state_new, ElementScratch &s,
                               Vector<double> &residual, FullMatrix<double> *tangent,
                               std::vector<Tensor<2, 3>> *cauchy_stress)
  {
    const unsigned int n_nodes = s.n_nodes;
    const unsigned int n_state = material.n_state_variables();
    residual = 0;
    if (n_nodes != 8)
      throw std::invalid_argument("element_residual_and_tangent: hexahedra with 8 nodes only");
    if (tangent)
      std::fill(s.K_columns_by_component.begin(), s.K_columns_by_component.end(), 0.0);

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

        const auto status =
            material.update(F_bar, state_old.subspan(q * n_state, n_state), response,
                            state_new.subspan(q * n_state, n_state), tangent != nullptr);
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
        PointTangentTerms  &t = s.point;
        for (unsigned int j = 0; j < n_nodes; ++j)
          for (unsigned int L = 0; L < 3; ++L)
            t.gT[L][j] = g[j][L];
        material_rows(A, theta * theta * w, t);
        t.f_bar = use_f_bar;
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
            const double FAF = scalar_product(F, AF);
            // Geometric part of F-bar: P : dB_a/du_b
            //   = theta/3 [c_b g_a + c_a g_b + p/3 c_a c_b + p d_ab],
            // with g_a = P : G_a = (P g_i)_c, p = P : F and
            //   d_ab = tr(F^-1 G_b F^-1 G_a) - tr(F_0^-1 G0_b F_0^-1 G0_a)
            //        = (F^-T g_i)_d (F^-T g_j)_c - (F_0^-T g0_i)_d (F_0^-T g0_j)_c.
            // All F-bar terms but d_ab are sums of products x_a y_b, gathered into X_a . Y_b:
            //   X_a = [theta (A:F g_i)_c + F:A:F beta_a, theta beta_a, geo (g_a + p/3 c_a), geo c_a],
            //   Y_b = [beta_b, (F:A g_j)_d, c_b, g_b],  geo = theta / 3.
            const double geometric = theta / 3.;
            for (unsigned int i = 0; i < n_nodes; ++i)
              {
                const Tensor<1, 3> AFg = AF * g[i], FAg = FA * g[i];
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    const unsigned int a = 3 * i + c;
                    t.X[a][0] = w * (theta * AFg[c] + FAF * s.beta[a]);
                    t.X[a][1] = w * theta * s.beta[a];
                    t.X[a][2] = w * geometric * (s.Pg[i][c] + p / 3. * s.c[a]);
                    t.X[a][3] = w * geometric * s.c[a];
                    t.YT[0][c][i] = s.beta[a];
                    t.YT[1][c][i] = FAg[c];
                    t.YT[2][c][i] = s.c[a];
                    t.YT[3][c][i] = s.Pg[i][c];
                    t.h[i][c] = s.h[i][c];
                    t.h0[i][c] = s.h0[i][c];
                    t.hT[c][i] = s.h[i][c];
                    t.h0T[c][i] = s.h0[i][c];
                  }
              }
            t.weighted_geometric_p = w * geometric * p;
          }
        add_point_tangent(t, s.K_columns_by_component.data());
      }
    if (tangent)
      {
        // Columns back from component-major (d 8 + j) to deal.II's node-major (3 j + d) order.
        const double *K = s.K_columns_by_component.data();
        for (unsigned int a = 0; a < 24; ++a)
          for (unsigned int d = 0; d < 3; ++d)
            for (unsigned int j = 0; j < 8; ++j)
              (*tangent)(a, 3 * j + d) = K[a * 24 + d * 8 + j];
      }
    return materials::UpdateStatus::success;
  }
} // namespace indentsim::fem
