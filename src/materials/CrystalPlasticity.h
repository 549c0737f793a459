// Finite-strain rate-independent crystal elasto-plasticity, the paper's section 2.2 (eqs 10-15,
// Table 2), after Arminjon (1991), Gambin (1991) and Kowalczyk & Gambin (2004):
//   F = F_e F_p (eq. 1),
//   Psi = 1/2 E_e : L^e : E_e, E_e = (C_e - I)/2, C_e = F_e^T F_e (eq. 11, anisotropic
//   St-Venant-Kirchhoff, L^e cubic with C11, C12, C44 in the lattice frame),
//   S_e = L^e : E_e, Mandel stress M_e = 2 C_e dPsi/dC_e = C_e S_e (eq. 10),
//   resolved shear tau^r = M_e : (m_0^r (x) n_0^r),
//   F_p(t + dt) = exp(dt L_p) F_p(t) (eq. 12), L_p = sum_r gamma_dot^r m_0^r (x) n_0^r (eq. 13),
//   regularized Schmid yield surface Phi = (sum_r (tau^r / tau_c^r)^(2n))^(1/2n), f = Phi - 1
//   (eq. 14), associated flow gamma_dot^r = lambda_dot / tau_c^r (tau^r / tau_c^r)^(2n-1)
//   (eq. 15) with lambda_dot from the KKT conditions (eq. 8),
//   extended Voce hardening (Tome et al. 1984) with latent hardening (REFERENCES.md):
//   tau_c(Gamma) = tau0 + (tau1 + theta1 Gamma)(1 - exp(-theta0 Gamma / tau1)),
//   tau_c_dot^r = h(Gamma) sum_s h_rs |gamma_dot^s|, h = dtau_c/dGamma, h_rs = q + (1 - q) delta_rs,
//   Gamma = sum_r int |gamma_dot^r| dt.
//
// Lattice orientation. The intermediate configuration is the lattice frame: F_p starts as the
// orientation g (v_crystal = g v_sample, Orientation.h), so F_e = g^T is a pure rotation in the
// virgin state, and m_0, n_0 and L^e are always used in crystal components (never rotated). The
// orientation therefore lives in each point's state, which is all a polycrystal needs.
//
// Integration over one increment (backward Euler in the exponential map, eq. 12): unknowns are
// the elastic strain E_e (6), the scaled multiplier Delta lambda / tau0 and the critical shears
// tau_c^r / tau0 (12 for FCC); residuals
//   R_E   = E_e - 1/2 (A^T C_e^tr A - I),  A = exp(-Delta L_p),  C_e^tr = F_p,n^-T C F_p,n^-1,
//   R_f   = Phi(E_e, tau_c) - 1,
//   R_tc  = tau_c^r - tau_c,n^r - Hbar sum_s h_rs |Delta gamma^s|,
//   Delta gamma^r = Delta lambda / tau_c^r (tau^r / (Phi tau_c^r))^(2n-1).
// Dividing tau^r by Phi in the flow rule changes nothing at the solution (Phi = 1), but makes
// Delta gamma the gradient of the degree-one homogeneous Phi, so its size does not explode as
// (tau/tau_c)^19 while Newton iterates from an elastic trial far outside the yield surface.
// Hbar = (tau_c(Gamma_n + Delta Gamma) - tau_c(Gamma_n)) / Delta Gamma is the secant of the Voce
// law over the increment: the update is exact whenever the slip rates keep their proportions
// during the increment (in particular for q = 1, where tau_c^r = tau_c(Gamma) exactly), so a
// monotonic single-crystal path does not depend on the step size.
// The local Newton (ImplicitLocalProblem::solve_with_jacobian, backtracking line search) starts
// from the elastic trial; a failure is returned as a status and the load stepper cuts the
// increment back.
//
// Cost. The material point dominates crystal indentation runs, so the Jacobian of the 19
// residuals is written out by the chain rule in plain doubles rather than obtained by forward AD
// through everything (which cost 2.1 M instructions per plastic update against 0.35 M now, same
// solution to round-off; tests/unit/crystal_reference_update.h keeps that AD version as the
// oracle). Every residual depends on the unknowns through Delta gamma^r, rho_r = tau^r/tau_c^r
// and Phi, with (d_r = rho_r/Phi, g_r = d_r^(2n-1) = dPhi/drho_r, w_r = (2n-1) d_r^(2n-2))
//   dDelta gamma^r = g_r/tau_c^r dlambda - lambda g_r/tau_c^r^2 dtau_c^r
//                    + lambda w_r/(tau_c^r Phi) (drho_r - d_r sum_s g_s drho_s),
//   drho_r = (m_0^r (x) n_0^r) : (2 dE_e S_e + C_e (L^e : dE_e)) / tau_c^r - rho_r dtau_c^r/tau_c^r,
//   dR_E = dE_e - 1/2 sum_r dC_e/dDelta gamma^r dDelta gamma^r,  C_e = A^T C_e^tr A,
// where dA/dX (X = -Delta L_p) comes from the terms T_j = X^j/j! already formed for exp(X):
//   dexp(X)/dX_ab = sum_j T_j e_a e_b^T G_j,  G_j = sum_m j! m!/(j+m+1)! T_m
// (through the squarings by the product rule), and Hbar'(Delta Gamma) by one AD direction.
// The critical shears are then eliminated from each Newton system: dDelta gamma/dtau_c is
// diagonal plus rank one (each system's own tau_c, and all of them through Phi), so with the
// latent form h_rs = q + (1 - q) delta_rs the block dR_tc/dtau_c = D - P Q^T is diagonal plus
// rank two, inverted by Sherman-Morrison-Woodbury, and a 7x7 Schur complement on (E_e,
// Delta lambda) remains; when D or the 2x2 capacitance matrix is near singular (large
// increments with q > 1) the dense 19x19 LU is used instead. The consistent tangent dP/dF
// follows from the implicit function theorem, dx/dC_e^tr = -(dR/dx)^-1 dR/dC_e^tr (only R_E
// depends on C_e^tr: dR_E = -1/2 A^T dC_e^tr A), solved the same way with 6 right-hand sides,
// and the chain rule through P = F F_p,n^-1 A S_e A^T F_p,n^-T.
// Most points of an indentation are elastic, so that branch is kept lean: since
// max_r |rho_r| <= Phi <= n_slip^(1/2n) max_r |rho_r| (eq. 14), a trial whose largest |rho_r| is
// below n_slip^(-1/2n) is elastic without evaluating Phi, and the tangent of
// P = F_e S_e F_p,n^-T is written in closed form for the cubic L^e (its 45 independent entries).
//
// State (22 doubles for 12 systems): F_p (9, row-major), tau_c^r (n_systems), Gamma.
// Units: GPa for moduli and stresses.
#pragma once

#include <materials/MaterialModel.h>
#include <materials/SlipSystems.h>

#include <array>
#include <vector>

namespace indentsim::materials
{
  // Cubic elastic constants in the lattice frame [GPa].
  struct CubicElasticity
  {
    double C11 = 106.7, C12 = 60.4, C44 = 28.3;
  };

  // Extended Voce hardening with latent hardening (REFERENCES.md; the paper's Table 2).
  struct ExtendedVoceHardening
  {
    double tau0 = 0.12;   // initial critical resolved shear stress [GPa]
    double tau1 = 0.02;   // [GPa]
    double theta0 = 0.1;  // initial hardening rate [GPa]
    double theta1 = 0.006; // asymptotic hardening rate [GPa]
    double q = 1.4;       // latent hardening ratio [-]

    // tau_c(Gamma) [GPa].
    double critical_shear(double Gamma) const;
    // h(Gamma) = dtau_c/dGamma [GPa].
    double hardening_rate(double Gamma) const;
  };

  class CrystalPlasticity : public MaterialModel
  {
  public:
    // Throws std::invalid_argument for a non-positive-definite stiffness, tau0 <= 0,
    // negative hardening parameters, tau1 = 0 with theta0 > 0, q < 0 or n < 1.
    CrystalPlasticity(const SlipSystems           &slip_systems,
                      const CubicElasticity       &elasticity,
                      const ExtendedVoceHardening &hardening,
                      double                       yield_exponent_n);

    unsigned int n_state_variables() const override { return 9 + n_systems + 1; }
    unsigned int n_slip_systems() const { return n_systems; }

    // F_p = I (lattice axes along the sample axes), tau_c^r = tau0, Gamma = 0.
    void initial_state(std::span<double> state) const override;
    // F_p = g, tau_c^r = tau0, Gamma = 0.
    void oriented_initial_state(std::span<double>   state,
                                const Tensor<2, 3> &orientation) const override;

    UpdateStatus update(const Tensor<2, 3>     &F,
                        std::span<const double> state_old,
                        MaterialPointResponse  &response,
                        std::span<double>       state_new,
                        bool                    compute_tangent = true) const override;

    // The accumulated slip Gamma.
    double equivalent_plastic_strain(std::span<const double> state) const override
    {
      return state[9 + n_systems];
    }

    // Voigt average shear modulus (C11 - C12 + 3 C44) / 5 [GPa].
    double reference_modulus() const override;
    // The latent-hardening coupling and the non-symmetric Mandel stress of the anisotropic
    // lattice make the tangent non-symmetric: GMRES, not CG.
    bool symmetric_tangent() const override { return false; }
    // A local Newton with its tangent (about 28 us from the trial, about half from the previous
    // iterate's state) against an elastic point (about 5 us), averaged over the cells of the
    // assumed plastic zone that are not yet or not all plastic: set by whole runs (`crystal_24`,
    // 2 ranks, spread of the ranks' cell loops: 0.2 % at 2, 4-5 % at 3 and 6, 8 % at 8).
    double relative_plastic_cost() const override { return 2.0; }

    // Accessors of a state.
    static Tensor<2, 3> plastic_deformation(std::span<const double> state); // F_p
    double critical_shear(std::span<const double> state, unsigned int r) const
    {
      return state[9 + r];
    }

    // Resolved shear stresses tau^r = M_e : (m_0^r (x) n_0^r) [GPa] at deformation F with the
    // plastic state of `state` held fixed.
    std::vector<double> resolved_shear_stresses(const Tensor<2, 3>     &F,
                                                std::span<const double> state) const;

    // Phi of eq. 14 for given resolved and critical shears.
    double yield_function_value(const std::vector<double> &tau,
                                const std::vector<double> &tau_c) const;

    const SlipSystems           &slip_systems() const { return systems; }
    const CubicElasticity       &elastic_constants() const { return elasticity; }
    const ExtendedVoceHardening &hardening_law() const { return hardening; }
    double                       yield_exponent() const { return n; }

  private:
    template <int n_slip>
    UpdateStatus update_impl(const Tensor<2, 3>     &F,
                             std::span<const double> state_old,
                             MaterialPointResponse  &response,
                             std::span<double>       state_new,
                             bool                    compute_tangent) const;

    SlipSystems           systems;
    unsigned int          n_systems;
    CubicElasticity       elasticity;
    ExtendedVoceHardening hardening;
    double                n; // yield exponent (the surface uses 2n)
    std::vector<std::array<std::array<double, 3>, 3>> schmid; // m_0^r (x) n_0^r
    double yield_bound_factor; // n_systems^(1/2n) >= Phi / max_r |tau^r / tau_c^r|
  };
} // namespace indentsim::materials
