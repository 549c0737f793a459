#include "fem/AxisymmetricElement.h"

#include "fem/TangentRow.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace indentsim::fem
{
  using namespace dealii;

  namespace
  {
    // Components of the 3x3 tensors: (r, theta, z).
    constexpr unsigned int r_ = 0, theta_ = 1, z_ = 2;

    unsigned int gauss_points_per_direction(const unsigned int n_q_points)
    {
      const auto k = static_cast<unsigned int>(std::lround(std::sqrt(double(n_q_points))));
      if (n_q_points == 0 || k * k != n_q_points)
        throw std::invalid_argument("AxisymmetricScratch: n_q_points must be k^2 (k x k Gauss "
                                    "points), not " +
                                    std::to_string(n_q_points));
      return k;
    }
  } // namespace

  AxisymmetricScratch::AxisymmetricScratch(const unsigned int n_q_points)
    : n_q_points(n_q_points)
    , values(n_q_points)
    , grad(n_q_points)
    , radius(n_q_points)
    , dV(n_q_points)
    , reference_values(n_q_points)
    , reference_grad(n_q_points)
    , F(n_q_points)
    , G(n_q_points)
    , H(n_q_points)
    , trace(n_q_points)
  {
    const QGauss<2> gauss(gauss_points_per_direction(n_q_points));
    const FE_Q<2>   bilinear(1);
    const Point<2>  centre(0.5, 0.5);
    for (unsigned int i = 0; i < n_nodes; ++i)
      {
        for (unsigned int q = 0; q < n_q_points; ++q)
          {
            reference_values[q][i] = bilinear.shape_value(i, gauss.point(q));
            reference_grad[q][i] = bilinear.shape_grad(i, gauss.point(q));
          }
        reference_values0[i] = bilinear.shape_value(i, centre);
        reference_grad0[i] = bilinear.shape_grad(i, centre);
      }
    weights = gauss.get_weights();
  }

  void require_axisymmetric_dof_layout(const FiniteElement<2> &fe)
  {
    bool ordered = fe.n_components() == 2 && fe.n_dofs_per_cell() == AxisymmetricScratch::n_dofs &&
                   fe.n_dofs_per_vertex() == 2;
    for (unsigned int a = 0; ordered && a < fe.n_dofs_per_cell(); ++a)
      ordered = fe.system_to_component_index(a) == std::make_pair(a % 2, a / 2);
    if (!ordered)
      throw std::invalid_argument("axisymmetric element: the displacement element must be "
                                  "FESystem(FE_Q<2>(1), 2) with node-wise dof numbering "
                                  "(a = 2 i + c), not " +
                                  fe.get_name());
  }

  namespace
  {
    // The bilinear map X(xi) = sum_i X_i N_i(xi) at one point: R = X_r, grad_X N_i =
    // J^-T grad_xi N_i with J = dX/dxi = sum_i X_i (x) grad_xi N_i; returns det J.
    double map_point(const std::array<Point<2>, 4> &vertices, const std::array<double, 4> &N,
                     const std::array<Tensor<1, 2>, 4> &reference, std::array<double, 4> &values,
                     std::array<Tensor<1, 2>, 4> &gradients, double &radius)
    {
      Tensor<2, 2> J;
      radius = 0;
      for (unsigned int i = 0; i < 4; ++i)
        {
          radius += N[i] * vertices[i][0];
          for (unsigned int k = 0; k < 2; ++k)
            J[k] += vertices[i][k] * reference[i];
        }
      const double       det = determinant(J);
      const Tensor<2, 2> J_inv_T = transpose(invert(J));
      for (unsigned int i = 0; i < 4; ++i)
        {
          values[i] = N[i];
          gradients[i] = J_inv_T * reference[i];
        }
      return det;
    }

    [[noreturn]] void bad_cell(const std::array<Point<2>, 4> &vertices, const std::string &why)
    {
      std::ostringstream message;
      message << "reinit_axisymmetric: the cell with vertices (R, Z) [um]";
      for (const Point<2> &v : vertices)
        message << " (" << v[0] << ", " << v[1] << ")";
      message << " " << why;
      throw std::invalid_argument(message.str());
    }
  } // namespace

  void reinit_axisymmetric(AxisymmetricScratch &s, const std::array<Point<2>, 4> &vertices)
  {
    for (unsigned int q = 0; q <= s.n_q_points; ++q) // q = n_q_points: the centre
      {
        const bool   centre = q == s.n_q_points;
        double      &R = centre ? s.radius0 : s.radius[q];
        const double det =
            map_point(vertices, centre ? s.reference_values0 : s.reference_values[q],
                      centre ? s.reference_grad0 : s.reference_grad[q],
                      centre ? s.values0 : s.values[q], centre ? s.grad0 : s.grad[q], R);
        if (!(det > 0))
          bad_cell(vertices, "is not mapped orientation-preserving (det dX/dxi <= 0)");
        if (!(R > 0))
          bad_cell(vertices, "has a Gauss point or its centre at R <= 0 (a vertex at R < 0?)");
        if (!centre)
          s.dV[q] = 2 * numbers::PI * R * det * s.weights[q]; // the full ring
      }
  }

  namespace
  {
    // MeridianTensor entries (rr, rz, zr, zz, tt) and their places in the 3x3 tensor.
    constexpr unsigned int rr = 0, rz = 1, zr = 2, zz = 3, tt = 4;

    // A row over the eight dofs b of an element (a row of the 8 x 8 tangent).
    using tangent_row::load, tangent_row::Row, tangent_row::store;

    // The rows over b of (F^-1 G_b) with rz and zr exchanged, so that
    // tr(H_b H_a) = sum_k (H_a)_k rows[k][b].
    void swapped_rows(const std::array<MeridianTensor, 8> &H, double (&rows)[5][8])
    {
      constexpr unsigned int swap[5] = {rr, zr, rz, zz, tt};
      for (unsigned int b = 0; b < 8; ++b)
        for (unsigned int k = 0; k < 5; ++k)
          rows[k][b] = H[b][swap[k]];
    }
    constexpr std::array<std::pair<unsigned int, unsigned int>, 5> place = {
        {{r_, r_}, {r_, z_}, {z_, r_}, {z_, z_}, {theta_, theta_}}};

    // F at Gauss point q (q = n_q_points: the centre), as MeridianTensor.
    MeridianTensor deformation_gradient(const AxisymmetricScratch &s, const unsigned int q,
                                        const Vector<double> &u_local)
    {
      const bool     centre = q == s.n_q_points;
      const auto    &N = centre ? s.values0 : s.values[q];
      const auto    &g = centre ? s.grad0 : s.grad[q];
      const double   R = centre ? s.radius0 : s.radius[q];
      MeridianTensor F = {{1, 0, 0, 1, 1}};
      double         u_r = 0;
      for (unsigned int i = 0; i < AxisymmetricScratch::n_nodes; ++i)
        {
          const double ur_i = u_local[2 * i], uz_i = u_local[2 * i + 1];
          u_r += N[i] * ur_i;
          F[rr] += ur_i * g[i][0];
          F[rz] += ur_i * g[i][1];
          F[zr] += uz_i * g[i][0];
          F[zz] += uz_i * g[i][1];
        }
      F[tt] += u_r / R; // hoop stretch 1 + u_r/R
      return F;
    }

    Tensor<2, 3> full_tensor(const MeridianTensor &X)
    {
      Tensor<2, 3> full;
      for (unsigned int k = 0; k < 5; ++k)
        full[place[k].first][place[k].second] = X[k];
      return full;
    }

    // G_a = dF/du_a of dof a = 2 i + c at Gauss point q (q = n_q_points: the centre).
    MeridianTensor dof_gradient(const AxisymmetricScratch &s, const unsigned int q,
                                const unsigned int a)
    {
      const bool         centre = q == s.n_q_points;
      const auto        &g = (centre ? s.grad0 : s.grad[q])[a / 2];
      const unsigned int i = a / 2;
      if (a % 2 == 1)
        return {{0, 0, g[0], g[1], 0}};
      const double N_over_R = centre ? s.values0[i] / s.radius0 : s.values[q][i] / s.radius[q];
      return {{g[0], g[1], 0, 0, N_over_R}};
    }

    // J = det F of the block form; the in-plane part and the hoop stretch must be positive on
    // their own (J > 0 alone would let a negative hoop stretch and a folded (r, z) section
    // pass together).
    double in_plane_determinant(const MeridianTensor &X)
    {
      return X[rr] * X[zz] - X[rz] * X[zr];
    }
    double determinant(const MeridianTensor &X)
    {
      return in_plane_determinant(X) * X[tt];
    }
    bool admissible(const MeridianTensor &F)
    {
      const double in_plane = in_plane_determinant(F);
      return F[tt] > 0 && in_plane > 0 && std::isfinite(F[tt]) && std::isfinite(in_plane);
    }

    MeridianTensor invert(const MeridianTensor &X)
    {
      const double d = in_plane_determinant(X);
      return {{X[zz] / d, -X[rz] / d, -X[zr] / d, X[rr] / d, 1 / X[tt]}};
    }

    // X Y.
    MeridianTensor product(const MeridianTensor &X, const MeridianTensor &Y)
    {
      return {{X[rr] * Y[rr] + X[rz] * Y[zr], X[rr] * Y[rz] + X[rz] * Y[zz],
               X[zr] * Y[rr] + X[zz] * Y[zr], X[zr] * Y[rz] + X[zz] * Y[zz], X[tt] * Y[tt]}};
    }

    double trace(const MeridianTensor &X)
    {
      return X[rr] + X[zz] + X[tt];
    }

    // tr(X Y).
    double trace_of_product(const MeridianTensor &X, const MeridianTensor &Y)
    {
      return X[rr] * Y[rr] + X[rz] * Y[zr] + X[zr] * Y[rz] + X[zz] * Y[zz] + X[tt] * Y[tt];
    }

    // X : Y = X_ij Y_ij.
    double scalar_product(const MeridianTensor &X, const MeridianTensor &Y)
    {
      double sum = 0;
      for (unsigned int k = 0; k < 5; ++k)
        sum += X[k] * Y[k];
      return sum;
    }

    // The block entries of a 3x3 tensor (the stress P: its other entries, zero for an isotropic
    // material under an axisymmetric F, would meet only zeros of the block tensors B_a, G_a, F
    // it is contracted with).
    MeridianTensor block_entries(const Tensor<2, 3> &X)
    {
      MeridianTensor block;
      for (unsigned int k = 0; k < 5; ++k)
        block[k] = X[place[k].first][place[k].second];
      return block;
    }

    // The 5 x 5 block of A = dP/dF that maps block tensors to the block entries of A : X.
    std::array<MeridianTensor, 5> block_entries(const Tensor<4, 3> &A)
    {
      std::array<MeridianTensor, 5> block;
      for (unsigned int k = 0; k < 5; ++k)
        for (unsigned int l = 0; l < 5; ++l)
          block[k][l] = A[place[k].first][place[k].second][place[l].first][place[l].second];
      return block;
    }
  } // namespace

  Tensor<2, 3> axisymmetric_deformation_gradient(const AxisymmetricScratch &s, const unsigned int q,
                                                 const Vector<double> &u_local)
  {
    return full_tensor(deformation_gradient(s, q, u_local));
  }

  namespace
  {
    // J_0 at the element centre: d ln J_0/du_a = tr(F_0^-1 G0_a),
    // d^2 ln J_0/du_a du_b = -tr(F_0^-1 G0_b F_0^-1 G0_a). Returns J_0 (0 if inadmissible).
    double centre_dilatation(AxisymmetricScratch &s, const Vector<double> &u_local)
    {
      const MeridianTensor F0 = deformation_gradient(s, s.n_q_points, u_local);
      if (!admissible(F0))
        return 0;
      const MeridianTensor                                    F0_inv = invert(F0);
      std::array<MeridianTensor, AxisymmetricScratch::n_dofs> H0; // F_0^-1 G0_a
      for (unsigned int a = 0; a < AxisymmetricScratch::n_dofs; ++a)
        {
          H0[a] = product(F0_inv, dof_gradient(s, s.n_q_points, a));
          s.dlnJ0[a] = trace(H0[a]);
        }
      for (unsigned int a = 0; a < AxisymmetricScratch::n_dofs; ++a)
        for (unsigned int b = 0; b < AxisymmetricScratch::n_dofs; ++b)
          s.d2lnJ0[a][b] = -trace_of_product(H0[b], H0[a]);
      return determinant(F0);
    }

    // J_0 = J_bar = sum_q J_q dV_q / V (Nagtegaal, Parks and Rice 1974), with
    //   dJ_q/du_a = J_q tr(F_q^-1 G_a),
    //   d^2 J_q/du_a du_b = J_q [tr(F_q^-1 G_a) tr(F_q^-1 G_b) - tr(F_q^-1 G_b F_q^-1 G_a)],
    //   d ln J_bar/du_a = sum_q dV_q dJ_q/du_a / (V J_bar),
    //   d^2 ln J_bar/du_a du_b = sum_q dV_q d^2 J_q/du_a du_b / (V J_bar)
    //                            - d ln J_bar/du_a d ln J_bar/du_b.
    // Needs s.F, s.H and s.trace at every Gauss point (the kernel fills them).
    [[gnu::target_clones("arch=x86-64-v4", "arch=haswell", "default")]] double
    mean_dilatation(AxisymmetricScratch &s)
    {
      constexpr unsigned int n_dofs = AxisymmetricScratch::n_dofs;
      double                 volume = 0, weighted_J = 0;
      for (unsigned int q = 0; q < s.n_q_points; ++q)
        {
          volume += s.dV[q];
          weighted_J += s.dV[q] * determinant(s.F[q]);
        }
      const double J_bar = weighted_J / volume;
      s.dlnJ0.fill(0);
      for (auto &row : s.d2lnJ0)
        row.fill(0);
      for (unsigned int q = 0; q < s.n_q_points; ++q)
        {
          const double weight = s.dV[q] * determinant(s.F[q]) / weighted_J;
          const auto  &H = s.H[q];
          double       H_rows[5][n_dofs];
          swapped_rows(H, H_rows);
          const Row trace = load(s.trace[q].data());
          const Row Hb[5] = {load(H_rows[0]), load(H_rows[1]), load(H_rows[2]), load(H_rows[3]),
                             load(H_rows[4])};
          for (unsigned int a = 0; a < n_dofs; ++a)
            {
              const MeridianTensor &Ha = H[a];
              s.dlnJ0[a] += weight * s.trace[q][a];
              double *row = s.d2lnJ0[a].data();
              store(row, load(row) + weight * (s.trace[q][a] * trace -
                                               (Ha[0] * Hb[0] + Ha[1] * Hb[1] + Ha[2] * Hb[2] +
                                                Ha[3] * Hb[3] + Ha[4] * Hb[4])));
            }
        }
      const Row dlnJ0 = load(s.dlnJ0.data());
      for (unsigned int a = 0; a < n_dofs; ++a)
        store(s.d2lnJ0[a].data(), load(s.d2lnJ0[a].data()) - s.dlnJ0[a] * dlnJ0);
      // Exactly symmetric (the two triangles were summed in different orders).
      for (unsigned int a = 0; a < n_dofs; ++a)
        for (unsigned int b = 0; b < a; ++b)
          s.d2lnJ0[b][a] = s.d2lnJ0[a][b];
      return J_bar;
    }

    // Adds one Gauss point's K_ab = (B_a : A : B_b + P : dB_a/du_b) dV, the second term (F-bar
    // only) theta/3 [c_b P:G_a + c_a P:G_b + p/3 c_a c_b + p d_ab] with p = P : F and
    // d_ab = d^2 ln J_0/du_a du_b + tr(F^-1 G_b F^-1 G_a) (s.H[q][a] = F^-1 G_a), to the
    // row-major 8 x 8 matrix K. P: the block entries of response.P. Every term of row a is a
    // scalar of a times a row over b: the rows over b (A : B_b, the entries of B_b and of
    // F^-1 G_b, c_b, P : G_b) are formed once, and each row of K takes 5 (14 with F-bar)
    // multiply-adds of them. The clones are chosen at load time.
    [[gnu::target_clones("arch=x86-64-v4", "arch=haswell", "default")]] void
    add_point_tangent(const AxisymmetricScratch &s, const unsigned int q,
                      const materials::MaterialPointResponse &response, const MeridianTensor &P,
                      const double theta, const bool use_f_bar, double *__restrict K)
    {
      constexpr unsigned int n_dofs = AxisymmetricScratch::n_dofs;
      static_assert(n_dofs == 8, "one Row per row of the element tangent");
      const std::array<MeridianTensor, 5> A = block_entries(response.dP_dF);
      const double                        dV = s.dV[q];
      // (B_b)_k and (A : B_b)_k dV as rows over b.
      double B_rows[5][n_dofs];
      for (unsigned int b = 0; b < n_dofs; ++b)
        for (unsigned int k = 0; k < 5; ++k)
          B_rows[k][b] = s.B[b][k];
      Row AB[5];
      for (unsigned int k = 0; k < 5; ++k)
        {
          Row sum = A[k][0] * load(B_rows[0]);
          for (unsigned int l = 1; l < 5; ++l)
            sum += A[k][l] * load(B_rows[l]);
          AB[k] = dV * sum;
        }
      if (!use_f_bar)
        {
          for (unsigned int a = 0; a < n_dofs; ++a)
            {
              const MeridianTensor &Ba = s.B[a];
              store(K + 8 * a, load(K + 8 * a) + Ba[0] * AB[0] + Ba[1] * AB[1] + Ba[2] * AB[2] +
                                   Ba[3] * AB[3] + Ba[4] * AB[4]);
            }
          return;
        }
      const auto  &G = s.G[q], &H = s.H[q];
      const double p = scalar_product(P, s.F[q]);
      double       PG[n_dofs], H_rows[5][n_dofs];
      for (unsigned int b = 0; b < n_dofs; ++b)
        PG[b] = scalar_product(P, G[b]);
      swapped_rows(H, H_rows);
      const Row    c = load(s.c.data()), PG_row = load(PG);
      const Row    Hb[5] = {load(H_rows[0]), load(H_rows[1]), load(H_rows[2]), load(H_rows[3]),
                            load(H_rows[4])};
      const double f = theta / 3. * dV;
      for (unsigned int a = 0; a < n_dofs; ++a)
        {
          const MeridianTensor &Ba = s.B[a], &Ha = H[a];
          const Row d = load(s.d2lnJ0[a].data()) + Ha[0] * Hb[0] + Ha[1] * Hb[1] + Ha[2] * Hb[2] +
                        Ha[3] * Hb[3] + Ha[4] * Hb[4];
          const Row geometric =
              (f * PG[a]) * c + (f * s.c[a]) * PG_row + (f * p / 3. * s.c[a]) * c + (f * p) * d;
          store(K + 8 * a, load(K + 8 * a) + Ba[0] * AB[0] + Ba[1] * AB[1] + Ba[2] * AB[2] +
                               Ba[3] * AB[3] + Ba[4] * AB[4] + geometric);
        }
    }
  } // namespace

  materials::UpdateStatus axisymmetric_element_residual_and_tangent(
      const materials::MaterialModel &material, const bool use_f_bar, const Vector<double> &u_local,
      std::span<const double> state_old, std::span<double> state_new, AxisymmetricScratch &s,
      Vector<double> &residual, FullMatrix<double> *tangent,
      std::vector<Tensor<2, 3>> *cauchy_stress)
  {
    constexpr unsigned int n_dofs = AxisymmetricScratch::n_dofs;
    const unsigned int     n_state = material.n_state_variables();
    AssertDimension(u_local.size(), n_dofs);
    AssertDimension(residual.size(), n_dofs);
    Assert(!tangent || (tangent->m() == n_dofs && tangent->n() == n_dofs),
           ExcMessage("the element tangent must be 8 x 8"));
    Assert(!cauchy_stress || cauchy_stress->size() >= s.n_q_points,
           ExcMessage("one Cauchy stress per Gauss point"));
    Assert(state_old.size() >= s.n_q_points * n_state && state_new.size() >= s.n_q_points * n_state,
           ExcMessage("one material state per Gauss point"));
    residual = 0;
    if (tangent)
      *tangent = 0;

    // Kinematics at every Gauss point first: the mean dilatation needs them all, with
    // F^-1 G_a and its trace tr(F^-1 G_a) (= d ln J/du_a).
    for (unsigned int q = 0; q < s.n_q_points; ++q)
      {
        s.F[q] = deformation_gradient(s, q, u_local);
        if (!admissible(s.F[q]))
          return materials::UpdateStatus::invalid_deformation;
        for (unsigned int a = 0; a < n_dofs; ++a)
          s.G[q][a] = dof_gradient(s, q, a);
        if (!use_f_bar)
          continue;
        const MeridianTensor F_inv = invert(s.F[q]);
        for (unsigned int a = 0; a < n_dofs; ++a)
          {
            s.H[q][a] = product(F_inv, s.G[q][a]);
            s.trace[q][a] = trace(s.H[q][a]);
          }
      }
    double J0 = 1;
    if (use_f_bar)
      {
        J0 = s.dilatation == FBarDilatation::element_centre ? centre_dilatation(s, u_local)
                                                            : mean_dilatation(s);
        if (!(J0 > 0) || !std::isfinite(J0))
          return materials::UpdateStatus::invalid_deformation;
      }

    materials::MaterialPointResponse response;
    for (unsigned int q = 0; q < s.n_q_points; ++q)
      {
        const MeridianTensor &F = s.F[q];
        const double          theta = use_f_bar ? std::cbrt(J0 / determinant(F)) : 1.0;
        const Tensor<2, 3>    F_bar = theta * full_tensor(F);
        const auto            status =
            material.update(F_bar, state_old.subspan(q * n_state, n_state), response,
                            state_new.subspan(q * n_state, n_state), tangent != nullptr);
        if (status != materials::UpdateStatus::success)
          return status;
        if (cauchy_stress)
          (*cauchy_stress)[q] = response.tau / dealii::determinant(F_bar);

        // B_a = theta G_a + beta_a F with beta_a = theta c_a / 3.
        const MeridianTensor P = block_entries(response.P);
        const auto          &G = s.G[q];
        for (unsigned int a = 0; a < n_dofs; ++a)
          {
            s.B[a] = G[a];
            if (use_f_bar)
              {
                s.c[a] = s.dlnJ0[a] - s.trace[q][a];
                for (unsigned int k = 0; k < 5; ++k)
                  s.B[a][k] = theta * G[a][k] + (theta * s.c[a] / 3.) * F[k];
              }
            residual[a] += scalar_product(P, s.B[a]) * s.dV[q];
          }
        if (tangent)
          add_point_tangent(s, q, response, P, theta, use_f_bar, &(*tangent)(0, 0));
      }
    return materials::UpdateStatus::success;
  }
} // namespace indentsim::fem
