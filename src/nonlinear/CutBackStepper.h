// The step control of a loading segment, apart from any mesh: the size of the next increment of
// the control value (depth [um] or force [mN]) and the retries of a failed increment.
//
// A failed increment (any nonlinear::IncrementStatus but converged) is first retried from the
// converged state if it started from the extrapolated one (the predictor can put nodes deep
// into the indenter or far beyond yield), then halved, up to loading.max_cutbacks times in a
// row; a hold cannot be cut back. After a cut-back the increment grows again (doubled) only once
// three steps in a row have converged easily (no cut-back, at most 6 Newton iterations), so
// that a difficult stretch is not retried at every step; it never exceeds the programme's
// nominal increment. Geometric spacing raises the nominal increment step by step, and the
// increment keeps its fraction of it: the nominal one, or 2^-k of it after k cut-backs not yet
// grown back. Depth-controlled unloading is paced by force: each step lowers the force by about
// max_force / unload_points, with the depth increment from the last step's secant unloading
// stiffness (the first step takes a quarter of the nominal increment); the elastic recovery
// spans a small part of the depth, so uniform depth steps would leave the Oliver-Pharr fit a
// handful of points. A partial unload is paced the same way to equal drops of its force,
// after a small first probe of the stiffness, and lands on its target force.
#pragma once

#include "nonlinear/IncrementStatus.h"
#include "nonlinear/LoadingProgramme.h"

#include <functional>
#include <limits>
#include <string>

namespace indentsim::nonlinear
{
  // Where a segment's step control stands; a plain value (checkpoints store it byte for byte).
  struct IncrementControl
  {
    double       increment = 0;       // current increment of the control value
    double       paced_increment = 0; // force-paced unloading's increment (else infinity)
    unsigned int easy_steps = 0;      // easy steps in a row since the last growth
    unsigned int segment_steps = 0;   // converged steps of this segment

    // At the start of a segment of `nominal` increments; a paced segment's first increment is
    // `probe` if given (> 0), else a quarter of the nominal one.
    void start_segment(double nominal, bool paced, double probe = 0);
    // The increment the next attempt takes.
    double step_size() const;
    // After a converged step: scales the increment with the nominal one (before and after the
    // step), doubles it after easy steps, and paces unloading from the step's secant (depth and
    // force before and after) to force drops of `pacing_force`. With a finite `remaining_drop`
    // (a partial unload's force still to shed) the drops are evened out to land on it, the
    // last one 5 % beyond so that no sliver of a step is left.
    void after_step(bool easy, bool paced, double nominal_before, double nominal_after,
                    double depth_before, double depth_after, double force_before,
                    double force_after, double pacing_force,
                    double remaining_drop = std::numeric_limits<double>::infinity());
  };

  // What the stepper reports while it retries (for the console and run.log).
  struct RetryEvent
  {
    unsigned int    step;               // the step being attempted (1-based)
    double          value;              // its target control value
    IncrementStatus status;             // why it failed
    bool            from_extrapolation; // true: retried from the converged state next
    double          next_increment;     // otherwise: the increment after the cut-back
  };

  // Solves one step of `segment` from the control value `value` (step `step` + 1): calls
  // `solve(target, extrapolate)` until it converges, retrying and cutting back as described
  // above (`reject` restores the converged state after each failure). Returns the control value
  // reached and counts the cut-backs into `cutbacks`. Throws std::runtime_error naming the
  // target when the hold fails or max_cutbacks halvings do not help.
  double solve_with_cutbacks(const LoadingProgramme &programme, const Segment &segment,
                             IncrementControl &control, double value, unsigned int step,
                             unsigned int                                        max_cutbacks,
                             const std::function<IncrementStatus(double, bool)> &solve,
                             const std::function<void()>                        &reject,
                             const std::function<void(const RetryEvent &)>      &report,
                             unsigned int                                       &cutbacks);
} // namespace indentsim::nonlinear
