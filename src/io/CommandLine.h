// The command line of the indentsim executable:
//   indentsim run CASE.yaml [--output DIR] [--overwrite] [--compare-j2]
//   indentsim check CASE.yaml [--output DIR] [--compare-j2]
//   indentsim study STUDY.yaml [--output DIR] [--ranks N] [--jobs J] [--dry-run] [--only NAMES]
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
    run,     // validate the case, prepare the output directory, compute
    check,   // validate the case and print the resolved case; no computation
    study,   // run the cases of a study file (skipping finished ones) and write a report
    help,
    version
  };

  struct CommandLineOptions
  {
    Command                    command = Command::help;
    std::string                case_file;         // run, check
    std::optional<std::string> output_directory;  // --output DIR: replaces output.directory
    bool                       overwrite = false; // --overwrite: replace an earlier run's results
    bool                       compare_j2 = false; // --compare-j2: sets the case's compare_j2

    // study (study/StudyRunner.h); output_directory above replaces the study's `output`.
    std::string              study_file;
    unsigned int             study_ranks = 1;   // --ranks N: MPI ranks of each case
    unsigned int             study_jobs = 1;    // --jobs J: cases run side by side
    bool                     study_dry_run = false; // --dry-run: print the plan, run nothing
    std::vector<std::string> study_only;        // --only NAME[,NAME...]: case names or groups
  };

  // `arguments` excludes the program name. Throws CommandLineError.
  CommandLineOptions parse_command_line(const std::vector<std::string> &arguments);

  // From main()'s arguments (argv[0] is skipped).
  CommandLineOptions parse_command_line(int argc, const char *const *argv);

  std::string usage_text(); // the short synopsis
  std::string help_text();  // synopsis, commands, options, units
  std::string version_text();
} // namespace indentsim::io
