// The forward runs of a calibration: for a parameter vector, every case its data need (the
// base case, and each data set's own case), with the parameters written into them, run as a
// batch of study cases (study/StudyRunner.h): each a process `indentsim run`, keyed by the hash
// of its resolved case in <output>/forward/cases/<name>-<key>/, cached (a case finished earlier,
// in this calibration or an interrupted one, is not run again), --jobs side by side, --ranks
// under MPI, or through a --launcher template. Forward runs draw no plots (output.plots: false).
// Units: those of the parameters' keys (um, mN, GPa).
#pragma once

#include "calibration/CalibrationFile.h"
#include "study/StudyFile.h"
#include "study/StudyRunner.h"

#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace indentsim::calibration
{
  using Point = std::vector<double>; // one value per parameter, in the calibration's order

  // The study of `points` (distinct) and, for point i, index[i][k]: its k-th forward case
  // (in the order of calibration.forward_cases()) among study.cases. A case is named
  // "c<k>_p<i>" after the first point that needs it: points that differ only in keys the case
  // does not see (a layer's key in a tensile case) share it. A case's directory is c<k>-<key>,
  // the same for the same values at whichever iteration they come. Throws CalibrationFileError
  // (from the case reader) if a case is refused.
  struct ForwardBatch
  {
    study::Study                          study;
    std::vector<std::vector<std::size_t>> index;
  };
  ForwardBatch forward_study(const Calibration &calibration, const std::vector<Point> &points);

  // One resolved forward case at `point` (the k-th of calibration.forward_cases()).
  io::Case forward_case(const Calibration &calibration, const Point &point, std::size_t k);

  class ForwardRuns
  {
  public:
    // `log` receives the study runner's lines (which case runs, how it ended); `warnings` a
    // warning with the last lines of each run that fails.
    ForwardRuns(const Calibration &calibration, const study::StudyRunSettings &settings,
                std::ostream &log, std::ostream &warnings);

    // For each point, the run directory of each forward case, or nullopt for a point whose
    // cases did not all finish. Throws study::StudyFileError when interrupted (SIGINT/SIGTERM),
    // std::runtime_error when a case's process could not be started at all (exit code 126/127).
    std::vector<std::optional<std::vector<std::string>>> run(const std::vector<Point> &points);

    unsigned int runs_computed() const { return computed_; } // processes that ran and finished
    unsigned int runs_reused() const { return reused_; }     // found finished (cached)
    unsigned int runs_failed() const { return failed_; }
    // Of the runs computed, those whose run_summary.json lists warnings, and the number of runs
    // that warned on each topic (study::warning_topics).
    unsigned int                               runs_warned() const { return warned_; }
    const std::map<std::string, unsigned int> &warned_topics() const { return warned_topics_; }

    // The run directory of each forward case at `point`, where run() puts (or found) it.
    std::vector<std::string> directories(const Point &point) const;

  private:
    const Calibration                  &calibration_;
    study::StudyRunSettings             settings_;
    std::ostream                       &log_, &warnings_;
    unsigned int                        computed_ = 0, reused_ = 0, failed_ = 0, warned_ = 0;
    std::map<std::string, unsigned int> warned_topics_;
  };
} // namespace indentsim::calibration
