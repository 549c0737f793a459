#include "solver/FiniteStrainElement.h"

#include <deal.II/base/tensor.h>

#include <cmath>

namespace indentsim::solver
{
  using namespace dealii;

  ElementScratch::ElementScratch(const unsigned int n_dofs, const unsigned int n_q_points)
    : n_dofs(n_dofs)
    , n_q_points(n_q_points)
    , G(n_q_points, std::vector<Tensor<2, 3>>(n_dofs))
    , G0(n_dofs)
    , JxW(n_q_points)
    , B(n_dofs)
    , A_B(n_dofs)
    , H(n_dofs)
    , H0(n_dofs)
    , c(n_dofs)
    , g(n_dofs)
  {}

  namespace
  {
    Tensor<2, 3> deformation_gradient(const std::vector<Tensor<2, 3>> &G,
                                      const Vector<double>            &u_local)
    {
      Tensor<2, 3> F = unit_symmetric_tensor<3>();
      for (unsigned int a = 0; a < G.size(); ++a)
        F += u_local[a] * G[a];
      return F;
    }

    // tr(X Y) without forming the product.
    double trace_of_product(const Tensor<2, 3> &X, const Tensor<2, 3> &Y)
    {
      double sum = 0;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          sum += X[i][j] * Y[j][i];
      return sum;
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
    const unsigned int n_dofs = s.n_dofs;
    const unsigned int n_state = material.n_state_variables();
    residual = 0;
    if (tangent)
      *tangent = 0;

    Tensor<2, 3> F0_inv;
    double       J0 = 1;
    if (use_f_bar)
      {
        const Tensor<2, 3> F0 = deformation_gradient(s.G0, u_local);
        J0 = determinant(F0);
        if (!(J0 > 0) || !std::isfinite(J0))
          return materials::UpdateStatus::invalid_deformation;
        F0_inv = invert(F0);
        for (unsigned int a = 0; a < n_dofs; ++a)
          s.H0[a] = F0_inv * s.G0[a];
      }

    materials::MaterialPointResponse response;
    for (unsigned int q = 0; q < s.n_q_points; ++q)
      {
        const std::vector<Tensor<2, 3>> &G = s.G[q];
        const Tensor<2, 3>               F = deformation_gradient(G, u_local);
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

        // B_a = dF_bar/du_a.
        if (use_f_bar)
          {
            const Tensor<2, 3> F_inv = invert(F);
            for (unsigned int a = 0; a < n_dofs; ++a)
              {
                s.H[a] = F_inv * G[a];
                s.c[a] = trace(s.H0[a]) - trace(s.H[a]);
                s.B[a] = theta * (G[a] + (s.c[a] / 3.) * F);
              }
          }
        else
          for (unsigned int a = 0; a < n_dofs; ++a)
            s.B[a] = G[a];

        const double w = s.JxW[q];
        for (unsigned int a = 0; a < n_dofs; ++a)
          residual[a] += scalar_product(P, s.B[a]) * w;

        if (!tangent)
          continue;

        // Material part B_a : A : B_b.
        for (unsigned int b = 0; b < n_dofs; ++b)
          s.A_B[b] = double_contract<2, 0, 3, 1>(response.dP_dF, s.B[b]);
        for (unsigned int a = 0; a < n_dofs; ++a)
          for (unsigned int b = 0; b < n_dofs; ++b)
            (*tangent)(a, b) += scalar_product(s.B[a], s.A_B[b]) * w;

        // Geometric part of F-bar: P : dB_a/du_b
        //   = theta/3 [c_b g_a + c_a g_b + p/3 c_a c_b + p d_ab],
        // with g_a = P : G_a, p = P : F and
        //   d_ab = tr(F^-1 G_b F^-1 G_a) - tr(F_0^-1 G0_b F_0^-1 G0_a).
        if (use_f_bar)
          {
            const double p = scalar_product(P, F);
            for (unsigned int a = 0; a < n_dofs; ++a)
              s.g[a] = scalar_product(P, G[a]);
            const double factor = theta / 3. * w;
            for (unsigned int a = 0; a < n_dofs; ++a)
              for (unsigned int b = 0; b < n_dofs; ++b)
                {
                  const double d_ab = trace_of_product(s.H[b], s.H[a]) -
                                      trace_of_product(s.H0[b], s.H0[a]);
                  (*tangent)(a, b) += factor * (s.c[b] * s.g[a] + s.c[a] * s.g[b] +
                                                p / 3. * s.c[a] * s.c[b] + p * d_ab);
                }
          }
      }
    return materials::UpdateStatus::success;
  }
} // namespace indentsim::solver
