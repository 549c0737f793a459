// Compressible neo-Hookean hyperelasticity, the elastic law of the paper (eq. 2):
//   W = mu/2 (I1 - 3 - log I3) + lambda/4 (I3 - 1 - log I3),  I1 = tr b, I3 = det b = J^2,
// with b = F F^T. Kirchhoff stress (eq. 3, tau = 2 b dW/db):
//   tau = mu (b - 1) + lambda/2 (J^2 - 1) 1,   P = tau F^-T.
// The same law, evaluated in b_e = F C_p^-1 F^T with a frozen plastic metric, is the elastic
// predictor and the elastic response of J2Plasticity, so that part is exposed here too.
#pragma once

#include "materials/MaterialModel.h"

#include <deal.II/base/symmetric_tensor.h>

namespace indentsim::materials
{
  // True if every entry of F is finite and det F > 0; then J_minus_one = det F - 1 (computed
  // without cancellation). Otherwise the update must return UpdateStatus::invalid_deformation.
  bool admissible_deformation(const Tensor<2, 3> &F, double &J_minus_one);

  class NeoHookean : public MaterialModel
  {
  public:
    // Lame constants from Young's modulus E [GPa] and Poisson's ratio nu (-1 < nu < 0.5):
    // mu = E / (2 (1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu)). Throws on invalid values.
    NeoHookean(double young_modulus, double poisson_ratio);

    unsigned int n_state_variables() const override { return 0; }
    void         initial_state(std::span<double> /*state*/) const override {}

    UpdateStatus update(const Tensor<2, 3> &F, std::span<const double> state_old,
                        MaterialPointResponse &response, std::span<double> state_new,
                        bool compute_tangent = true) const override;

    double equivalent_plastic_strain(std::span<const double> /*state*/) const override
    {
      return 0.0;
    }

    // The shear modulus mu [GPa].
    double reference_modulus() const override { return mu; }

    double shear_modulus() const { return mu; }
    double lame_lambda() const { return lambda; }

    // Strain energy density W(F) of eq. 2 [GPa = mJ/mm^3], evaluated with H = F - I and
    // log1p(J - 1) so that small strains keep their relative accuracy; +inf for J <= 0.
    double energy(const Tensor<2, 3> &F) const;

    // Kirchhoff stress for the elastic left Cauchy-Green tensor b_e and J = det F (eq. 3):
    // tau = mu (b_e - 1) + lambda/2 (J^2 - 1) 1, written with J - 1 for round-off safety.
    dealii::SymmetricTensor<2, 3> kirchhoff_stress(const dealii::SymmetricTensor<2, 3> &b_e,
                                                   double J_minus_one) const;

    // tau, P and (if asked) the closed-form dP/dF for b_e = F C_p^-1 F^T with C_p^-1 held
    // fixed: P = mu (F C_p^-1 - F^-T) + lambda/2 (J^2 - 1) F^-T and
    //   dP_iJ/dF_kL = mu delta_ik C_p^-1_LJ + (mu - lambda/2 (J^2 - 1)) F^-1_Li F^-1_Jk
    //                 + lambda J^2 F^-1_Ji F^-1_Lk.
    // The caller has checked J = 1 + J_minus_one > 0. No allocation.
    void elastic_response(const Tensor<2, 3> &F, const dealii::SymmetricTensor<2, 3> &C_p_inverse,
                          double J_minus_one, MaterialPointResponse &response,
                          bool compute_tangent) const;

  private:
    double mu;     // shear modulus [GPa]
    double lambda; // first Lame constant [GPa]
  };
} // namespace indentsim::materials
