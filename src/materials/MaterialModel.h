// The one shape every constitutive model has (see docs/development.md, style):
//   update(F_new, state_old) -> {P, dP/dF, state_new, status}.
// Models know nothing about meshes, MPI or linear algebra, so each can be tested at a single
// material point. Units: stresses and moduli in GPa, strains dimensionless.
#pragma once

#include <deal.II/base/tensor.h>

#include <span>
#include <string>

namespace indentsim::materials
{
  using dealii::Tensor;

  // A numerical failure is reported, never thrown out of a quadrature loop: the load stepper
  // cuts the increment back and retries.
  enum class UpdateStatus
  {
    success,
    invalid_deformation, // det F <= 0 or not finite
    local_newton_failed  // return mapping did not converge
  };

  std::string to_string(UpdateStatus status);

  // Output of one material-point update (total-Lagrangian form).
  struct MaterialPointResponse
  {
    Tensor<2, 3> P;     // first Piola-Kirchhoff stress [GPa]
    Tensor<4, 3> dP_dF; // consistent (algorithmic) tangent dP/dF [GPa]
    Tensor<2, 3> tau;   // Kirchhoff stress tau = P F^T [GPa]
  };

  class MaterialModel
  {
  public:
    virtual ~MaterialModel() = default;

    // Number of doubles in this model's internal state at one material point.
    virtual unsigned int n_state_variables() const = 0;

    // Writes the state of virgin material into `state` (size n_state_variables()).
    virtual void initial_state(std::span<double> state) const = 0;

    // The same for a material point whose crystal lattice has the orientation g (Bunge, passive:
    // v_crystal = g v_sample; see materials/crystal/Orientation.h). Anisotropic models store it in the
    // state, so polycrystals need nothing but a per-point initial state; isotropic models ignore
    // it.
    virtual void oriented_initial_state(std::span<double>   state,
                                        const Tensor<2, 3> &orientation) const
    {
      (void)orientation;
      initial_state(state);
    }

    // The same for a material point at the depth `depth` [um] below the undeformed indented
    // surface: a depth-graded material (LayeredMaterial) picks the layer there; the others
    // ignore the depth.
    virtual void initial_state_at_depth(std::span<double> state, const Tensor<2, 3> &orientation,
                                        double depth) const
    {
      (void)depth;
      oriented_initial_state(state, orientation);
    }

    // Stress and consistent tangent for deformation gradient F at the end of the increment,
    // starting from the converged state of the previous increment. `state_new` receives the
    // updated internal state. Inputs are never modified. On entry `state_new` may hold a hint:
    // this point's state from an earlier evaluation of the same increment (the solvers keep the
    // previous global Newton iterate there, and state_old itself at the start of an increment).
    // A model may start its local iteration from it (CrystalPlasticity does); the result is
    // the same to the local tolerance whatever the hint holds, and an unusable hint is ignored.
    // When `compute_tangent` is false the tangent member of `response` is left untouched (used
    // for stress recovery and output).
    virtual UpdateStatus update(const Tensor<2, 3> &F, std::span<const double> state_old,
                                MaterialPointResponse &response, std::span<double> state_new,
                                bool compute_tangent = true) const = 0;

    // Equivalent (accumulated) plastic strain stored in a state, for output; 0 for elastic models.
    virtual double equivalent_plastic_strain(std::span<const double> state) const = 0;

    // Small-strain shear and bulk moduli [GPa], used to scale penalties and tolerances.
    virtual double reference_modulus() const = 0;

    // True when the consistent tangent has the major symmetry dP_iJ/dF_kL = dP_kL/dF_iJ
    // (hyperelastic models and associative plasticity with isotropic hardening); the Newton
    // systems are then symmetric and CG applies. The unit tests check the claim.
    virtual bool symmetric_tangent() const { return true; }

    // Cost of a quadrature point in plastic flow relative to an elastic one (element kernel
    // included), from bench/bench_material_point and whole runs on the project's machine. The
    // indentation mesh is partitioned over MPI ranks with the cells of the expected plastic
    // zone weighted by it, so that the rank holding the zone under the indenter is not the
    // slowest. 1 for hyperelastic models.
    virtual double relative_plastic_cost() const { return 1.0; }
  };
} // namespace indentsim::materials
