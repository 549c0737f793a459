#include "nonlinear/CutBackStepper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace indentsim::nonlinear
{
  void IncrementControl::start_segment(const double nominal, const bool paced, const double probe)
  {
    increment = nominal;
    easy_steps = 0;
    segment_steps = 0;
    paced_increment = !paced      ? std::numeric_limits<double>::infinity()
                      : probe > 0 ? probe
                                  : nominal / 4;
  }

  double IncrementControl::step_size() const
  {
    return std::min(increment, paced_increment);
  }

  void IncrementControl::after_step(const bool easy, const bool paced, const double nominal_before,
                                    const double nominal_after, const double depth_before,
                                    const double depth_after, const double force_before,
                                    const double force_after, const double pacing_force,
                                    const double remaining_drop)
  {
    if (paced && depth_before - depth_after > 0 && force_before - force_after > 0)
      {
        const double compliance = (depth_before - depth_after) / (force_before - force_after);
        double       drop = pacing_force;
        if (std::isfinite(remaining_drop))
          {
            const double steps_left = std::max(1.0, std::round(remaining_drop / pacing_force));
            drop = remaining_drop / steps_left * (steps_left == 1 ? 1.05 : 1.0);
          }
        paced_increment = drop * compliance;
      }
    // The increment keeps its fraction of the nominal one (2^-k after k outstanding cut-backs).
    if (nominal_before > 0)
      increment *= nominal_after / nominal_before;
    easy_steps = easy ? easy_steps + 1 : 0;
    if (easy_steps >= 3)
      {
        increment *= 2;
        easy_steps = 0;
      }
  }

  double solve_with_cutbacks(const LoadingProgramme &programme, const Segment &segment,
                             IncrementControl &control, const double value, const unsigned int step,
                             const unsigned int                                  max_cutbacks,
                             const std::function<IncrementStatus(double, bool)> &solve,
                             const std::function<void()>                        &reject,
                             const std::function<void(const RetryEvent &)>      &report,
                             unsigned int                                       &cutbacks)
  {
    const bool hold = segment.kind == SegmentKind::hold;
    double     target = value;
    bool       extrapolate = !hold;
    cutbacks = 0;
    while (true)
      {
        if (segment.kind == SegmentKind::unload || segment.kind == SegmentKind::partial_unload)
          target = std::max(segment.target, value - control.step_size());
        else if (!hold)
          target = std::min(segment.target, value + control.increment);
        const IncrementStatus status = solve(target, extrapolate);
        if (status == IncrementStatus::converged)
          return target;
        reject();
        if (extrapolate && step > 0)
          {
            extrapolate = false;
            report({step + 1, target, status, true, 0.0});
            continue;
          }
        ++cutbacks;
        report({step + 1, target, status, false, control.step_size() / 2});
        if (cutbacks > max_cutbacks || hold)
          throw std::runtime_error(std::string(hold ? "hold" : "increment") + " to " +
                                   std::to_string(target) + programme.unit() + " failed after " +
                                   std::to_string(cutbacks - 1) + " cut-backs (" +
                                   to_string(status) + ")");
        control.increment = control.step_size() / 2;
      }
  }
} // namespace indentsim::nonlinear
