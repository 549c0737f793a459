// The record of an indentation run as it goes, on rank 0: load_penetration.csv (one row per
// converged step, written and flushed at once, so a stopped run leaves a valid curve), run.log
// (the same steps and notes: cut-backs, resume, stop, end) and the console's progress line.
// Units: um, mN, GPa, s.
//
// A write that fails (a full disk) is never silent: the recorder keeps the first failure
// (file and system reason) and stops writing; throw_if_failed() raises it. The problem calls
// that at a point where all MPI ranks meet (output::write_collectively), so that rank 0's
// failure stops every rank.
#pragma once

#include "nonlinear/StepRecord.h"
#include "output/OutputFile.h"

#include <optional>
#include <string>
#include <vector>

namespace indentsim::output
{
  // "12m05s"
  std::string format_duration(double seconds);

  // What the header of run.log states about the model.
  struct RunLogHeader
  {
    unsigned int n_cells = 0, n_dofs = 0, n_constrained_dofs = 0, n_ranks = 1;
  };

  class RunRecorder
  {
  public:
    // Writes both files in `directory` (an empty directory: records nothing) with their headers
    // and the rows of `records` (a resumed run's steps so far; the log gets the rows of the steps
    // after 0), each as a whole (the previous file stays until the new one is complete), then
    // opens them for the following rows. Throws OutputError.
    void open(const std::string &directory, const RunLogHeader &header,
              const std::vector<nonlinear::StepRecord> &records = {});
    bool is_open() const { return csv_.is_open(); }

    void csv_row(const nonlinear::StepRecord &record);
    // The step's line of run.log.
    void log_row(const nonlinear::StepRecord &record);
    // A comment line of run.log ("# " + text).
    void log_note(const std::string &text);

    // Throws the first failure of a write since open() (OutputError), if any.
    void throw_if_failed() const;

  private:
    // Flushes `file`; keeps its first failure.
    void flush(AppendFile &file);

    AppendFile                 csv_, log_;
    std::optional<OutputError> failure_;
  };

  // The console's line for a converged step: step, segment, depth, force, contact, Newton
  // iterations, augmentations, cut-backs, penetration, wall time and ETA.
  struct ProgressLine
  {
    const nonlinear::StepRecord &record;
    bool                         show_cycle;   // the programme has several cycles
    const double                *force_target; // force control: the step's target [mN]
    bool                         show_stick;   // friction: the sticking nodes
    double                       eta;          // [s]
  };
  std::ostream &operator<<(std::ostream &out, const ProgressLine &line);
} // namespace indentsim::output
