#include "nonlinear/IncrementStatus.h"

namespace indentsim::nonlinear
{
  std::string to_string(const IncrementStatus status)
  {
    switch (status)
      {
      case IncrementStatus::converged:
        return "converged";
      case IncrementStatus::material_failure:
        return "material update failed";
      case IncrementStatus::contact_search_failure:
        return "contact search failed";
      case IncrementStatus::newton_diverged:
        return "Newton diverged";
      case IncrementStatus::linear_solver_failure:
        return "linear solver failed";
      case IncrementStatus::too_many_iterations:
        return "Newton iteration limit reached";
      case IncrementStatus::too_many_augmentations:
        return "augmentation limit reached";
      }
    return "unknown";
  }
} // namespace indentsim::nonlinear
