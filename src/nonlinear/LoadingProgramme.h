// The loading programme of an indentation run: per cycle, load to the maximum, hold it, unload;
// with partial unloads (io::PartialUnloads), the first loading stops at every multiple of their
// depth spacing for a partial unload and a reload to that depth. The control value is the
// indenter depth [um] or, under force control, the indenter force [mN] of the whole indent. Knows nothing of meshes: the stepper (IndentationRun.cc) walks it.
#pragma once

#include "case/Case.h"

#include <string>
#include <vector>

namespace indentsim::nonlinear
{
  enum class SegmentKind
  {
    load,
    hold,
    unload,
    partial_unload, // by a fraction of the force at its start (depth control)
    reload          // back to the depth where the partial unload started
  };
  // "load" | "hold" | "unload" | "partial_unload" | "reload": the `segment` column of
  // load_penetration.csv.
  const char *to_string(SegmentKind kind);

  struct Segment
  {
    SegmentKind kind;
    double      target; // control value at the end of the segment [um or mN]; a partial
                        // unload's end is a force (partial_unload_target), this is 0
    unsigned int steps; // nominal increments (hold: the steps held)
    unsigned int cycle; // 1, 2, ...
  };

  struct LoadingProgramme
  {
    explicit LoadingProgramme(const io::LoadingParameters &loading);

    bool                 force_control;
    double               maximum; // max_depth [um] or, under force control, max_force [mN]
    std::vector<Segment> segments;
    // Depth-controlled unloading is paced by force (unload_points > 0), and so is a partial
    // unload: see IncrementControl (nonlinear/CutBackStepper.h).
    bool paced(const Segment &segment) const;
    // The force drop per step of paced `segment`, from the largest force so far and the force
    // where the segment started [mN].
    double pacing_force(const Segment &segment, double max_force, double start_force) const;
    // The force at which a partial unload that started at `start_force` ends [mN].
    double partial_unload_target(double start_force) const;
    // A partial unload has ended at `force` (within 5 % of one step's force drop).
    bool partial_unload_done(double force, double start_force) const;
    // The depth increment of a partial unload's first step, a probe of the unloading
    // stiffness, from the depth where it starts [um].
    double partial_unload_probe(double start_depth) const;
    // The increment of the control value a step of `segment` takes from `value` without
    // cut-backs: maximum / steps (uniform spacing, holds, unloading), or under geometric
    // spacing of the loading the way to the first target (first_fraction of the maximum), then
    // (ratio - 1) value, with ratio = (1 / first_fraction)^(1 / (steps - 1)) so that `steps`
    // increments reach the maximum.
    double nominal_increment(const Segment &segment, double value) const;
    // The steps the rest of the programme takes without cut-backs (for the ETA), from the
    // control value `value` within segment `index` (`index_done`: that segment has just ended):
    // a load, reload or uniform unloading counts the nominal increments left to its target
    // (walked as nominal_increment walks them); a hold, a paced unloading and a partial unload
    // count their nominal steps whole, their progress not being the control value's. At the
    // programme's start this is expected_steps(loading).
    double remaining_steps(std::size_t index, double value, bool index_done) const;
    // " um" or " mN": the unit of the control value in messages.
    const char *unit() const { return force_control ? " mN" : " um"; }

  private:
    // The nominal increments `segment` takes from `from` to its target (fractional; >= 0).
    double steps_to_target(const Segment &segment, double from) const;

    unsigned int unload_points_;
    double       partial_fraction_;
    unsigned int partial_points_;
    bool         geometric_;
    double       first_fraction_;
    double       ratio_; // geometric: h_(k+1) / h_k
  };

  // The number of steps a loading programme is expected to take without cut-backs (for the
  // ETA): depth-controlled unloading is paced by force and takes about unload_points + 1, a
  // partial unload points + 1 and its reload one.
  unsigned int expected_steps(const io::LoadingParameters &loading);
} // namespace indentsim::nonlinear
