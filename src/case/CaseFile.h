// Reading, validating and writing YAML case files, and protecting an output directory.
//
// A case file is YAML in um, mN, GPa. Only two keys are required: `test` and `material.model`;
// every other key has the default listed in Case.h (and in the README). `specimen.f_bar`, when
// absent, defaults to true for `j2` and `crystal` and false for `neo_hookean`. A relative
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

#include <case/Case.h>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

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

  // Parses, fills defaults and validates. Throws CaseFileError.
  Case read_case_file(const std::string &path);

  // The same from YAML text; `source_name` stands for the file name in messages and in
  // Case::source_file.
  Case parse_case_yaml(const std::string &yaml_text, const std::string &source_name);

  // The value checks applied by read_case_file, for a case assembled or modified in code (for
  // example after `--output` replaced output.directory). Throws CaseFileError.
  void validate_case(const Case &resolved_case);

  // Every key (defaults filled in) as YAML with unit comments; read_case_file() of this text
  // gives back an identical Case (numbers are written in shortest round-trip form).
  std::string resolved_case_yaml(const Case &resolved_case);

  // The candidate closest to `word` if it is plausibly a typo of it, else "" (the "did you
  // mean" of the messages; also used by the study file reader).
  // The words separated by `separator`.
  std::string join(const std::vector<std::string> &words, const std::string &separator = ", ");
  // A YAML node as it was written, in one line (flow style for lists and maps); "(no value)"
  // for a missing or null node. For error messages.
  std::string node_text(const YAML::Node &node);

  std::string closest_name(const std::string &word, const std::vector<std::string> &candidates);

  // Writes resolved_case_yaml() to `path`. Throws CaseFileError if it cannot be written.
  void write_resolved_case(const Case &resolved_case, const std::string &path);

  // File names every run writes into its output directory; the writers use these names so that
  // the directory protection below recognizes an earlier run.
  namespace output_files
  {
    inline constexpr const char *load_penetration_csv = "load_penetration.csv";
    inline constexpr const char *load_penetration_png = "load_penetration.png";
    inline constexpr const char *stress_strain_csv    = "stress_strain.csv";    // tensile
    inline constexpr const char *stress_strain_j2_csv = "stress_strain_j2.csv"; // compare_j2
    inline constexpr const char *stress_strain_png    = "stress_strain.png";
    inline constexpr const char *resolved_case        = "resolved_case.yaml";
    inline constexpr const char *log                  = "run.log";
    inline constexpr const char *run_summary          = "run_summary.json"; // cost of the run
    // Pile-up of the top surface (solver/PileUp.h) at maximum depth and after unloading.
    inline constexpr const char *pileup_json          = "pileup.json";
    inline constexpr const char *pileup_max_depth_csv = "pileup_max_depth.csv";
    inline constexpr const char *pileup_unloaded_csv  = "pileup_unloaded.csv";
    inline constexpr const char *pileup_profiles_csv  = "pileup_profiles.csv";
    inline constexpr const char *pileup_max_depth_png = "pileup_max_depth.png";
    inline constexpr const char *pileup_unloaded_png  = "pileup_unloaded.png";
    inline constexpr const char *pileup_profiles_png  = "pileup_profiles.png";
    // Oliver-Pharr analysis of the unloading (analysis/OliverPharr.h).
    inline constexpr const char *oliver_pharr_json    = "oliver_pharr.json";
    inline constexpr const char *oliver_pharr_png     = "oliver_pharr.png";
    // The measured curve (output.experimental_curve) converted, and the comparison with it.
    inline constexpr const char *experimental_curve_csv     = "experimental_curve.csv";
    inline constexpr const char *experiment_comparison_json = "comparison_with_experiment.json";
    // Checkpoint of a stopped indentation run (rank_<r>.bin), read by `run --resume`; removed
    // when the run finishes.
    inline constexpr const char *checkpoint_directory = "checkpoint";
    // ParaView series: specimen.pvd, specimen_<step>.pvtu, specimen_<step>.<rank>.vtu.
    inline constexpr const char *paraview_basename = "specimen";

    // Exact names that mark an earlier run and are removed by --overwrite.
    inline constexpr std::array<const char *, 19> known_names = {
      {experimental_curve_csv, experiment_comparison_json, oliver_pharr_json, oliver_pharr_png,
       load_penetration_csv, load_penetration_png, stress_strain_csv, stress_strain_j2_csv,
       stress_strain_png, resolved_case, log, run_summary, pileup_json, pileup_max_depth_csv,
       pileup_unloaded_csv, pileup_profiles_csv, pileup_max_depth_png, pileup_unloaded_png,
       pileup_profiles_png}};
    // Files named paraview_basename* with these extensions are ours as well.
    inline constexpr std::array<const char *, 3> paraview_extensions = {
      {".pvd", ".vtu", ".pvtu"}};
  } // namespace output_files

  // Creates `directory` (with parents) and checks that it is writable by creating and removing a
  // probe file. If it already holds an earlier run's results (any of output_files) and
  // `overwrite` is false, throws CaseFileError telling the user to pass --overwrite or choose
  // another directory. With `overwrite` true, removes only our own known output files (the names
  // above, specimen*.pvd/.vtu/.pvtu and the folder `checkpoint` with its rank_*.bin files);
  // nothing else, and no other folder, is ever deleted.
  void prepare_output_directory(const std::string &directory, bool overwrite);
} // namespace indentsim::io
