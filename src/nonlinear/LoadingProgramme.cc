#include "nonlinear/LoadingProgramme.h"

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
    return loading.cycles * (loading.steps + loading.hold_steps + unload_steps);
  }

  LoadingProgramme::LoadingProgramme(const io::LoadingParameters &loading)
    : force_control(is_force_control(loading))
    , maximum(force_control ? loading.max_force : loading.max_depth)
    , expected_steps(nonlinear::expected_steps(loading))
    , unload_points_(loading.unload_points)
    , geometric_(loading.spacing == io::Spacing::geometric && loading.steps > 1)
    , first_fraction_(loading.first_fraction)
    , ratio_(geometric_ ? std::pow(1 / loading.first_fraction, 1.0 / (loading.steps - 1)) : 1.0)
  {
    // Under force control, unloading stops at 1 % of the maximum force: towards zero force the
    // contact stiffness vanishes and the depth is no longer determined by the force.
    const double unload_target = force_control ? 0.01 * loading.max_force : 0.0;
    for (unsigned int cycle = 1; cycle <= loading.cycles; ++cycle)
      {
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
    if (!geometric_ || segment.kind != SegmentKind::load)
      return maximum / segment.steps;
    const double first = first_fraction_ * maximum;
    // Below the first target (to 1e-9 of it), the rest of the way there.
    if (value < first * (1 - 1e-9))
      return first - value;
    return (ratio_ - 1) * value;
  }

  bool LoadingProgramme::paced(const Segment &segment) const
  {
    return segment.kind == SegmentKind::unload && !force_control && unload_points_ > 0;
  }
} // namespace indentsim::nonlinear
