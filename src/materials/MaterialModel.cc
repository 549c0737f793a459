#include "materials/MaterialModel.h"

namespace indentsim::materials
{
  std::string to_string(const UpdateStatus status)
  {
    switch (status)
      {
      case UpdateStatus::success:
        return "success";
      case UpdateStatus::invalid_deformation:
        return "invalid deformation (det F <= 0 or not finite)";
      case UpdateStatus::local_newton_failed:
        return "local Newton (return mapping) did not converge";
      }
    return "unknown UpdateStatus";
  }
} // namespace indentsim::materials
