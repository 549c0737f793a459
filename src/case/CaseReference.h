// The case-file reference (docs/case-file-reference.md), generated from the schema.
#pragma once

#include <string>

namespace indentsim::io
{
  // The command that regenerates docs/case-file-reference.md from the repository root.
  inline constexpr const char *case_reference_command =
      "cmake --build build --target case_reference && build/case_reference > "
      "docs/case-file-reference.md";

  // The Markdown text: a header (units, how it is generated), one table per section with key,
  // type, unit, default, allowed values and description, and the notes that apply to several
  // keys.
  std::string case_file_reference_markdown();
} // namespace indentsim::io
