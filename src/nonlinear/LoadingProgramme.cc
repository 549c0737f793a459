#include "nonlinear/LoadingProgramme.h"

#include <algorithm>
#include <cmath>

namespace indentsim::nonlinear
{
  namespace
  {
    // Increments of an unloading segment in uniform steps (unload_steps, 0: as loading).
    unsigned int uniform_unload_steps(const io::LoadingParameters &loading)
    {
      return loading.unload_steps > 0 ? loading.unload_steps : loading.steps;
    }

    bool is_force_control(const io::LoadingParameters &loading)
    {
      return loading.control == io::Control::force;
    }

    // The depths of the partial unloads: every multiple of their spacing below the maximum
    // depth (to 1e-9 of it: a partial unload at the maximum would repeat the full unload).
    std::vector<double> partial_unload_depths(const io::LoadingParameters &loading)
    {
      std::vector<double> depths;
      const double        every = loading.partial_unloads.every;
      if (!loading.partial_unloads.enabled())
        return depths;
      for (unsigned int k = 1; k * every < loading.max_depth * (1 - 1e-9); ++k)
        depths.push_back(k * every);
      return depths;
    }
  } // namespace

  const char *to_string(const SegmentKind kind)
  {
    switch (kind)
      {
      case SegmentKind::load:
        return "load";
      case SegmentKind::hold:
        return "hold";
      case SegmentKind::unload:
        return "unload";
      case SegmentKind::partial_unload:
        return "partial_unload";
      case SegmentKind::reload:
        return "reload";
      }
    return "?";
  }

  unsigned int expected_steps(const io::LoadingParameters &loading)
  {
    unsigned int unload_steps = 0;
    if (loading.unload)
      unload_steps = !is_force_control(loading) && loading.unload_points > 0
                         ? loading.unload_points + 1
                         : uniform_unload_steps(loading);
    const auto partial = partial_unload_depths(loading).size();
    return loading.cycles * (loading.steps + loading.hold_steps + unload_steps) +
           partial * (loading.partial_unloads.points + 2);
  }

  LoadingProgramme::LoadingProgramme(const io::LoadingParameters &loading)
    : force_control(is_force_control(loading))
    , maximum(force_control ? loading.max_force : loading.max_depth)
    , unload_points_(loading.unload_points)
    , partial_fraction_(loading.partial_unloads.fraction)
    , partial_points_(loading.partial_unloads.points)
    , geometric_(loading.spacing == io::Spacing::geometric && loading.steps > 1)
    , first_fraction_(loading.first_fraction)
    , ratio_(geometric_ ? std::pow(1 / loading.first_fraction, 1.0 / (loading.steps - 1)) : 1.0)
  {
    // Under force control, unloading stops at 1 % of the maximum force: towards zero force the
    // contact stiffness vanishes and the depth is no longer determined by the force.
    const double unload_target = force_control ? 0.01 * loading.max_force : 0.0;
    for (unsigned int cycle = 1; cycle <= loading.cycles; ++cycle)
      {
        if (cycle == 1)
          for (const double depth : partial_unload_depths(loading))
            {
              segments.push_back({SegmentKind::load, depth, loading.steps, cycle});
              segments.push_back({SegmentKind::partial_unload, 0.0, partial_points_, cycle});
              segments.push_back({SegmentKind::reload, depth, loading.steps, cycle});
            }
        segments.push_back({SegmentKind::load, maximum, loading.steps, cycle});
        if (loading.hold_steps > 0)
          segments.push_back({SegmentKind::hold, maximum, loading.hold_steps, cycle});
        if (loading.unload)
          segments.push_back(
              {SegmentKind::unload, unload_target, uniform_unload_steps(loading), cycle});
      }
  }

  double LoadingProgramme::nominal_increment(const Segment &segment, const double value) const
  {
    // A reload takes the increments of the loading it returns to.
    const bool loading = segment.kind == SegmentKind::load || segment.kind == SegmentKind::reload;
    if (!geometric_ || !loading)
      return maximum / segment.steps;
    const double first = first_fraction_ * maximum;
    // Below the first target (to 1e-9 of it), the rest of the way there.
    if (value < first * (1 - 1e-9))
      return first - value;
    return (ratio_ - 1) * value;
  }

  double LoadingProgramme::steps_to_target(const Segment &segment, const double from) const
  {
    if (segment.kind == SegmentKind::hold)
      return segment.steps;
    if (paced(segment))
      return (segment.kind == SegmentKind::partial_unload ? partial_points_ : unload_points_) + 1;
    const bool   loading = segment.kind != SegmentKind::unload;
    const double way = loading ? segment.target - from : from - segment.target;
    if (!(way > 0))
      return 0;
    if (!geometric_ || !loading)
      return way / (maximum / segment.steps);
    // Geometric: one increment to the first target, then a factor ratio per increment.
    const double first = first_fraction_ * maximum;
    if (from < first * (1 - 1e-9))
      return 1 + std::max(0.0, std::log(segment.target / first) / std::log(ratio_));
    return std::log(segment.target / from) / std::log(ratio_);
  }

  double LoadingProgramme::remaining_steps(const std::size_t index, const double value,
                                           const bool index_done) const
  {
    double remaining = 0;
    double from = value;
    for (std::size_t k = index; k < segments.size(); ++k)
      {
        const bool current = k == index;
        if (!current)
          {
            // A reload starts where its partial unload ended, just below its target: one step.
            const Segment &previous = segments[k - 1];
            from =
                previous.kind == SegmentKind::partial_unload ? segments[k].target : previous.target;
          }
        if (current && index_done)
          continue;
        const double steps = steps_to_target(segments[k], from);
        remaining += current ? steps : std::max(1.0, steps);
      }
    return remaining;
  }

  bool LoadingProgramme::paced(const Segment &segment) const
  {
    return segment.kind == SegmentKind::partial_unload ||
           (segment.kind == SegmentKind::unload && !force_control && unload_points_ > 0);
  }

  double LoadingProgramme::pacing_force(const Segment &segment, const double max_force,
                                        const double start_force) const
  {
    if (segment.kind == SegmentKind::partial_unload)
      return partial_fraction_ * start_force / partial_points_;
    return unload_points_ > 0 ? max_force / unload_points_ : 0.0;
  }

  double LoadingProgramme::partial_unload_target(const double start_force) const
  {
    return (1 - partial_fraction_) * start_force;
  }

  bool LoadingProgramme::partial_unload_done(const double force, const double start_force) const
  {
    const double step_drop = partial_fraction_ * start_force / partial_points_;
    return force <= partial_unload_target(start_force) + 0.05 * step_drop;
  }

  double LoadingProgramme::partial_unload_probe(const double start_depth) const
  {
    // The force falls by S dh; with S at most about 20 P / h for the unloading of a metal
    // (m / (1 - h_f / h) with m <= 2 and h_f / h <= 0.9), this probe lowers it by at most
    // 0.2 fraction P: well inside the partial unload.
    return 0.01 * partial_fraction_ * start_depth;
  }
} // namespace indentsim::nonlinear
