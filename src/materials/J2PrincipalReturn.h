// The return mapping of J2Plasticity (see J2Plasticity.h for the model) in principal space, in
// plain doubles. The backward-Euler exponential map eps_e = eps_e^tr - Delta gamma N(eps_e) has
// a flow direction N that is an isotropic function of eps_e, so the solution is coaxial with
// b_e^tr (Simo 1992, CMAME 99, 61-112, section 3; de Souza Neto, Peric & Owen 2008, section
// 14.5). In the eigenbasis of b_e^tr, with the trial principal log strains t_a = 1/2 log
// lambda_a (lambda_a the eigenvalues of b_e^tr), the return is 4 scalar equations in the
// principal elastic log strains e_a and Delta gamma, scaled to strain units (the yield condition
// divided by mu so that one tolerance fits both parts):
//   R_a = e_a - t_a + Delta gamma N_a,   N_a = sqrt(3/2) D_a / |D|,   a = 1, 2, 3,
//   R_4 = sqrt(3/2) |D| / J^m - sigma_y(gamma_p,n + Delta gamma) / mu,
// with D_a = b_a - (b_1 + b_2 + b_3)/3 the principal dev b_e (dev tau = mu dev b_e, eq. 3) and
// b_a = exp(2 e_a); m = 1 for the Cauchy measure, 0 for the Kirchhoff one. The sum of the R_a
// gives e_1 + e_2 + e_3 = t_1 + t_2 + t_3 (isochoric flow). The Jacobian, by hand:
//   dR_a/de_c = delta_ac + c_N 2 b_c (delta_ac - 1/3 - D_a D_c / |D|^2),  c_N = sqrt(3/2) Dg / |D|,
//   dR_a/dDelta gamma = N_a,   dR_4/de_c = sqrt(3/2) 2 b_c D_c / (|D| J^m),
//   dR_4/dDelta gamma = -h / mu,   dR_4/dJ = -m sqrt(3/2) |D| / J^(m+1),   dR_a/dt_c = -delta_ac,
// (using dD_a/de_c = 2 b_c (delta_ac - 1/3), d|D|/de_c = 2 b_c D_c / |D|, sum_a D_a = 0), and the
// sensitivity de/d(t, J) by the implicit function theorem gives the principal part of the
// consistent tangent. The flow stress is any law of IsotropicHardening.h: a smooth law (power,
// Voce) with its value and slope, a piecewise-linear one (linear, table) segment by segment
// (solve() below, docs/theory.md). Units: GPa for stresses and moduli, strains dimensionless.
#pragma once

#include "materials/IsotropicHardening.h"

#include <array>

namespace indentsim::materials
{
  class J2PrincipalReturn
  {
  public:
    // (e_1, e_2, e_3, Delta gamma) and the 4x4 matrices on them.
    using Vector = std::array<double, 4>;
    using Matrix = std::array<Vector, 4>;

    enum class Outcome
    {
      plastic,          // Delta gamma > 0
      on_yield_surface, // Delta gamma = 0 to round-off: the elastic solution
      not_converged
    };

    // The return from the trial principal log strains t_a with J = det F [-], from gamma_p,n,
    // for shear modulus mu [GPa] and the yield measure (cauchy: m = 1).
    J2PrincipalReturn(const IsotropicHardening &law, double mu, double gamma_p_n,
                      const std::array<double, 3> &trial_log_strain, double J, bool cauchy);

    // The local Newton (and for a piecewise-linear law the segment walk).
    Outcome solve();

    // After solve(): e_a and Delta gamma.
    double elastic_log_strain(const unsigned int a) const { return x[a]; }
    double delta_gamma() const { return x[3]; }
    // c_N = sqrt(3/2) Delta gamma / |D| at the solution: R_a = e_a - t_a + c_N D_a.
    double flow_factor() const;

    // The residual R(x) and, if dR_dx is not null, its Jacobian; public for the tests.
    void evaluate(const Vector &x, Vector &R, Matrix *dR_dx) const;

    // After solve() with Outcome::plastic: de_a/dt_c (column c < 3) and de_a/dJ (column 3) at
    // the solution, by the implicit function theorem. False if dR/dx is singular.
    bool sensitivity(std::array<Vector, 3> &de_dp) const;

  private:
    // The principal dev b_e, D_a, the principal b_a and |D| at x.
    struct DeviatoricPart
    {
      std::array<double, 3> D, b;
      double                norm;
    };
    static DeviatoricPart deviatoric_part(const Vector &x);
    // The flow stress sigma_y(gamma_p,n + Delta gamma) and its slope h [GPa]: the current line
    // (a linear law, or one segment of a table) or the smooth law.
    IsotropicHardening::FlowStress flow_stress(double delta_gamma) const;
    // The local Newton with the current line or the smooth law: the Hencky guess first, the
    // trial state as fallback.
    Outcome solve_with_current_law();
    // The segment walk of a piecewise-linear law.
    Outcome solve_piecewise_linear();

    const IsotropicHardening      &law;
    double                         mu;
    double                         gamma_p_n;
    std::array<double, 3>          t; // trial principal log strains
    double                         J;
    double                         J_m; // J^m
    bool                           cauchy;
    bool                           smooth;         // the law itself, else the line below
    IsotropicHardening::FlowStress line{0.0, 0.0}; // sigma_y and h of the line at gamma_p,n
    Vector                         x{{0.0, 0.0, 0.0, 0.0}};
  };
} // namespace indentsim::materials
