// The command line of the indentsim executable:
//   indentsim run CASE.yaml [--output DIR] [--overwrite | --resume] [--compare-j2]
//   indentsim check CASE.yaml [--output DIR] [--compare-j2]
//   indentsim analyze RUN_DIR_OR_CSV [--indenter SHAPE | --indenter-case CASE.yaml] [...]
//   indentsim study STUDY.yaml [--output DIR] [--ranks N] [--jobs J] [--dry-run] [--only NAMES]
//                              [--launcher TEMPLATE]
//   indentsim calibrate CONFIG.yaml [--output DIR] [--ranks N] [--jobs J] [--dry-run]
//                              [--launcher TEMPLATE]
//   indentsim --help | --version
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace indentsim::io
{
  // Bad usage; what() holds the problem followed by the usage text.
  class CommandLineError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  enum class Command
  {
    run,       // validate the case, prepare the output directory, compute
    check,     // validate the case and print the resolved case; no computation
    analyze,   // Oliver-Pharr analysis of a run directory or a load-penetration CSV
    study,     // run the cases of a study file (skipping finished ones) and write a report
    calibrate, // fit case keys to measured curves (calibration/CalibrationRunner.h)
    help,
    version
  };

  // indentsim analyze: what to analyse and how (analysis/OliverPharr.h).
  struct AnalyzeOptions
  {
    std::string           target;         // a run directory or a CSV of depth and force
    std::string           indenter_shape; // --indenter SHAPE: the shape with its default keys
    std::string           indenter_case;  // --indenter-case FILE: the indenter block of a case
    std::optional<double> epsilon;        // --epsilon: geometry factor (default by shape)
    double                beta = 1.0;     // --beta
    double                fit_lower = 0.5, fit_upper = 1.0;         // --fit-range LO,HI (of P_max)
    std::optional<double> sample_poisson_ratio;                     // --poisson NU
    std::optional<double> indenter_modulus;                         // --indenter-modulus E [GPa]
    double                indenter_poisson_ratio = 0.07;            // --indenter-poisson NU
    std::string depth_column, force_column, depth_unit, force_unit; // CSV columns and units
  };

  struct CommandLineOptions
  {
    Command                    command = Command::help;
    std::string                case_file;          // run, check
    std::optional<std::string> output_directory;   // --output DIR: replaces output.directory
    bool                       overwrite = false;  // --overwrite: replace an earlier run's results
    bool                       compare_j2 = false; // --compare-j2: sets the case's compare_j2
    bool                       resume = false;     // --resume: continue from the checkpoint
    AnalyzeOptions             analyze;            // analyze

    // study (study/StudyRunner.h); output_directory above replaces the study's `output`.
    std::string              study_file;
    unsigned int             study_ranks = 1;       // --ranks N: MPI ranks of each case
    unsigned int             study_jobs = 1;        // --jobs J: cases run side by side
    bool                     study_dry_run = false; // --dry-run: print the plan, run nothing
    std::vector<std::string> study_only;            // --only NAME[,NAME...]: case names or groups
    std::string study_launcher; // --launcher TEMPLATE: "srun -n {ranks} {command}"; "": direct
    // calibrate uses study_file (the calibration file), output_directory, study_ranks,
    // study_jobs, study_dry_run and study_launcher.
  };

  // `arguments` excludes the program name. Throws CommandLineError.
  CommandLineOptions parse_command_line(const std::vector<std::string> &arguments);

  // From main()'s arguments (argv[0] is skipped).
  CommandLineOptions parse_command_line(int argc, const char *const *argv);

  std::string usage_text(); // the short synopsis
  std::string help_text();  // synopsis, commands, options, units
  std::string version_text();
} // namespace indentsim::io
