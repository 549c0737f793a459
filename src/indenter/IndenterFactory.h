// Builds the indenter surface named in the case file.
#pragma once

#include "case/IndenterParameters.h"
#include "indenter/IndenterSurface.h"

#include <memory>

namespace indentsim::indenter
{
  // The shape named by parameters.shape with the keys that belong to it (the other keys are
  // ignored). Throws std::invalid_argument for an unknown shape or an out-of-range value
  // (read_case_file rejects both earlier) and ProfileTableError for a bad profile_table file.
  std::unique_ptr<IndenterSurface> create_indenter(const io::IndenterParameters &parameters);
} // namespace indentsim::indenter
