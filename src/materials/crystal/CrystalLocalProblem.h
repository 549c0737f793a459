// The local problem of one crystal-plasticity increment (backward Euler in the exponential map,
// eq. 12), for any elasticity, flow rule and hardening law with the interfaces of
// LatticeElasticity.h, RegularizedSchmidFlow.h and FamilyVoceHardening.h. Unknowns x: the
// elastic strain E_e (6), the scaled multiplier Delta lambda / tau_ref and the scaled critical
// shears tau_c^r / tau_ref (tau_ref the hardening law's stress scale, the smallest tau0); residuals in strain units
// (stresses divided by the elastic stiffness scale):
//   R_E   = E_e - 1/2 (A^T C_e^tr A - I),  A = exp(-Delta L_p),  C_e^tr = F_p,n^-T C F_p,n^-1,
//   R_f   = Phi(tau, tau_c) - 1,
//   R_tc  = tau_c^r - tau_c,n^r - Delta tau_c^r(Delta gamma)   (the hardening law),
//   Delta gamma^r = Delta lambda dPhi/dtau^r                  (the flow rule),
//   tau^r = M_e : (m_0^r (x) n_0^r),  M_e = C_e S_e (eq. 10),    S_e = L^e : E_e (the elasticity).
// The Jacobian is written out by the chain rule in plain doubles:
//   dDelta gamma^r = N_r dlambda + c_r (drho_r - d_r dPhi) + D_r dtau_c^r  (the flow rule's
//                    linearization, rho_r = tau^r / tau_c^r, dPhi = sum_s g_s drho_s),
//   dtau^r = (m_0^r (x) n_0^r) : (2 dE_e S_e + C_e (L^e : dE_e)),
//   dR_E = dE_e - 1/2 sum_r dC_e/dDelta gamma^r dDelta gamma^r,  C_e = A^T C_e^tr A,
// with dA/dX (X = -Delta L_p) from exp_matrix_and_derivative. The critical shears are
// eliminated from each Newton system (solve_linearized): dDelta gamma/dtau_c is diagonal plus
// rank one (each system's own tau_c, and all of them through Phi), and the hardening increment
// depends on the total slip and the system's own, so dR_tc/dtau_c is diagonal plus rank two
// (plus one per slip family with a latent matrix between families).
#pragma once

#include "materials/ImplicitLocalProblem.h"
#include "materials/crystal/ExtendedVoceHardening.h"
#include "materials/crystal/MatrixExponential.h"
#include "materials/crystal/SmallMatrix.h"

#include <array>
#include <cmath>
#include <utility>

namespace indentsim::materials::crystal
{
  // The constitutive laws of a crystal and its Schmid tensors m_0^r (x) n_0^r.
  template <typename Elasticity, typename FlowRule, typename Hardening>
  struct CrystalLaws
  {
    const Elasticity *elasticity;
    const FlowRule   *flow_rule;
    const Hardening  *hardening;
    const Matrix     *schmid;
    double            stress_scale;    // tau_ref, the initial critical shear [GPa]
    double            stiffness_scale; // [GPa]
  };

  // Everything that follows from (E_e, tau_c, Delta lambda): S_e = L^e : E_e, the resolved shears
  // tau^r [GPa] and the flow rule's rho_r = tau^r / tau_c^r, Phi and Delta gamma^r.
  template <typename FlowRule, int n_slip>
  struct SlipState
  {
    Matrix                                       S_e;
    std::array<double, n_slip>                   tau;
    typename FlowRule::template Response<n_slip> flow;
  };

  // S_e and the resolved shears [GPa] of an unrolled elastic strain.
  template <typename Laws>
  void resolved_shears(const Laws &laws, const double *E_e, const int n_slip, Matrix &S_e,
                       double *tau)
  {
    S_e = laws.elasticity->stress(symmetric_matrix(E_e));
    const Matrix M_e = multiply(right_cauchy_green(E_e), S_e);
    for (int r = 0; r < n_slip; ++r)
      tau[r] = contract(M_e, laws.schmid[r]);
  }

  template <typename Laws, typename FlowRule, int n_slip>
  void evaluate_slip(const Laws &laws, const double *E_e,
                     const double                *tau_c,  // scaled
                     const double                 lambda, // scaled
                     SlipState<FlowRule, n_slip> &out)
  {
    resolved_shears(laws, E_e, n_slip, out.S_e, out.tau.data());
    laws.flow_rule->template evaluate<n_slip>(out.tau, tau_c, lambda, laws.stress_scale, out.flow);
  }

  template <typename Elasticity, typename FlowRule, typename Hardening, int n_slip>
  struct CrystalLocalProblem
  {
    static constexpr int n_unknowns = 7 + n_slip;
    static constexpr int lambda_index = 6;
    static constexpr int tau_c_index = 7;
    using Laws = CrystalLaws<Elasticity, FlowRule, Hardening>;
    using Unknowns = std::array<double, n_unknowns>;
    using Jacobian = std::array<std::array<double, n_unknowns>, n_unknowns>;

    Laws          laws;
    double        Gamma_n;
    const double *tau_c_n; // n_slip [GPa]
    Matrix        C_e_trial;

    // slip and A are written by every evaluation, the rest by those with a Jacobian; the
    // state update and the consistent tangent reuse them.
    SlipState<FlowRule, n_slip>                        slip;
    Matrix                                             A;     // exp(-Delta L_p)
    std::array<Matrix, 9>                              dA_dX; // dA/dX_ab, row-major ab
    std::array<std::array<double, n_unknowns>, n_slip> ddelta_gamma_dx;
    // dR_tc/dtau_c = diag(tau_c_diagonal) - low_rank_P low_rank_Q^T (see solve_linearized), of
    // rank 2 plus one per family with a latent matrix.
    static constexpr int                             max_rank = 2 + max_slip_families;
    int                                              rank = 2;
    std::array<double, n_slip>                       tau_c_diagonal;
    std::array<std::array<double, max_rank>, n_slip> low_rank_P, low_rank_Q;

    // X = -Delta L_p = -sum_r Delta gamma^r m_0^r (x) n_0^r (eq. 13)
    Matrix minus_delta_L_p() const
    {
      Matrix X;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            double sum = 0.0;
            for (int r = 0; r < n_slip; ++r)
              if (laws.schmid[r][i][j] != 0.0)
                sum -= slip.flow.delta_gamma[r] * laws.schmid[r][i][j];
            X[i][j] = sum;
          }
      return X;
    }

    void operator()(const Unknowns &x, Unknowns &R, Jacobian *jacobian)
    {
      evaluate_slip<Laws, FlowRule, n_slip>(laws, &x[0], &x[tau_c_index], x[lambda_index], slip);

      // A = exp(-Delta L_p) (eqs 12-13), with dA/dX when the Jacobian is wanted.
      const Matrix                         X = minus_delta_L_p();
      Matrix                               C_e;
      std::array<std::array<double, 9>, 6> dC_e_dX; // unrolled C_e by X_ab
      if (jacobian)
        {
          exp_matrix_and_derivative(X, A, dA_dX);
          // dC_e/dX_ab = dA^T B + B^T dA, B = C_e^tr A
          const Matrix B = multiply(C_e_trial, A);
          C_e = multiply_transposed_first(A, B);
          for (unsigned int ab = 0; ab < 9; ++ab)
            {
              const Matrix dA_T_B = multiply_transposed_first(dA_dX[ab], B);
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

      const double residual_scale = laws.stress_scale / laws.stiffness_scale;
      R[lambda_index] = (slip.flow.Phi - 1.0) * residual_scale;

      double                     delta_Gamma = 0.0;
      std::array<double, n_slip> abs_delta_gamma;
      for (int r = 0; r < n_slip; ++r)
        {
          abs_delta_gamma[r] =
              slip.flow.delta_gamma[r] >= 0 ? slip.flow.delta_gamma[r] : -slip.flow.delta_gamma[r];
          delta_Gamma += abs_delta_gamma[r];
        }
      HardeningIncrement<n_slip> hardening;
      laws.hardening->template increment<n_slip>(Gamma_n, abs_delta_gamma, delta_Gamma, hardening);
      for (int r = 0; r < n_slip; ++r)
        R[tau_c_index + r] =
            (laws.stress_scale * x[tau_c_index + r] - tau_c_n[r] - hardening.value[r]) /
            laws.stiffness_scale;
      if (jacobian)
        assemble_jacobian(x, dC_e_dX, hardening, *jacobian);
    }

    void assemble_jacobian(const Unknowns &x, const std::array<std::array<double, 9>, 6> &dC_e_dX,
                           const HardeningIncrement<n_slip> &hardening, Jacobian &J)
    {
      const double  lambda = x[lambda_index];
      const double *tau_c = &x[tau_c_index];

      // drho_r/dE_k = (m_0^r (x) n_0^r) : dM_e/dE_k / (tau_ref tau_c^r),
      // dM_e = 2 dE S_e + C_e (L^e : dE) (eq. 10).
      const Matrix          C_e_of_E = right_cauchy_green(&x[0]);
      std::array<Matrix, 6> dM_dE;
      for (unsigned int k = 0; k < 6; ++k)
        {
          Matrix dE{};
          dE[sym_i[k]][sym_j[k]] = 1.0;
          dE[sym_j[k]][sym_i[k]] = 1.0;
          const Matrix dS = laws.elasticity->stress(dE);
          const Matrix first = multiply(dE, slip.S_e);
          const Matrix second = multiply(C_e_of_E, dS);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              dM_dE[k][i][j] = 2.0 * first[i][j] + second[i][j];
        }
      typename FlowRule::template Linearization<n_slip> flow;
      laws.flow_rule->template linearize<n_slip>(slip.flow, tau_c, lambda, flow);

      std::array<double, n_unknowns>            dPhi_dx{};
      std::array<std::array<double, 6>, n_slip> drho_dE;
      for (int r = 0; r < n_slip; ++r)
        {
          const double scale = 1.0 / (laws.stress_scale * tau_c[r]);
          for (unsigned int k = 0; k < 6; ++k)
            drho_dE[r][k] = contract(dM_dE[k], laws.schmid[r]) * scale;
          const double g = flow.dPhi_dratio[r];
          for (unsigned int k = 0; k < 6; ++k)
            dPhi_dx[k] += g * drho_dE[r][k];
          // drho_r/dtau_c^r = -rho_r / tau_c^r
          dPhi_dx[tau_c_index + r] = -g * slip.flow.ratio[r] / tau_c[r];
        }

      // dDelta gamma^r/dtau_c^s = delta_rs D_r + u_r v_s (the critical shear of the system
      // itself, and every tau_c through Phi).
      std::array<double, n_slip> D, u, v;
      for (int r = 0; r < n_slip; ++r)
        {
          auto        &row = ddelta_gamma_dx[r];
          const double c = flow.ratio_rate[r];
          for (unsigned int k = 0; k < 6; ++k)
            row[k] = c * (drho_dE[r][k] - flow.relative_ratio[r] * dPhi_dx[k]);
          row[lambda_index] = flow.lambda_rate[r];
          D[r] = flow.tau_c_rate[r];
          u[r] = c * flow.relative_ratio[r];
          v[r] = -dPhi_dx[tau_c_index + r];
        }
      for (int r = 0; r < n_slip; ++r)
        for (int s = 0; s < n_slip; ++s)
          ddelta_gamma_dx[r][tau_c_index + s] = u[r] * v[s] + (r == s ? D[r] : 0.0);

      // R_E rows: dR_E/dx = I_E - 1/2 dC_e/dDelta gamma dDelta gamma/dx.
      for (unsigned int k = 0; k < 6; ++k)
        {
          std::array<double, n_slip> dC_e_ddelta_gamma;
          for (int r = 0; r < n_slip; ++r)
            {
              double sum = 0.0;
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  sum -= dC_e_dX[k][3 * a + b] * laws.schmid[r][a][b];
              dC_e_ddelta_gamma[r] = sum;
            }
          auto  &row = J[k];
          double dC_e_u = 0.0;
          for (int j = 0; j < tau_c_index; ++j)
            row[j] = 0.0;
          for (int r = 0; r < n_slip; ++r)
            {
              const double dC = -0.5 * dC_e_ddelta_gamma[r];
              for (int j = 0; j < tau_c_index; ++j)
                row[j] += dC * ddelta_gamma_dx[r][j];
              dC_e_u += dC * u[r];
            }
          row[k] += 1.0;
          for (int s = 0; s < n_slip; ++s)
            row[tau_c_index + s] = -0.5 * dC_e_ddelta_gamma[s] * D[s] + dC_e_u * v[s];
        }

      // R_f row.
      const double residual_scale = laws.stress_scale / laws.stiffness_scale;
      for (int j = 0; j < n_unknowns; ++j)
        J[lambda_index][j] = dPhi_dx[j] * residual_scale;

      assemble_hardening_rows(D, u, v, hardening, J);
    }

    // R_tc rows: dDelta tau_c^r = a_r dDelta Gamma + sum_g c_rg dDelta Gamma_g
    // + b_r d|Delta gamma^r| (the hardening law, HardeningIncrement), so
    // dR_tc^r/dtau_c^s = delta_rs (tau_ref - b_r s_r D_r)/C
    //                    - (a_r e_s + sum_g c_rg e_gs + b_r s_r u_r v_s)/C,
    // s_r = sign(Delta gamma^r), e = dDelta Gamma/dtau_c, e_g = dDelta Gamma_g/dtau_c, C the
    // stiffness scale: diagonal minus rank 2 (plus one per family), kept for solve_linearized.
    void assemble_hardening_rows(const std::array<double, n_slip> &D,
                                 const std::array<double, n_slip> &u,
                                 const std::array<double, n_slip> &v,
                                 const HardeningIncrement<n_slip> &hardening, Jacobian &J)
    {
      const double C = laws.stiffness_scale;
      const int    n_families = static_cast<int>(hardening.n_families);
      rank = 2 + n_families;
      // Row k of dDelta Gamma/dx (k = 0) and dDelta Gamma_g/dx (k = 2 + g) on the unknowns
      // before the critical shears; their tau_c columns go to low_rank_Q.
      std::array<std::array<double, tau_c_index>, max_rank> dslip_dx;
      std::array<double, max_rank>                          sign_u;
      std::array<double, n_slip>                            sign;
      for (int k = 0; k < rank; ++k)
        {
          dslip_dx[k].fill(0.0);
          sign_u[k] = 0.0;
        }
      for (int r = 0; r < n_slip; ++r)
        {
          sign[r] = slip.flow.delta_gamma[r] >= 0 ? 1.0 : -1.0;
          for (int j = 0; j < tau_c_index; ++j)
            dslip_dx[0][j] += sign[r] * ddelta_gamma_dx[r][j];
          sign_u[0] += sign[r] * u[r];
        }
      for (int r = 0; r < n_slip && n_families > 0; ++r)
        {
          const int g = 2 + int(hardening.family_of_system[r]);
          for (int j = 0; j < tau_c_index; ++j)
            dslip_dx[g][j] += sign[r] * ddelta_gamma_dx[r][j];
          sign_u[g] += sign[r] * u[r];
        }
      for (int r = 0; r < n_slip; ++r)
        {
          const double a = hardening.total_rate[r];
          const double b = hardening.own_rate[r] * sign[r];
          tau_c_diagonal[r] = (laws.stress_scale - b * D[r]) / C;
          auto &P = low_rank_P[r];
          auto &Q = low_rank_Q[r];
          P[0] = a / C;
          Q[0] = sign[r] * D[r] + sign_u[0] * v[r];
          P[1] = b * u[r] / C;
          Q[1] = v[r];
          for (int g = 0; g < n_families; ++g)
            {
              const bool own_family = int(hardening.family_of_system[r]) == g;
              P[2 + g] = hardening.family_rate[r][g] / C;
              Q[2 + g] = (own_family ? sign[r] * D[r] : 0.0) + sign_u[2 + g] * v[r];
            }
          auto &row = J[tau_c_index + r];
          for (int j = 0; j < tau_c_index; ++j)
            {
              double sum = P[0] * dslip_dx[0][j] + b * ddelta_gamma_dx[r][j] / C;
              for (int g = 0; g < n_families; ++g)
                sum += P[2 + g] * dslip_dx[2 + g][j];
              row[j] = -sum;
            }
        }
      if (rank == 2)
        assemble_tau_c_block<2>(J);
      else
        {
          for (int r = 0; r < n_slip; ++r) // the unused columns take part as zeros
            for (int k = rank; k < max_rank; ++k)
              low_rank_P[r][k] = low_rank_Q[r][k] = 0.0;
          assemble_tau_c_block<max_rank>(J);
        }
    }

    // J_tt = diag(tau_c_diagonal) - P Q^T with R columns of P and Q (a compile-time R keeps the
    // common rank 2 as fast as a hand-written one).
    template <int R>
    void assemble_tau_c_block(Jacobian &J) const
    {
      for (int r = 0; r < n_slip; ++r)
        for (int s = 0; s < n_slip; ++s)
          {
            double product = 0.0;
            for (int k = 0; k < R; ++k)
              product += low_rank_P[r][k] * low_rank_Q[s][k];
            J[tau_c_index + r][tau_c_index + s] = -product + (r == s ? tau_c_diagonal[r] : 0.0);
          }
    }

    // Solves J X = B, J from the last evaluation with a Jacobian, by eliminating the critical
    // shears: with y = (E_e, Delta lambda), t = tau_c,
    //   Z = J_tt^-1 [J_ty | B_t],  (J_yy - J_yt Z_y) X_y = B_y - J_yt Z_B,  X_t = Z_B - Z_y X_y,
    // where J_tt = D - P Q^T (diagonal plus low rank: the latent hardening and the shared Phi)
    // is inverted by the Sherman-Morrison-Woodbury formula
    //   J_tt^-1 = D^-1 + D^-1 P (I - Q^T D^-1 P)^-1 Q^T D^-1.
    // That needs D and the small capacitance away from singular: for large increments with
    // q > 1, D_r = (tau_ref - b_r D_r)/C can approach zero while J itself is regular, so those
    // cases fall back to the dense LU of J.
    template <int n_rhs>
    bool solve_linearized(const Jacobian                                    &J,
                          std::array<std::array<double, n_rhs>, n_unknowns> &B) const
    {
      constexpr int n_y = tau_c_index, n_columns = n_y + n_rhs;
      const auto    dense = [&]() {
        auto copy = J;
        return materials::internal::solve_dense<n_unknowns, n_rhs>(copy, B);
      };
      const double diagonal_floor = 0.1 * laws.stress_scale / laws.stiffness_scale;
      for (int r = 0; r < n_slip; ++r)
        if (!(std::abs(tau_c_diagonal[r]) >= diagonal_floor))
          return dense();
      // Z = J_tt^-1 [J_ty | B_t]
      std::array<std::array<double, n_columns>, n_slip> Z;
      if (!(rank == 2 ? woodbury_solve<2, n_rhs>(J, B, Z)
                      : woodbury_solve<max_rank, n_rhs>(J, B, Z)))
        return dense();

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
      if (!materials::internal::solve_dense<n_y, n_rhs>(schur, X_y))
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

    // Z = J_tt^-1 [J_ty | B_t] by the Sherman-Morrison-Woodbury formula with R columns of P and
    // Q; false if the capacitance is near singular.
    template <int R, int n_rhs>
    bool woodbury_solve(const Jacobian                                              &J,
                        const std::array<std::array<double, n_rhs>, n_unknowns>     &B,
                        std::array<std::array<double, tau_c_index + n_rhs>, n_slip> &Z) const
    {
      constexpr int n_y = tau_c_index, n_columns = n_y + n_rhs;
      // The capacitance I - Q^T D^-1 P (R x R) in LU with partial pivoting.
      std::array<std::array<double, R>, R> capacitance{};
      for (int i = 0; i < R; ++i)
        capacitance[i][i] = 1.0;
      for (int r = 0; r < n_slip; ++r)
        for (int i = 0; i < R; ++i)
          for (int j = 0; j < R; ++j)
            capacitance[i][j] -= low_rank_Q[r][i] * low_rank_P[r][j] / tau_c_diagonal[r];
      std::array<int, R> pivot_row;
      double             determinant = 1.0;
      for (int k = 0; k < R; ++k)
        {
          int pivot = k;
          for (int i = k + 1; i < R; ++i)
            if (std::abs(capacitance[i][k]) > std::abs(capacitance[pivot][k]))
              pivot = i;
          pivot_row[k] = pivot;
          std::swap(capacitance[k], capacitance[pivot]);
          determinant *= capacitance[k][k];
          if (capacitance[k][k] == 0.0)
            break;
          for (int i = k + 1; i < R; ++i)
            {
              capacitance[i][k] /= capacitance[k][k];
              for (int j = k + 1; j < R; ++j)
                capacitance[i][j] -= capacitance[i][k] * capacitance[k][j];
            }
        }
      if (!(std::abs(determinant) >= 1e-3))
        return false;

      std::array<std::array<double, n_columns>, R> W{};
      for (int r = 0; r < n_slip; ++r)
        {
          const double inverse_diagonal = 1.0 / tau_c_diagonal[r];
          for (int c = 0; c < n_columns; ++c)
            {
              Z[r][c] = (c < n_y ? J[n_y + r][c] : B[n_y + r][c - n_y]) * inverse_diagonal;
              for (int k = 0; k < R; ++k)
                W[k][c] += low_rank_Q[r][k] * Z[r][c];
            }
        }
      // W := capacitance^-1 W (the LU's row swaps, then forward and back substitution).
      for (int k = 0; k < R; ++k)
        {
          std::swap(W[k], W[pivot_row[k]]);
          for (int i = k + 1; i < R; ++i)
            for (int c = 0; c < n_columns; ++c)
              W[i][c] -= capacitance[i][k] * W[k][c];
        }
      for (int k = R - 1; k >= 0; --k)
        for (int c = 0; c < n_columns; ++c)
          {
            double sum = W[k][c];
            for (int j = k + 1; j < R; ++j)
              sum -= capacitance[k][j] * W[j][c];
            W[k][c] = sum / capacitance[k][k];
          }
      for (int r = 0; r < n_slip; ++r)
        for (int k = 0; k < R; ++k)
          {
            const double p = low_rank_P[r][k] / tau_c_diagonal[r];
            for (int c = 0; c < n_columns; ++c)
              Z[r][c] += p * W[k][c];
          }

      return true;
    }
  };
} // namespace indentsim::materials::crystal
