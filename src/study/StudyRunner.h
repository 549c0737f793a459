// Runs the cases of a study (study/StudyFile.h) and writes the report.
// Units everywhere: lengths um, forces mN, stresses and moduli GPa (1 GPa*um^2 = 1 mN).
//
// Each case runs as its own process, `indentsim run case.yaml --overwrite` (under
// `mpirun -np N` with --ranks N), in <output>/cases/<name>-<key>/, its console output in
// console.log there; up to `jobs` cases run side by side. When a case's process ends with exit
// code 0 and has written run_summary.json, the study writes study_case.json with
// "completed": true next to it: that file marks the case finished, and a rerun skips it.
// (run_summary.json alone does not: the tensile test writes it before its J2 comparison run.)
// A case without that mark was interrupted or failed: a rerun starts it again from its first
// increment (there is no in-run checkpoint). A failed case is reported and the others go on.
//
// At the end the runner writes <output>/study.json (the cases, their keys, status and report
// settings) and calls python/study_report.py, which writes report.md, report.html and the
// figures in <output>/figures/.
#pragma once

#include "study/StudyFile.h"

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace indentsim::study
{
  // File names in a case directory besides the run's own outputs (io::output_files).
  namespace study_files
  {
    inline constexpr const char *case_input = "case.yaml";      // what the process runs
    inline constexpr const char *console_log = "console.log";   // its stdout and stderr
    inline constexpr const char *case_mark = "study_case.json"; // "completed": true|false
    inline constexpr const char *index = "study.json";          // in the study's output
    inline constexpr const char *study_copy = "study.yaml";     // copy of the study file
  }                                                             // namespace study_files

  struct StudyRunSettings
  {
    unsigned int             ranks = 1;       // MPI ranks per case (mpirun -np)
    unsigned int             jobs = 1;        // cases run side by side
    bool                     dry_run = false; // list the cases and their state, run nothing
    std::vector<std::string> only;            // case names or groups to run; empty: all
    std::string              executable;      // indentsim binary for the cases ("": this one)
    std::string              report_script;   // "": python/study_report.py of the source tree
    // How a case's command is launched: "" runs it directly (under `mpirun -np N` for ranks > 1);
    // otherwise a template of words in which {command} stands for the case's command
    // (`indentsim run case.yaml ...`) and {ranks} for the number of ranks, e.g.
    // "srun -n {ranks} {command}" for a cluster's scheduler. Without {command} it is refused.
    std::string launcher;
    // A batch of another command's cases (indentsim calibrate): no plan table, no study.json,
    // no copy of the study file, no report; only the cases' own files.
    bool batch = false;
  };

  // The words of `launcher` (see StudyRunSettings) with {command} and {ranks} replaced. Throws
  // StudyFileError if the template has no {command} word.
  std::vector<std::string> launch_command(const std::string              &launcher,
                                          const std::vector<std::string> &command,
                                          unsigned int                    ranks);

  enum class CaseState
  {
    finished,   // study_case.json says completed and run_summary.json exists
    failed,     // study_case.json says not completed (the process failed)
    unfinished, // the directory exists without a mark: interrupted
    not_started // no directory yet
  };

  std::string to_string(CaseState state);

  // The state of a case from the files in its directory.
  CaseState case_state(const StudyCase &study_case);

  // The exit code a failed or finished case's process ended with (its study_case.json), or -1
  // if it has none (not run, unfinished).
  int case_exit_code(const StudyCase &study_case);
  // The last `count` lines of a text file, each indented as "    | line\n" (a failed case's
  // console output in a report); empty if the file cannot be read.
  std::string last_lines(const std::string &path, std::size_t count);
  // The topics of the warnings a finished run recorded (its run_summary.json, "warnings"), in
  // their order; empty if it has none or no summary.
  std::vector<std::string> warning_topics(const std::string &run_directory);

  // Exit codes of a process that never ran (the shell's: not executable, not found).
  inline constexpr int exit_cannot_execute = 126;
  inline constexpr int exit_not_found = 127;

  // Exit codes of StudyRunner::run().
  inline constexpr int exit_ok = 0;
  inline constexpr int exit_case_failed = 3;   // at least one case failed (the others ran)
  inline constexpr int exit_report_failed = 4; // every case ran, the report could not be written
  inline constexpr int exit_interrupted = 130; // SIGINT or SIGTERM: running cases were stopped

  class StudyRunner
  {
  public:
    // Throws StudyFileError if `settings.only` names no case or group of the study.
    StudyRunner(const Study &study, const StudyRunSettings &settings, std::ostream &out);

    // Runs the selected, unfinished cases, then writes study.json and the report. Returns one of
    // the exit codes above. Throws StudyFileError if the output directory cannot be written.
    int run();

  private:
    const Study      &study_;
    StudyRunSettings  settings_;
    std::ostream     &out_;
    std::vector<bool> selected_; // per case of the study

    // Where the run stands: per case its state and whether it ran now; counts of this run.
    struct Progress
    {
      std::vector<CaseState> states;
      std::vector<bool>      ran_now;
      std::size_t            n_to_run = 0, n_done = 0, n_failed = 0;
    };
    // A child process running a case.
    struct Running
    {
      std::size_t                           index; // in study_.cases
      pid_t                                 pid;
      std::chrono::steady_clock::time_point start;
    };

    void                     prepare_output_directory() const;
    std::vector<std::string> child_environment(const std::vector<std::string> &start) const;
    // Runs the cases `to_run` (indices), settings_.jobs at a time; false if SIGINT or SIGTERM
    // stopped them.
    bool run_cases(const std::vector<std::size_t> &to_run,
                   const std::vector<std::string> &variables, Progress &progress);
    // Starts a case's child; if it cannot start, the case is finished as failed (exit 127).
    std::optional<Running> start_case(std::size_t index, const std::vector<std::string> &variables,
                                      Progress &progress);
    // Writes the case's study_case.json mark and reports the outcome.
    void finish_case(const Running &job, int exit_code, Progress &progress);

    void                     print_plan(const std::vector<CaseState> &states) const;
    std::vector<std::string> case_command(const StudyCase &study_case) const;
    bool                     resumable(const StudyCase &study_case) const;
    void write_index(const std::vector<CaseState> &states, const std::vector<bool> &ran_now) const;
    int  write_report() const;
  };
} // namespace indentsim::study
