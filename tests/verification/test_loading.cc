// Loading programmes: force control (the depth an unknown of the bordered Newton system)
// against depth control, hold segments and load-unload cycles. Units: um, mN, GPa.
#include "../test_cases.h"
#include "case/Case.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace indentsim;

namespace
{
  // The shared elastic rounded-cone case on a smaller block, to 0.3 um in 3 steps.
  io::Case elastic_case()
  {
    io::Case c = test_cases::elastic_rounded_cone_case();
    c.specimen.size = {{40., 40., 20.}};
    c.specimen.refined_region = {{4., 4., 2.}};
    c.specimen.contact_elements = 16;
    c.loading.max_depth = 0.3;
    c.loading.steps = 3;
    return c;
  }

  std::vector<nonlinear::StepRecord> run(const io::Case &c)
  {
    problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
    problem.setup();
    problem.run("");
    return problem.records();
  }
} // namespace

// Requirement: force control reaches the depth at which depth control produces that force: on
// the path-independent elastic problem to the Newton tolerance (1e-6 relative asserted), with
// the force target met at every step.
TEST(ForceControl, ElasticDepthMatchesDepthControl)
{
  io::Case     depth_case = elastic_case();
  const auto   by_depth = run(depth_case);
  const double force = by_depth.back().force;
  ASSERT_GT(force, 0);

  io::Case force_case = elastic_case();
  force_case.loading.control = "force";
  force_case.loading.max_force = force;
  force_case.loading.max_depth = 1.5; // admissible depth only
  force_case.loading.steps = 4;
  const auto by_force = run(force_case);
  // Step 1 makes the first contact under depth control; then the force targets follow.
  ASSERT_GE(by_force.size(), 6u);
  EXPECT_EQ(by_force[1].segment, "load");
  EXPECT_LT(by_force[1].force, force / 4);
  EXPECT_NEAR(by_force.back().force, force, 1e-8 * force);
  std::cout << "[ force control ] F = " << force << " mN: depth " << by_force.back().depth
            << " um (depth control: " << depth_case.loading.max_depth << " um)" << std::endl;
  EXPECT_NEAR(by_force.back().depth, depth_case.loading.max_depth,
              1e-6 * depth_case.loading.max_depth);
}

// Requirement: on the plastic J2 case, load and unload under force control reach the states that
// depth control reaches through the same depths: replaying the force-controlled run's depths
// under depth control reproduces its forces (to 1e-4 of the maximum force; plasticity makes the
// result depend on the increments, so the replay uses the same ones). The bottom reaction
// balances the indenter force at every step (to 1e-6 of the maximum force), and unloading ends
// at 1 % of the maximum force.
TEST(ForceControl, PlasticLoadUnloadReplaysUnderDepthControl)
{
  io::Case force_case = test_cases::small_j2_case();
  force_case.loading.control = "force";
  force_case.loading.max_force = 6.0;
  force_case.loading.max_depth = 3.0;
  force_case.loading.steps = 4;
  force_case.loading.unload = true;
  const auto by_force = run(force_case);
  ASSERT_GT(by_force.size(), 8u);
  EXPECT_EQ(by_force.back().segment, "unload");
  EXPECT_NEAR(by_force.back().force, 0.06, 1e-8 * 6.0);

  io::Case                     depth_case = test_cases::small_j2_case();
  problems::IndentationProblem<3> replay(depth_case, MPI_COMM_WORLD, false);
  replay.setup();
  double largest_difference = 0;
  for (std::size_t i = 1; i < by_force.size(); ++i)
    {
      const auto &target = by_force[i];
      EXPECT_NEAR(target.bottom_reaction, target.force, 1e-6 * 6.0) << "step " << i;
      nonlinear::StepRecord record;
      if (replay.solve_increment(target.depth, record) != nonlinear::IncrementStatus::converged)
        {
          replay.reject_increment();
          ASSERT_EQ(replay.solve_increment(target.depth, record, false),
                    nonlinear::IncrementStatus::converged)
              << "step " << i;
        }
      replay.accept_increment();
      largest_difference = std::max(largest_difference, std::abs(record.force - target.force));
      EXPECT_NEAR(record.force, target.force, 1e-4 * 6.0)
          << "step " << i << " (" << target.segment << ") at depth " << target.depth << " um";
    }
  std::cout << "[ force control ] J2: " << by_force.size() - 1
            << " steps replayed under depth control, largest force difference "
            << largest_difference << " mN" << std::endl;
}

// Requirement: the programme is recorded step by step: hold steps repeat the maximum (same depth
// and force), every cycle loads, holds and unloads, and the elastic second cycle reproduces the
// first (path independence, 1e-7 relative).
TEST(LoadingProgramme, HoldAndCyclesAreRecorded)
{
  io::Case c = elastic_case();
  c.loading.unload = true;
  c.loading.hold_steps = 2;
  c.loading.cycles = 2;
  const auto               records = run(c);
  std::vector<std::string> kinds;
  for (const auto &r : records)
    if (kinds.empty() || kinds.back() != r.segment + std::to_string(r.cycle))
      kinds.push_back(r.segment + std::to_string(r.cycle));
  EXPECT_EQ(kinds, (std::vector<std::string>{"start0", "load1", "hold1", "unload1", "load2",
                                             "hold2", "unload2"}));
  std::vector<double> max_force(3, 0.0);
  for (std::size_t i = 1; i < records.size(); ++i)
    {
      const auto &r = records[i];
      max_force[r.cycle] = std::max(max_force[r.cycle], r.force);
      if (r.segment == "hold")
        {
          EXPECT_EQ(r.depth, records[i - 1].depth);
          EXPECT_NEAR(r.force, records[i - 1].force, 1e-7 * r.force); // Newton tolerance
        }
    }
  EXPECT_GT(max_force[1], 0);
  EXPECT_NEAR(max_force[2], max_force[1], 1e-7 * max_force[1]);
}
