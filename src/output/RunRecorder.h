// The record of an indentation run as it goes, on rank 0: load_penetration.csv (one row per
// converged step, written and flushed at once, so a stopped run leaves a valid curve), run.log
// (the same steps and notes: cut-backs, resume, stop, end) and the console's progress line.
// Units: um, mN, GPa, s.
#pragma once

#include "nonlinear/StepRecord.h"

#include <fstream>
#include <string>

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
    // Opens both files in `directory` (an empty directory: records nothing) and writes their
    // headers.
    void open(const std::string &directory, const RunLogHeader &header);
    bool is_open() const { return csv_.is_open(); }

    void csv_row(const nonlinear::StepRecord &record);
    // The step's line of run.log.
    void log_row(const nonlinear::StepRecord &record);
    // A comment line of run.log ("# " + text).
    void log_note(const std::string &text);

  private:
    std::ofstream csv_, log_;
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
