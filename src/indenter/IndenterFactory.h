// Builds the indenter surface named in the case file.
#pragma once

#include <indenter/IndenterSurface.h>
#include <io/Case.h>

#include <memory>

namespace indentsim::indenter
{
  // Throws std::invalid_argument for an unknown shape (read_case_file rejects it earlier).
  std::unique_ptr<IndenterSurface> create_indenter(const io::IndenterParameters &parameters);
} // namespace indentsim::indenter
