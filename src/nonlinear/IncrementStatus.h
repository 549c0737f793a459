// The outcome of solving one load increment, shared by the load steppers (indentation and
// tensile): anything but `converged` makes the stepper cut the increment back and retry.
#pragma once

#include <string>

namespace indentsim::nonlinear
{
  enum class IncrementStatus
  {
    converged,
    material_failure,       // a material point returned a failure status
    contact_search_failure, // the closest-point projection onto the indenter failed
    newton_diverged,
    linear_solver_failure, // the linear solver of a Newton iteration did not converge
    too_many_iterations,
    too_many_augmentations // augmented-Lagrangian passes exhausted
  };

  std::string to_string(IncrementStatus status);
} // namespace indentsim::nonlinear
