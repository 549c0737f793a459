// Regression: a small J2 indentation (load and unload) against a gold CSV. Tolerance 1e-6 relative
// on the force, 1e-6 mN below 1 mN (the Newton tolerance is 1e-8 relative; the solver is
// deterministic, so a change beyond 1e-6 means the physics or the algorithm changed), 1e-9 um on
// the prescribed depth, the active contact nodes exactly. The test only reads the gold file: after
// an intended change scripts/regenerate_gold.sh rewrites it from regression/small_j2.yaml (the same
// case as a file), and the commit explains the change.
#include "../test_cases.h"
#include "case/Case.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

using namespace indentsim;

namespace
{
  const std::string gold_file =
      std::string(INDENTSIM_TEST_DATA_DIR) + "/regression/gold/small_j2.csv";

  io::Case small_j2_load_unload_case()
  {
    io::Case c = test_cases::small_j2_case();
    c.loading.unload = true;
    c.loading.unload_steps = 40; // 0.025 um unloading increments
    return c;
  }
} // namespace

// The small J2 load-unload curve (depth, force, active nodes) reproduces the gold file.
TEST(Regression, SmallJ2IndentationMatchesGold)
{
  const io::Case               c = small_j2_load_unload_case();
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  problem.run("");
  const auto &records = problem.records();

  std::ifstream in(gold_file);
  ASSERT_TRUE(in) << "missing gold file " << gold_file;
  std::string line;
  std::size_t i = 0;
  while (std::getline(in, line))
    {
      if (line.empty() || line[0] == '#' || line[0] == 'd')
        continue;
      ASSERT_LT(i, records.size()) << "the run has fewer steps than the gold file";
      std::istringstream row(line);
      double             depth, force;
      unsigned int       n_active;
      char               comma;
      row >> depth >> comma >> force >> comma >> n_active;
      EXPECT_NEAR(records[i].depth, depth, 1e-9) << "row " << i;
      EXPECT_NEAR(records[i].force, force, 1e-6 * std::max(1.0, std::abs(force))) << "row " << i;
      EXPECT_EQ(records[i].n_active_nodes, n_active) << "row " << i;
      ++i;
    }
  EXPECT_EQ(i, records.size()) << "the run and the gold file differ in length";
}
