// Reading, validating and writing YAML case files.
//
// A case file is YAML in um, mN, GPa. Only two keys are required: `test` and `material.model`;
// every other key has the default declared in the schema (Schema.cc, listed in
// docs/case-file-reference.md). `specimen.f_bar`, when
// absent, defaults to true for `j2` and `crystal` and for `neo_hookean` with poisson_ratio >
// 0.45 (plain hexahedra lock when nearly incompressible), false for other `neo_hookean` cases.
// A case file holds one YAML document; binary content and tabs in the indentation are named. A relative
// `output.directory` is relative to the current working directory (not to the case file).
// The crystal keys (material.lattice, .elastic, .hardening, .yield_exponent_n, .orientation)
// are read and checked for every model but used only by `crystal`; `material.orientation` is
// either `euler_bunge_deg` or `surface_normal` + `reference_direction`, and the resolved case
// writes the form that was given. The indenter keys likewise are read and checked for every
// shape but used only by their shapes; `indenter.file` is relative to the case file's directory
// (stored as an absolute path) and read only for `shape: profile_table`. `specimen.symmetry:
// quarter` needs an indenter with the mirror planes x = 0 and y = 0 (not berkovich, vickers only
// at multiples of 45 deg).
//
// Bad input never reaches the solver: every problem raises one CaseFileError whose message names
// the file, the key path (e.g. `material.poisson_ratio`), the offending value and what is allowed.
#pragma once

#include "case/Case.h"
#include "case/OutputDirectory.h"

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace indentsim::indenter
{
  class IndenterSurface;
}

namespace YAML
{
  class Node;
}

namespace indentsim::io
{
  // Bad input or I/O concerning a case file or an output directory.
  class CaseFileError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // Above this Poisson ratio a neo-Hookean case gets the F-bar element by default
  // (specimen.f_bar not given): plain trilinear hexahedra lock when nearly incompressible.
  inline constexpr double nearly_incompressible_poisson_ratio = 0.45;

  // Parses, fills defaults and validates. Throws CaseFileError.
  Case read_case_file(const std::string &path);

  // The same from YAML text; `source_name` stands for the file name in messages and in
  // Case::source_file.
  Case parse_case_yaml(const std::string &yaml_text, const std::string &source_name);

  // A case ready to run, and the indenter its validation built (the run takes it over, so that
  // each indenter is built once per run).
  struct RunCase
  {
    Case                                             the_case;
    std::shared_ptr<const indenter::IndenterSurface> indenter;
  };
  // Reads `path` as read_case_file does, applies `adjust` (the command line's changes; it
  // returns the key paths it set, whose messages then name no line of the file) and validates
  // once. Throws CaseFileError.
  RunCase read_case_for_run(const std::string                                     &path,
                            const std::function<std::vector<std::string>(Case &)> &adjust);

  // The value checks applied by read_case_file, for a case assembled or modified in code (for
  // example after `--output` replaced output.directory). Throws CaseFileError.
  void validate_case(const Case &resolved_case);

  // Every key (defaults filled in) as YAML with unit comments; read_case_file() of this text
  // gives back an identical Case (numbers are written in shortest round-trip form).
  std::string resolved_case_yaml(const Case &resolved_case);

  // The words separated by `separator`.
  std::string join(const std::vector<std::string> &words, const std::string &separator = ", ");
  // A YAML node as it was written, in one line (flow style for lists and maps); "(no value)"
  // for a missing or null node. For error messages.
  std::string node_text(const YAML::Node &node);

  // The candidate closest to `word` if it is plausibly a typo of it, else "" (the "did you
  // mean" of the messages; also used by the study file reader).
  std::string closest_name(const std::string &word, const std::vector<std::string> &candidates);

  // What the YAML parser would report only generically, found in the text of a case or study
  // file: binary content (a NUL byte, or bytes that are not UTF-8) or a tab in the indentation
  // of a line. The first one as {0-based line, message}; std::nullopt if none.
  std::optional<std::pair<int, std::string>> yaml_text_problem(const std::string &text);

  // The 0-based line of the '---' that starts a second YAML document in `text` (a '---' after
  // the first document's content), -1 if there is none.
  int second_document_line(const std::string &text);

  // Writes resolved_case_yaml() to `path` (through a temporary file: a previous file stays
  // until the new one is complete). Throws output::OutputError if it cannot be written.
  void write_resolved_case(const Case &resolved_case, const std::string &path);

} // namespace indentsim::io
