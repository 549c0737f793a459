// The mesh-free parts of the nonlinear solver: the loading programme, the cut-back stepper and
// the scalar rules of the Newton iteration, each against hand-computed values.
// Units: um, mN.
#include "case/Case.h"
#include "nonlinear/CutBackStepper.h"
#include "nonlinear/LoadingProgramme.h"
#include "nonlinear/NewtonSteps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

using namespace indentsim;
using namespace indentsim::nonlinear;

namespace
{
  // Two cycles of loading to 2 um in 10 steps, a hold of 3 and an unloading of 5.
  io::LoadingParameters two_cycles()
  {
    io::LoadingParameters loading;
    loading.max_depth = 2.0;
    loading.steps = 10;
    loading.hold_steps = 3;
    loading.cycles = 2;
    loading.unload_steps = 5;
    return loading;
  }

  // Loading to 1.5 um in 30 steps with a partial unload (20 % of the force in 4 steps) every
  // 0.5 um, then paced unloading in 10 force steps.
  io::LoadingParameters partial_unloads()
  {
    io::LoadingParameters loading;
    loading.max_depth = 1.5;
    loading.steps = 30;
    loading.unload_points = 10;
    loading.partial_unloads = {0.5, 0.2, 4};
    return loading;
  }
} // namespace

// Two cycles of load, hold and unload appear in that order with their targets and step counts;
// force control unloads to 1 % of the maximum force.
TEST(LoadingProgramme, CyclesOfLoadHoldUnload)
{
  io::LoadingParameters  loading = two_cycles();
  const LoadingProgramme depth(loading);
  ASSERT_EQ(depth.segments.size(), 6u);
  EXPECT_FALSE(depth.force_control);
  EXPECT_EQ(depth.maximum, 2.0);
  const SegmentKind  kinds[3] = {SegmentKind::load, SegmentKind::hold, SegmentKind::unload};
  const unsigned int steps[3] = {10, 3, 5};
  const double       targets[3] = {2.0, 2.0, 0.0};
  for (unsigned int i = 0; i < 6; ++i)
    {
      EXPECT_EQ(depth.segments[i].kind, kinds[i % 3]);
      EXPECT_EQ(depth.segments[i].steps, steps[i % 3]);
      EXPECT_EQ(depth.segments[i].target, targets[i % 3]);
      EXPECT_EQ(depth.segments[i].cycle, i / 3 + 1);
    }
  EXPECT_TRUE(depth.paced(depth.segments[2]));
  EXPECT_FALSE(depth.paced(depth.segments[0]));
  // Paced unloading takes unload_points + 1 steps: 2 (10 + 3 + 21).
  EXPECT_EQ(expected_steps(loading), 68u);
  EXPECT_STREQ(to_string(SegmentKind::hold), "hold");

  loading.control = "force";
  loading.max_force = 500.0;
  const LoadingProgramme force(loading);
  EXPECT_TRUE(force.force_control);
  EXPECT_EQ(force.maximum, 500.0);
  EXPECT_EQ(force.segments[2].target, 5.0);
  EXPECT_FALSE(force.paced(force.segments[2]));
  EXPECT_EQ(expected_steps(loading), 2u * (10 + 3 + 5));
  EXPECT_STREQ(force.unit(), " mN");
}

namespace
{
  // A stepper run against a solver that fails for targets beyond `limit` (from the
  // extrapolated start only, if `extrapolation_only`).
  struct FakeSolver
  {
    double              limit;
    bool                extrapolation_only = false;
    std::vector<double> targets;
    std::vector<bool>   extrapolated;
    unsigned int        rejections = 0;

    IncrementStatus operator()(const double target, const bool extrapolate)
    {
      targets.push_back(target);
      extrapolated.push_back(extrapolate);
      const bool fails = target > limit && (extrapolate || !extrapolation_only);
      return fails ? IncrementStatus::newton_diverged : IncrementStatus::converged;
    }
  };

  io::LoadingParameters loading_to(const double max_depth, const unsigned int steps)
  {
    io::LoadingParameters loading;
    loading.max_depth = max_depth;
    loading.steps = steps;
    loading.unload = false;
    return loading;
  }
} // namespace

// A failed extrapolated increment is retried from the converged state before any cut-back.
TEST(CutBackStepper, RetriesFromTheConvergedStateFirst)
{
  const LoadingProgramme programme(loading_to(1.0, 4));
  IncrementControl       control;
  control.start_segment(0.25, false);
  FakeSolver              solver{0.6, true};
  std::vector<RetryEvent> events;
  unsigned int            cutbacks = 7;
  const double            reached = solve_with_cutbacks(
                 programme, programme.segments[0], control, 0.5, 2, 8,
                 [&](double t, bool e) { return solver(t, e); }, [&]() { ++solver.rejections; },
                 [&](const RetryEvent &event) { events.push_back(event); }, cutbacks);
  EXPECT_EQ(reached, 0.75);
  EXPECT_EQ(cutbacks, 0u);
  EXPECT_EQ(solver.rejections, 1u);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_TRUE(events[0].from_extrapolation);
  EXPECT_EQ(events[0].step, 3u);
  EXPECT_EQ(solver.extrapolated, (std::vector<bool>{true, false}));
}

// Failures halve the increment until it converges; too many halvings throw, naming the target.
TEST(CutBackStepper, HalvesTheIncrementAndGivesUp)
{
  const LoadingProgramme programme(loading_to(1.0, 4));
  IncrementControl       control;
  control.start_segment(0.25, false);
  FakeSolver   solver{0.3};
  unsigned int cutbacks = 0;
  // From 0.25: 0.5 fails (twice: extrapolated, then converged start), 0.375 fails, 0.3125 fails,
  // 0.28125 converges.
  const double reached = solve_with_cutbacks(
      programme, programme.segments[0], control, 0.25, 1, 8,
      [&](double t, bool e) { return solver(t, e); }, []() {}, [](const RetryEvent &) {}, cutbacks);
  EXPECT_EQ(reached, 0.28125);
  EXPECT_EQ(cutbacks, 3u);
  EXPECT_EQ(control.increment, 0.03125);
  EXPECT_EQ(solver.targets, (std::vector<double>{0.5, 0.5, 0.375, 0.3125, 0.28125}));

  control.start_segment(0.25, false);
  FakeSolver never{-1.0};
  EXPECT_THROW(solve_with_cutbacks(
                   programme, programme.segments[0], control, 0.25, 0, 2,
                   [&](double t, bool e) { return never(t, e); }, []() {},
                   [](const RetryEvent &) {}, cutbacks),
               std::runtime_error);
  EXPECT_EQ(cutbacks, 3u);
}

// The increment doubles after three easy steps in a row; paced unloading takes its depth
// increment from the secant stiffness of the last step.
TEST(CutBackStepper, GrowsAfterEasyStepsAndPacesUnloading)
{
  IncrementControl control;
  control.start_segment(0.4, true);
  EXPECT_EQ(control.step_size(), 0.1);
  control.increment = 0.05;
  control.after_step(true, false, 0.1, 0.1, 0, 0, 0, 0, 0);
  control.after_step(true, false, 0.1, 0.1, 0, 0, 0, 0, 0);
  EXPECT_EQ(control.increment, 0.05);
  control.after_step(true, false, 0.1, 0.1, 0, 0, 0, 0, 0);
  EXPECT_EQ(control.increment, 0.1);
  EXPECT_EQ(control.easy_steps, 0u);
  control.after_step(false, true, 0.1, 0.1, 6.0, 5.9, 800.0, 600.0, 40.0);
  EXPECT_EQ(control.easy_steps, 0u);
  EXPECT_NEAR(control.paced_increment, 40.0 * 0.1 / 200.0, 1e-15);
}

// Geometric spacing: the first increment to first_fraction of the maximum, then increments in
// the ratio rho = (1/first_fraction)^(1/(steps-1)) to the value reached, so that exactly `steps`
// increments reach the maximum (h_k = h_max rho^(k - steps)); unloading keeps the uniform nominal
// increment.
TEST(LoadingProgramme, GeometricSpacingReachesTheMaximumInItsSteps)
{
  io::LoadingParameters loading;
  loading.max_depth = 6.0;
  loading.steps = 40;
  loading.spacing = io::Spacing::geometric;
  loading.first_fraction = 1.0 / 64;
  const LoadingProgramme programme(loading);
  const Segment         &load = programme.segments.at(0);
  const double           rho = std::pow(64.0, 1.0 / 39);
  double                 h = 0;
  for (unsigned int k = 1; k <= loading.steps; ++k)
    {
      const double increment = programme.nominal_increment(load, h);
      if (k == 1)
        EXPECT_DOUBLE_EQ(increment, 6.0 / 64);
      else
        EXPECT_NEAR(increment / h, rho - 1, 1e-13) << "step " << k;
      h = std::min(load.target, h + increment);
      EXPECT_NEAR(h, 6.0 * std::pow(rho, double(k) - 40), 1e-12) << "step " << k;
    }
  EXPECT_NEAR(h, 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(programme.nominal_increment(programme.segments.at(1), 6.0), 6.0 / 40);

  loading.spacing = io::Spacing::uniform;
  const LoadingProgramme uniform(loading);
  EXPECT_DOUBLE_EQ(uniform.nominal_increment(uniform.segments.at(0), 3.0), 6.0 / 40);
}

// Under geometric spacing a cut-back increment keeps its fraction of the nominal one as the
// nominal one grows, and doubles back towards it after three easy steps.
TEST(CutBackStepper, CutBackIncrementFollowsTheGrowingNominalOne)
{
  IncrementControl control;
  control.start_segment(0.1, false);
  control.increment = 0.025; // two cut-backs
  control.after_step(true, false, 0.1, 0.11, 0, 0, 0, 0, 0);
  EXPECT_NEAR(control.increment, 0.0275, 1e-15);
  control.after_step(true, false, 0.11, 0.121, 0, 0, 0, 0, 0);
  control.after_step(true, false, 0.121, 0.1331, 0, 0, 0, 0, 0);
  EXPECT_NEAR(control.increment, 2 * 0.1331 / 4, 1e-15);
}

// The line search minimises the quadratic model of |R|^2 within its bounds; a failed
// evaluation counts as a huge residual.
TEST(NewtonSteps, LineSearchStepFollowsTheQuadraticModel)
{
  EXPECT_DOUBLE_EQ(line_search_step(1.0, 1.0, 2.0, 1. / 16), 0.2);
  EXPECT_DOUBLE_EQ(line_search_step(1.0, 1.0, 1.0, 1. / 16), 0.5);
  EXPECT_DOUBLE_EQ(line_search_step(1.0, 1.0, std::numeric_limits<double>::infinity(), 1. / 16),
                   1. / 16);
}

// The linear tolerance follows the residual within [1e-10, 1e-3], above the oversolving floor.
TEST(NewtonSteps, InexactNewtonToleranceAndResidualPrediction)
{
  EXPECT_DOUBLE_EQ(linear_tolerance(1.0, 100.0, 0.0), 1e-3);
  EXPECT_DOUBLE_EQ(linear_tolerance(1e-4, 100.0, 0.0), 1e-7);
  EXPECT_DOUBLE_EQ(linear_tolerance(1e-4, 100.0, 1e-5), 1e-5);
  EXPECT_DOUBLE_EQ(linear_tolerance(1e-20, 100.0, 0.0), 1e-10);

  EXPECT_DOUBLE_EQ(predicted_residual(1e-2, 1e-1, 0.5), 1e-4);
  EXPECT_DOUBLE_EQ(predicted_residual(1e-2, 0.0, 0.5), 5e-3);
  EXPECT_TRUE(std::isinf(predicted_residual(1e-2, 0.0, 0.0)));

  ResidualReductions reductions;
  reductions.at(9, 12) = 0.25;
  EXPECT_EQ(reductions.at(5, 5), 0.25);
  EXPECT_EQ(reductions.at(0, 0), 0.0);
}

namespace
{
  // The steps the stepper's nominal walk takes through a loading segment from `from` to its
  // target (nominal_increment at each point, the last step cut to the target).
  unsigned int walked_steps(const LoadingProgramme &programme, const Segment &segment,
                            const double from)
  {
    unsigned int n = 0;
    for (double value = from; value < segment.target * (1 - 1e-12); ++n)
      value = std::min(segment.target, value + programme.nominal_increment(segment, value));
    return n;
  }
} // namespace

// The ETA's count of the steps left: at the start it is expected_steps(loading) (cycles with holds and
// paced unloading, force control, partial unloads, geometric loading with the default paced
// unloading); within a loading segment it counts what the nominal walk takes from there to the
// target, also from a depth between two nominal points (after a cut-back); a finished segment
// counts nothing.
TEST(LoadingProgramme, RemainingStepsCountTheNominalWalkLeft)
{
  const io::LoadingParameters cycles = two_cycles(), partial = partial_unloads();
  io::LoadingParameters       force = cycles;
  force.control = "force";
  force.max_force = 500.0;
  io::LoadingParameters geometric; // the default example's programme
  geometric.max_depth = 6.0;
  geometric.steps = 192;
  geometric.spacing = "geometric";
  for (const io::LoadingParameters &loading : {cycles, force, partial, geometric})
    {
      const LoadingProgramme programme(loading);
      // Within half a step: force control unloads 99 % of the way (4.95 of 5 steps a cycle).
      EXPECT_NEAR(programme.remaining_steps(0, 0.0, false), double(expected_steps(loading)), 0.5);
    }

  for (const char *spacing : {"uniform", "geometric"})
    {
      geometric.spacing = spacing;
      const LoadingProgramme programme(geometric);
      const Segment         &load = programme.segments[0];
      const double           unloading = programme.remaining_steps(0, 6.0, true);
      EXPECT_NEAR(unloading, 21.0, 1e-9) << spacing << ": unloading paced in 20 force steps";
      double value = 0.0;
      for (unsigned int k = 0; k < 150; ++k)
        value += programme.nominal_increment(load, value);
      // At a nominal point, and halfway to the next one (a cut-back).
      for (const double depth : {value, value + 0.5 * programme.nominal_increment(load, value)})
        {
          const double left = programme.remaining_steps(0, depth, false) - unloading;
          EXPECT_EQ(static_cast<unsigned int>(std::ceil(left - 1e-9)),
                    walked_steps(programme, load, depth))
              << spacing << " at " << depth << " um";
        }
      EXPECT_NEAR(programme.remaining_steps(0, value, false), 192.0 - 150.0 + 21.0, 1e-6)
          << spacing;
    }
}

// Partial unloads: the first loading stops at every multiple of their spacing below the
// maximum for a partial unload and a reload to the same depth; the full unload follows the
// maximum as before. The force targets, the probe and the step count by hand.
TEST(LoadingProgramme, PartialUnloadsAtEveryMultipleBelowTheMaximum)
{
  io::LoadingParameters  loading = partial_unloads();
  const LoadingProgramme programme(loading);
  // load 0.5, partial, reload 0.5, load 1.0, partial, reload 1.0, load 1.5, unload.
  ASSERT_EQ(programme.segments.size(), 8u);
  const SegmentKind kinds[8] = {SegmentKind::load, SegmentKind::partial_unload, SegmentKind::reload,
                                SegmentKind::load, SegmentKind::partial_unload, SegmentKind::reload,
                                SegmentKind::load, SegmentKind::unload};
  const double      targets[8] = {0.5, 0.0, 0.5, 1.0, 0.0, 1.0, 1.5, 0.0};
  for (unsigned int i = 0; i < 8; ++i)
    {
      EXPECT_EQ(programme.segments[i].kind, kinds[i]) << i;
      EXPECT_DOUBLE_EQ(programme.segments[i].target, targets[i]) << i;
    }
  EXPECT_STREQ(to_string(SegmentKind::partial_unload), "partial_unload");
  EXPECT_STREQ(to_string(SegmentKind::reload), "reload");
  EXPECT_TRUE(programme.paced(programme.segments[1]));
  EXPECT_FALSE(programme.paced(programme.segments[2]));
  // Reloads take the loading's increments; a partial unload drops 20 % of 50 mN in 4 steps.
  EXPECT_DOUBLE_EQ(programme.nominal_increment(programme.segments[2], 0.49), 0.05);
  EXPECT_DOUBLE_EQ(programme.pacing_force(programme.segments[1], 80.0, 50.0), 2.5);
  EXPECT_DOUBLE_EQ(programme.pacing_force(programme.segments[7], 80.0, 50.0), 8.0);
  EXPECT_DOUBLE_EQ(programme.partial_unload_target(50.0), 40.0);
  EXPECT_TRUE(programme.partial_unload_done(40.12, 50.0)); // within 5 % of a 2.5 mN step
  EXPECT_FALSE(programme.partial_unload_done(40.13, 50.0));
  EXPECT_DOUBLE_EQ(programme.partial_unload_probe(1.0), 0.002);
  // 30 + 11 (paced unloading) + 2 (4 + 2).
  EXPECT_EQ(expected_steps(loading), 53u);

  // A spacing that divides the maximum puts no partial unload at the maximum itself.
  loading.max_depth = 1.0;
  EXPECT_EQ(LoadingProgramme(loading).segments.size(), 5u);
}

// A partial unload's pacing evens the remaining force drop out over whole steps and overshoots
// the last by 5 %, from the secant compliance of the step before.
TEST(CutBackStepper, PartialUnloadLandsOnItsTargetForce)
{
  IncrementControl control;
  control.start_segment(0.05, true, 0.002);
  EXPECT_DOUBLE_EQ(control.step_size(), 0.002);
  // The probe lowered the force from 50 to 49 mN over 0.002 um: compliance 0.002 um/mN. With
  // 9 mN to go in drops of 2.5 mN: 4 steps of 2.25 mN.
  control.after_step(false, true, 0.05, 0.05, 1.0, 0.998, 50.0, 49.0, 2.5, 9.0);
  EXPECT_NEAR(control.paced_increment, 2.25 * 0.002, 1e-15);
  // 1.1 mN to go: one last step of 1.05 * 1.1 mN.
  control.after_step(false, true, 0.05, 0.05, 0.998, 0.994, 49.0, 47.0, 2.5, 1.1);
  EXPECT_NEAR(control.paced_increment, 1.05 * 1.1 * 0.002, 1e-15);
}
