// Finite-strain J2 elastoplasticity with isotropic hardening and the exponential-map return,
// exactly as the paper's section 2.1 (eqs 1-9; AceFEM's "NeoHookeWAMisesExH" element):
//   F = F_e F_p (eq. 1); neo-Hookean energy (eq. 2) in b_e = F_e F_e^T = F C_p^-1 F^T;
//   Huber-Mises-Hencky stress sigma_HMH = sqrt(3/2) |dev s| (eq. 4), s = tau / J (Cauchy, the
//   paper's choice and our default) or s = tau (Kirchhoff, selectable);
//   sigma_y = sigma_y0 + H gamma_p (eq. 5), or another law sigma_y(gamma_p) of
//   IsotropicHardening.h (power, Voce, table); yield function f = sigma_HMH - sigma_y (eq. 6);
//   associative flow (eq. 7), KKT conditions (eq. 8) and the exponential map (eq. 9).
//
// Backward-Euler exponential map in spatial form: with the trial state
// b_e^tr = F C_p,n^-1 F^T and eps_e = 1/2 log b_e,
//   eps_e = eps_e^tr - Delta gamma N,    N = sqrt(3/2) dev tau / |dev tau|,
//   f(tau(eps_e), gamma_p,n + Delta gamma) = 0,
// i.e. b_e = exp(-2 Delta gamma N) b_e^tr with N coaxial with b_e^tr. N is normalised so that
// sqrt(2/3) |Delta gamma N| = Delta gamma: the plastic multiplier is the equivalent plastic
// strain increment, as the paper says (for the Cauchy measure the factor 1/J of eq. 7 is
// absorbed into the multiplier). Plastic flow is isochoric (tr N = 0), so J_e = J and the
// pressure is untouched by the return. N is an isotropic function of eps_e, so eps_e stays
// coaxial with b_e^tr: the update takes the eigen-decomposition of b_e^tr and solves the return
// in principal space, 4 unknowns (the principal eps_e, Delta gamma) in plain doubles with a
// hand-derived Jacobian (J2PrincipalReturn.h; the neo-Hookean stress is not linear in eps_e, so
// it is a local Newton). The consistent tangent is the derivative of the isotropic function
// b_e(b_e^tr): its principal part from the implicit function theorem on that return, its
// eigenvector-rotation part from divided differences written without cancellation, so that it
// is exact also at repeated principal stretches (J2Plasticity.cc). The AD update through the
// tensor log/exp that the tests keep as the oracle (tests/unit/j2_reference_update.h) agrees to
// round-off.
//
// The flow stress sigma_y(gamma_p,n + Delta gamma) is any law of IsotropicHardening.h: a smooth
// law (power, Voce) enters the Newton with its value and slope; a piecewise-linear one (linear,
// table) is solved segment by segment, so that no Newton iteration crosses a kink
// (J2PrincipalReturn.cc, docs/theory.md).
//
// State (7 doubles): C_p^-1 in deal.II's unrolled symmetric order (00, 11, 22, 01, 02, 12),
// then gamma_p. Units: GPa for moduli and stresses.
#pragma once

#include "materials/IsotropicHardening.h"
#include "materials/MaterialModel.h"
#include "materials/NeoHookean.h"

#include <deal.II/base/symmetric_tensor.h>

namespace indentsim::materials
{
  // Which stress enters the Huber-Mises-Hencky stress of eq. 4.
  enum class YieldStressMeasure
  {
    cauchy,   // s = dev sigma = dev tau / J (the paper's eq. 4)
    kirchhoff // s = dev tau
  };

  class J2Plasticity : public MaterialModel
  {
  public:
    static constexpr unsigned int n_state = 7;
    static constexpr unsigned int gamma_p_index = 6;

    // E, nu as NeoHookean; yield_stress sigma_y0 > 0 and hardening_modulus H >= 0 [GPa]
    // (linear hardening). Throws std::invalid_argument on invalid values.
    J2Plasticity(double young_modulus, double poisson_ratio, double yield_stress,
                 double             hardening_modulus,
                 YieldStressMeasure yield_stress_measure = YieldStressMeasure::cauchy);

    // Any hardening law of IsotropicHardening.h.
    J2Plasticity(double young_modulus, double poisson_ratio, IsotropicHardening hardening_law,
                 YieldStressMeasure yield_stress_measure = YieldStressMeasure::cauchy);

    unsigned int n_state_variables() const override { return n_state; }

    // C_p^-1 = I, gamma_p = 0.
    void initial_state(std::span<double> state) const override;

    UpdateStatus update(const Tensor<2, 3> &F, std::span<const double> state_old,
                        MaterialPointResponse &response, std::span<double> state_new,
                        bool compute_tangent = true) const override;

    double equivalent_plastic_strain(std::span<const double> state) const override
    {
      return state[gamma_p_index];
    }

    // The shear modulus mu [GPa].
    double reference_modulus() const override { return elasticity.shear_modulus(); }

    // Symmetric for the Kirchhoff measure only: the Cauchy measure's 1/J couples the volume
    // change into the return (tested).
    bool symmetric_tangent() const override { return measure == YieldStressMeasure::kirchhoff; }

    // A return mapping with its tangent against an elastic point, element kernel included.
    double relative_plastic_cost() const override { return 3.0; }

    // C_p^-1 stored in a state.
    static dealii::SymmetricTensor<2, 3> plastic_metric_inverse(std::span<const double> state);

    // sigma_y(gamma_p) (eq. 5 for the linear law).
    double flow_stress(const double gamma_p) const { return hardening.flow_stress(gamma_p); }

    // f = sqrt(3/2) |dev tau| / J^m - sigma_y(gamma_p) (eqs 4-6), m = 1 for the Cauchy and
    // m = 0 for the Kirchhoff measure [GPa].
    double yield_function(const Tensor<2, 3> &tau, double J, double gamma_p) const;

    YieldStressMeasure        yield_stress_measure() const { return measure; }
    const NeoHookean         &elastic_law() const { return elasticity; }
    const IsotropicHardening &hardening_law() const { return hardening; }

  private:
    NeoHookean         elasticity;
    IsotropicHardening hardening;
    YieldStressMeasure measure;
  };
} // namespace indentsim::materials
