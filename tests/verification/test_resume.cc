// Stop and resume of indentation runs (README "Stopping and resuming"): a run stopped after a
// converged step and resumed in a fresh problem from its checkpoint gives the uninterrupted run's
// curve and pile-up (the direct solver makes both deterministic, so to round-off: 1e-10 relative,
// the pile-up height 1e-9), and a checkpoint of another case or a missing one is refused with a
// message.
#include "../test_cases.h"
#include "../test_files.h"
#include "case/Case.h"
#include "case/CaseFile.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

using namespace indentsim;
namespace fs = std::filesystem;

namespace
{
  using Outcome = problems::IndentationProblem<3>::RunOutcome;

  struct RunResult
  {
    Outcome                                     outcome;
    std::vector<nonlinear::StepRecord>          records;
    std::vector<analysis::pileup::PileUpResult> pileup;
  };

  // A fresh problem on MPI_COMM_WORLD, run into `directory` (stopped after `stop_after` if
  // given, resumed from the directory's checkpoint with `resume`).
  RunResult run(const io::Case &c, const fs::path &directory,
                std::optional<unsigned int> stop_after, bool resume)
  {
    problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
    problem.setup();
    if (stop_after)
      problem.stop_after_step(*stop_after);
    const Outcome outcome = problem.run(directory.string(), resume);
    return {outcome, problem.records(), problem.pileup_results()};
  }

  void expect_same_curve(const std::vector<nonlinear::StepRecord> &resumed,
                         const std::vector<nonlinear::StepRecord> &reference)
  {
    ASSERT_EQ(resumed.size(), reference.size());
    double largest = 0; // relative difference of depth and force, reported
    for (std::size_t i = 0; i < reference.size(); ++i)
      {
        const auto &r = resumed[i], &s = reference[i];
        if (s.force != 0)
          largest = std::max({largest, std::abs(r.force - s.force) / std::abs(s.force),
                              std::abs(r.depth - s.depth) / std::abs(s.depth)});
        EXPECT_EQ(r.step, s.step);
        EXPECT_EQ(r.segment, s.segment) << "step " << i;
        EXPECT_NEAR(r.depth, s.depth, 1e-10 * std::abs(s.depth)) << "step " << i;
        EXPECT_NEAR(r.force, s.force, 1e-10 * std::abs(s.force)) << "step " << i;
        EXPECT_NEAR(r.contact_area, s.contact_area, 1e-10 * s.contact_area) << "step " << i;
        EXPECT_EQ(r.newton_iterations, s.newton_iterations) << "step " << i;
        EXPECT_EQ(r.augmentations, s.augmentations) << "step " << i;
        EXPECT_EQ(r.cutbacks, s.cutbacks) << "step " << i;
        EXPECT_EQ(r.n_active_nodes, s.n_active_nodes) << "step " << i;
      }
    std::cout << "resumed vs uninterrupted: largest relative difference of depth and force "
              << largest << " over " << reference.size() << " records\n";
  }

  void expect_same_pileup(const std::vector<analysis::pileup::PileUpResult> &resumed,
                          const std::vector<analysis::pileup::PileUpResult> &reference)
  {
    ASSERT_EQ(resumed.size(), reference.size());
    ASSERT_FALSE(reference.empty());
    for (std::size_t i = 0; i < reference.size(); ++i)
      {
        EXPECT_EQ(resumed[i].stage, reference[i].stage);
        EXPECT_NEAR(resumed[i].depth, reference[i].depth, 1e-10 * reference[i].depth);
        EXPECT_NEAR(resumed[i].contact_radius, reference[i].contact_radius,
                    1e-10 * reference[i].contact_radius);
        EXPECT_NEAR(resumed[i].max_pileup, reference[i].max_pileup,
                    1e-9 * std::abs(reference[i].max_pileup) + 1e-14);
        EXPECT_NEAR(resumed[i].analysis_radius, reference[i].analysis_radius,
                    1e-10 * reference[i].analysis_radius + 1e-14);
      }
  }

  std::string message_of_resume(const io::Case &c, const fs::path &directory)
  {
    try
      {
        run(c, directory, std::nullopt, true);
      }
    catch (const io::CaseFileError &e)
      {
        return e.what();
      }
    return "";
  }
} // namespace

// Requirement: a J2 run stopped after step 3 of 6 and resumed in a fresh problem gives the
// uninterrupted run's records (depth, force, Newton iterations) and pile-up; the stopped run
// leaves a checkpoint, the finished one removes it.
TEST(Resume, StoppedAndResumedJ2RunEqualsUninterruptedRun)
{
  io::Case c = test_cases::small_j2_case();
  // The direct solver: resumed runs reproduce to round-off with it; the iterative one rebuilds
  // its AMG hierarchy on resume and agrees to the solver tolerance (user guide, "Stop and resume").
  c.solver.linear_solver = "direct";
  c.loading.steps = 6;
  c.output.checkpoint_interval_s = 0;
  const fs::path  reference_dir = test_files::scratch_directory("resume", "reference");
  const fs::path  resumed_dir = test_files::scratch_directory("resume", "resumed");
  const RunResult reference = run(c, reference_dir, std::nullopt, false);
  ASSERT_EQ(reference.outcome, Outcome::finished);

  const RunResult stopped = run(c, resumed_dir, 3, false);
  ASSERT_EQ(stopped.outcome, Outcome::stopped);
  EXPECT_EQ(stopped.records.size(), 4u); // the initial state and steps 1-3
  EXPECT_TRUE(fs::exists(resumed_dir / "checkpoint" / "rank_0.bin"));
  EXPECT_FALSE(fs::exists(resumed_dir / "pileup.json")); // no end-of-run outputs

  const RunResult resumed = run(c, resumed_dir, std::nullopt, true);
  ASSERT_EQ(resumed.outcome, Outcome::finished);
  expect_same_curve(resumed.records, reference.records);
  expect_same_pileup(resumed.pileup, reference.pileup);
  EXPECT_FALSE(fs::exists(resumed_dir / "checkpoint"));
  const std::string log = test_files::read_text(resumed_dir / "run.log");
  EXPECT_NE(log.find("# resumed at step 3"), std::string::npos);
}

// Requirement: the loop state survives a stop in the middle of force-paced unloading after a
// hold (segment index, paced increment, maximum force): the resumed curve equals the
// uninterrupted one, unloading and pile-up after unloading included.
TEST(Resume, StopDuringUnloadingAfterHold)
{
  io::Case c = test_cases::small_j2_case();
  // The direct solver: resumed runs reproduce to round-off with it; the iterative one rebuilds
  // its AMG hierarchy on resume and agrees to the solver tolerance (user guide, "Stop and resume").
  c.solver.linear_solver = "direct";
  c.loading.steps = 4;
  c.loading.hold_steps = 1;
  c.loading.unload = true;
  c.loading.unload_points = 3;
  c.output.checkpoint_interval_s = 0;
  const fs::path  reference_dir = test_files::scratch_directory("resume", "unload_reference");
  const fs::path  resumed_dir = test_files::scratch_directory("resume", "unload_resumed");
  const RunResult reference = run(c, reference_dir, std::nullopt, false);
  ASSERT_EQ(reference.outcome, Outcome::finished);
  // Stop after the first unloading step: the next one takes the paced increment computed from
  // it.
  unsigned int first_unload = 0;
  for (const auto &r : reference.records)
    if (r.segment == "unload")
      {
        first_unload = r.step;
        break;
      }
  ASSERT_GT(first_unload, 0u);
  ASSERT_GT(reference.records.size(), first_unload + 1);

  ASSERT_EQ(run(c, resumed_dir, first_unload, false).outcome, Outcome::stopped);
  const RunResult resumed = run(c, resumed_dir, std::nullopt, true);
  ASSERT_EQ(resumed.outcome, Outcome::finished);
  expect_same_curve(resumed.records, reference.records);
  expect_same_pileup(resumed.pileup, reference.pileup);
}

// Requirement: --resume refuses, with a message saying why, a directory without a checkpoint
// and a checkpoint of a different case; a changed output.checkpoint_interval_s is no change,
// and a force-controlled run (first touch under depth control, then the depth as an unknown)
// resumed after its first force step equals the uninterrupted one.
TEST(Resume, RefusesMissingCheckpointAndDifferentCaseAndResumesForceControl)
{
  io::Case c = test_cases::small_j2_case();
  // The direct solver: resumed runs reproduce to round-off with it; the iterative one rebuilds
  // its AMG hierarchy on resume and agrees to the solver tolerance (user guide, "Stop and resume").
  c.solver.linear_solver = "direct";
  c.loading.control = "force";
  c.loading.max_force = 1.0;
  c.loading.max_depth = 3.0;
  c.loading.steps = 2;
  c.output.checkpoint_interval_s = 0;
  const fs::path empty_dir = test_files::scratch_directory("resume", "empty");
  EXPECT_NE(message_of_resume(c, empty_dir).find("no checkpoint to resume from"),
            std::string::npos);

  const fs::path  reference_dir = test_files::scratch_directory("resume", "force_reference");
  const RunResult reference = run(c, reference_dir, std::nullopt, false);
  ASSERT_EQ(reference.outcome, Outcome::finished);
  const fs::path dir = test_files::scratch_directory("resume", "refuse");
  ASSERT_EQ(run(c, dir, 2, false).outcome, Outcome::stopped); // touch and the first force step
  io::Case changed = c;
  changed.material.yield_stress *= 1.01;
  EXPECT_NE(message_of_resume(changed, dir).find("belongs to a different case"), std::string::npos);
  // The checkpoint is still there and valid for the unchanged case.
  io::Case other_interval = c;
  other_interval.output.checkpoint_interval_s = 60;
  const RunResult resumed = run(other_interval, dir, std::nullopt, true);
  ASSERT_EQ(resumed.outcome, Outcome::finished);
  expect_same_curve(resumed.records, reference.records);
}

// Requirement: the checkpoint folder is one of a run's outputs: a plain rerun into the
// directory is refused, --overwrite removes it.
TEST(Resume, OverwriteKnowsTheCheckpointFolder)
{
  const fs::path dir = test_files::scratch_directory("resume", "protect");
  fs::create_directories(dir / "checkpoint");
  std::ofstream(dir / "checkpoint" / "rank_0.bin") << "x";
  EXPECT_THROW(io::prepare_output_directory(dir.string(), false), io::CaseFileError);
  io::prepare_output_directory(dir.string(), true);
  EXPECT_FALSE(fs::exists(dir / "checkpoint"));
}
