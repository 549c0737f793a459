// Study files: a named set of cases, each a base case file plus overrides, and the settings of
// the report that `indentsim study` writes (study/StudyRunner.h, python/study_report.py).
// Units everywhere: lengths um, forces mN, stresses and moduli GPa (1 GPa*um^2 = 1 mN).
//
// A study file is YAML:
//
//   output: results/study_paper          # relative to the working directory (like a case file)
//   report:                              # optional; what the report compares against
//     title: "..."
//     depth_at_force_mN: 821.2           # depth at which the finest J2 curve reaches this force
//     tensile_strains: [0.02, 0.05, 0.1, 0.2]
//     paper_max_depth_um: 6.0
//     paper_forces_mN: {mesh_j2: {48: 821.2, 72: 822.2}, mesh_crystal: {48: 830.3, 72: 829.4}}
//     paper_note: "..."
//   cases:
//     - name: j2_n48                     # letters, digits, _ and -; unique
//       base: ../examples/paper_j2_n12.yaml   # relative to the study file
//       overrides: {specimen: {contact_elements: 48}}
//       group: mesh_j2                   # or a list of groups
//       label: "J2, 48x48"               # legend entry (default: the name)
//
// The overrides are merged onto the base YAML: maps key by key, anything else (numbers, lists,
// words) replaced, a null value (~) removes the key (its default applies). material.orientation
// is replaced as a whole, since its keys are alternatives. The merged text goes through the case
// file reader and validator (case/CaseFile.h), so a case is checked exactly as `indentsim run`
// would check it; output.directory is set by the study: <output>/cases/<name>-<key>.
//
// The key of a case is the FNV-1a 64-bit hash (16 hex digits) of its resolved case in a
// canonical form: every key path with its value, sorted, without comments, without
// output.directory and solver.threads (neither changes a result). Two files that resolve to the
// same case give the same key, whatever their key order, comments, number spelling (6 or 6.0)
// or defaults written out; any changed value gives another key.
//
// Bad input raises StudyFileError naming the study file and line, the case, the key, the value
// and what is allowed.
#pragma once

#include "case/Case.h"
#include "case/CaseFile.h"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace indentsim::study
{
  // Bad input in a study file (or in a case it refers to). Derives from CaseFileError, so the
  // application reports it as bad input (exit code 1).
  class StudyFileError : public io::CaseFileError
  {
  public:
    using io::CaseFileError::CaseFileError;
  };

  // The groups the report knows: the tensile calibration (test: tensile), the mesh convergence
  // of J2 and of crystal plasticity (indentation, one case per contact_elements) and the
  // orientations (crystal indentation: curves and pile-up maps), and the irradiated layer against
  // the pristine metal (indentation with partial unloads; the first case of the group is the
  // pristine reference).
  inline const std::vector<std::string> known_groups = {
      "tensile", "mesh_j2", "mesh_crystal", "orientation", "irradiation_j2", "irradiation_crystal"};

  struct StudyCase
  {
    std::string              name;
    std::vector<std::string> groups;
    std::string              label;          // legend entry
    std::string              base_file;      // as resolved from the study file's directory
    std::string              overrides_text; // the overrides as written (flow YAML), "{}" if none
    io::Case                 resolved;       // output.directory = directory
    std::string              key;            // case_key(resolved)
    std::string              directory;      // <output>/cases/<name>-<key>, absolute
    int                      line = -1;      // 0-based line of the entry in the study file
  };

  struct StudyReportSettings
  {
    std::string         title = "indentsim study";
    double              depth_at_force_mN = 0.; // 0: not reported
    std::vector<double> tensile_strains = {0.02, 0.05, 0.1, 0.2};
    double              paper_max_depth_um = 0.; // 0: not stated
    // group (mesh_j2 | mesh_crystal) -> contact elements -> force at maximum depth [mN]
    std::map<std::string, std::map<unsigned int, double>> paper_forces_mN;
    std::string                                           paper_note;
  };

  struct Study
  {
    std::string            source_file;      // the study file as given
    std::string            output_directory; // absolute
    StudyReportSettings    report;
    std::vector<StudyCase> cases;
  };

  // Reads and validates a study file and every case in it. `output_override` (the command
  // line's --output), if not empty, replaces `output`. Throws StudyFileError.
  Study read_study_file(const std::string &path, const std::string &output_override = "");

  // The same from YAML text; base paths are relative to the directory of `source_name`.
  Study parse_study_yaml(const std::string &yaml_text, const std::string &source_name,
                         const std::string &output_override = "");

  // `overrides` merged onto a copy of `base` (see the rules above); neither is modified.
  YAML::Node merge_overrides(const YAML::Node &base, const YAML::Node &overrides);

  // The canonical text that the key hashes: io::canonical_case_text (case/Fingerprint.h), one
  // "path: value" line per key that determines the results, sorted.
  std::string canonical_case_text(const io::Case &resolved_case);

  // 64-bit FNV-1a of `text`.
  std::uint64_t fnv1a_64(const std::string &text);

  // The case key: io::case_fingerprint (case/Fingerprint.h) as 16 lower-case hex digits.
  std::string case_key(const io::Case &resolved_case);
} // namespace indentsim::study
