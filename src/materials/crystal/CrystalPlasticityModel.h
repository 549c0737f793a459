// Finite-strain rate-independent crystal elasto-plasticity (the paper's section 2.2, eqs 10-15)
// for any elasticity, flow rule and hardening law with the interfaces described in
// LatticeElasticity.h, RegularizedSchmidFlow.h and FamilyVoceHardening.h, and any lattice
// (SlipSystems.h): the laws supply their values and derivatives, this class does the rest.
//   F = F_e F_p (eq. 1),  E_e = (C_e - I)/2,  C_e = F_e^T F_e,  S_e = L^e : E_e (eq. 11),
//   Mandel stress M_e = C_e S_e (eq. 10),  resolved shear tau^r = M_e : (m_0^r (x) n_0^r),
//   F_p(t + dt) = exp(dt L_p) F_p(t) (eq. 12),  L_p = sum_r gamma_dot^r m_0^r (x) n_0^r (eq. 13),
// plastic flow and hardening as the flow rule and hardening law say, with the multiplier from
// the KKT conditions (eq. 8).
//
// Lattice orientation. The intermediate configuration is the lattice frame: F_p starts as the
// orientation g (v_crystal = g v_sample, Orientation.h), so F_e = g^T is a pure rotation in the
// virgin state, and m_0, n_0 and L^e are always used in crystal components (never rotated). The
// orientation therefore lives in each point's state, which is all a polycrystal needs.
//
// The update. Most points of an indentation are elastic, so that branch is kept lean: a trial
// below the flow rule's elastic_limit is elastic without evaluating Phi, and its tangent is the
// elasticity's closed form. Otherwise the local Newton of CrystalLocalProblem.h
// (ImplicitLocalProblem::solve_with_jacobian, backtracking line search) starts from the hint in
// state_new when that is a plastic state of the same increment, else from the elastic trial; a
// failure is returned as a status and the load stepper cuts the increment back. The Jacobian is
// written out by the chain rule in plain doubles rather than obtained by forward AD through
// everything, because the material point dominates crystal indentation runs
// (tests/unit/crystal_reference_update.h keeps the AD version as the oracle). The consistent
// tangent dP/dF follows from the implicit function theorem, dx/dC_e^tr = -(dR/dx)^-1 dR/dC_e^tr
// (only R_E depends on C_e^tr: dR_E = -1/2 A^T dC_e^tr A), solved with the local problem's
// structured solve for 6 right-hand sides, and the chain rule through
// P = F F_p,n^-1 A S_e A^T F_p,n^-T.
//
// The implementation is in CrystalPlasticityModel.templates.h; CrystalPlasticity.cc instantiates
// the paper's model. A new law is a new policy type; the integrator is instantiated for the slip
// system counts of `slip_system_counts` (a lattice with another count adds it there).
//
// State (22 doubles for 12 systems): F_p (9, row-major), tau_c^r (n_systems), Gamma.
// Units: GPa for moduli and stresses.
#pragma once

#include "materials/MaterialModel.h"
#include "materials/crystal/SlipSystems.h"
#include "materials/crystal/SmallMatrix.h"

#include <array>
#include <utility>
#include <vector>

namespace indentsim::materials
{
  template <typename Elasticity, typename FlowRule, typename Hardening>
  class CrystalPlasticityModel : public MaterialModel
  {
  public:
    // The slip-system counts the integrator is instantiated for: every combination of the
    // families of SlipSystems.h (FCC 12; BCC 12, 24, 36, 48; HCP multiples of 3 up to 30).
    static constexpr std::array<unsigned int, 12> slip_system_counts = {
        {12, 24, 18, 3, 6, 9, 15, 21, 27, 30, 36, 48}};

    // Throws std::invalid_argument ("CrystalPlasticity: ...") for an unsupported number of slip
    // systems or parameters a law rejects.
    CrystalPlasticityModel(const SlipSystems &slip_systems, const Elasticity &elasticity,
                           const FlowRule &flow_rule, const Hardening &hardening);

    unsigned int n_state_variables() const override { return 9 + n_systems + 1; }
    unsigned int n_slip_systems() const { return n_systems; }

    // F_p = I (lattice axes along the sample axes), tau_c^r = tau_c,0, Gamma = 0.
    void initial_state(std::span<double> state) const override;
    // F_p = g, tau_c^r = tau_c,0, Gamma = 0.
    void oriented_initial_state(std::span<double>   state,
                                const Tensor<2, 3> &orientation) const override;

    UpdateStatus update(const Tensor<2, 3> &F, std::span<const double> state_old,
                        MaterialPointResponse &response, std::span<double> state_new,
                        bool compute_tangent = true) const override;

    // The accumulated slip Gamma.
    double equivalent_plastic_strain(std::span<const double> state) const override
    {
      return state[9 + n_systems];
    }

    double reference_modulus() const override { return elasticity.reference_modulus(); }
    // The latent-hardening coupling and the non-symmetric Mandel stress of the anisotropic
    // lattice make the tangent non-symmetric: GMRES, not CG.
    bool symmetric_tangent() const override { return false; }
    // A local Newton with its tangent against an elastic point, averaged over the cells of the
    // assumed plastic zone that are not yet or not all plastic: set by the balance of the ranks'
    // cell loops in whole crystal runs.
    double relative_plastic_cost() const override { return 2.0; }

    // Accessors of a state.
    static Tensor<2, 3> plastic_deformation(std::span<const double> state); // F_p
    double              critical_shear(std::span<const double> state, unsigned int r) const
    {
      return state[9 + r];
    }

    // Resolved shear stresses tau^r = M_e : (m_0^r (x) n_0^r) [GPa] at deformation F with the
    // plastic state of `state` held fixed.
    std::vector<double> resolved_shear_stresses(const Tensor<2, 3>     &F,
                                                std::span<const double> state) const;

    // The flow rule's Phi for given resolved and critical shears.
    double yield_function_value(const std::vector<double> &tau,
                                const std::vector<double> &tau_c) const
    {
      return flow.value(tau, tau_c);
    }

    const SlipSystems &slip_systems() const { return systems; }
    const Elasticity  &elastic_constants() const { return elasticity; }
    const FlowRule    &flow_rule() const { return flow; }
    const Hardening   &hardening_law() const { return hardening; }

  private:
    template <std::size_t... index>
    UpdateStatus dispatch_update(std::index_sequence<index...>, const Tensor<2, 3> &F,
                                 std::span<const double> state_old, MaterialPointResponse &response,
                                 std::span<double> state_new, bool compute_tangent) const;

    template <int n_slip>
    UpdateStatus update_impl(const Tensor<2, 3> &F, std::span<const double> state_old,
                             MaterialPointResponse &response, std::span<double> state_new,
                             bool compute_tangent) const;

    template <int n_slip>
    bool warm_start_guess(const crystal::Matrix &F, std::span<const double> state_old,
                          std::span<const double> hint, std::array<double, 7 + n_slip> &x) const;

    template <typename LocalProblem>
    bool plastic_tangent(LocalProblem &problem, const typename LocalProblem::Jacobian &jacobian,
                         const crystal::Matrix &F_e_trial, const crystal::Matrix &F_e,
                         const crystal::Matrix &F_p_n_inverse, const crystal::Matrix &G_A,
                         Tensor<4, 3> &dP_dF) const;

    SlipSystems                  systems;
    unsigned int                 n_systems;
    Elasticity                   elasticity;
    FlowRule                     flow;
    Hardening                    hardening;
    std::vector<crystal::Matrix> schmid;        // m_0^r (x) n_0^r
    double                       elastic_limit; // of max_r |tau^r / tau_c^r|, the flow rule's
  };
} // namespace indentsim::materials
