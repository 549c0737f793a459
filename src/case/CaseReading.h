// Internal to src/case/: the pieces shared by the reader, the validator and CaseFile.cc.
#pragma once

#include "case/CaseFile.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace indentsim::io
{
  // Where a value came from, so that checks after reading can name the line.
  struct ValueOrigin
  {
    int         line = -1; // 0-based, as yaml-cpp counts
    std::string text;      // the value as written
  };
  using OriginMap = std::map<std::string, ValueOrigin>;

  // Throws CaseFileError "source:line: message" (no line if `line` < 0).
  [[noreturn]] void fail(const std::string &source, int line, const std::string &message);

  // "section.key", or "key" on the top level.
  std::string key_path(const std::string &section, const std::string &key);

  // Reads the YAML tree into a Case (structure: unknown, duplicate and missing keys; types),
  // recording where each value was given in `origins`. Ranges are left to validate_values.
  Case read_case_tree(const YAML::Node &root, const std::string &source, OriginMap &origins);

  // The value checks of the schema and the checks that involve several keys; `origins` is null
  // for a case that was not read from a file. Designs the automatic mesh of
  // specimen.contact_elements: auto into `checked` (mesh/MeshDesign.h). Returns the indenter the
  // checks built. `for_run`: the case is about to be computed (run, check), which adds the
  // checks of what the solver cannot compute (a sharp pyramid); a case read for its description
  // (the indenter of an analysis, a checkpoint's resolved case) skips them.
  std::unique_ptr<indenter::IndenterSurface>
  validate_values(Case &checked, const OriginMap *origins, bool for_run = false);

  // Parses YAML text into a Case with the origins of its values, without the value checks.
  Case parse_case_text(const std::string &yaml_text, const std::string &source_name,
                       OriginMap &origins);
} // namespace indentsim::io
