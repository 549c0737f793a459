// The one place that maps indenter.shape to an IndenterSurface implementation.
#include <indenter/IndenterFactory.h>
#include <indenter/RoundedCone.h>

#include <stdexcept>

namespace indentsim::indenter
{
  std::unique_ptr<IndenterSurface> create_indenter(const io::IndenterParameters &parameters)
  {
    if (parameters.shape == "rounded_cone")
      return std::make_unique<RoundedCone>(parameters.a, parameters.delta);
    throw std::invalid_argument("indenter.shape = '" + parameters.shape +
                                "': unknown indenter shape; allowed: rounded_cone");
  }
} // namespace indentsim::indenter
