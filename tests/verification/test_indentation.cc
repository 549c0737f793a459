// Verification of the indentation solver: elastic indentation by the paper's rounded cone
// against Sneddon's closed form (REFERENCES.md), equilibrium of contact force and support
// reaction, and the exactness of the augmented-Lagrangian contact. Units: um, mN, GPa.
#include "indenter/SneddonReference.h"
#include "io/Case.h"
#include "solver/IndentationProblem.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace indentsim;

namespace
{
  // Elastic (neo-Hookean) half-space under a rounded cone with delta = 1 um, so that the
  // Hertz regime h <= 0.1 delta is resolved by a modest mesh: at h = 0.1 um the contact radius is
  // sqrt(R h) = 0.78 um (R = A^2 delta = 6.15 um), at h = delta it is 2.8 um.
  io::Case elastic_case()
  {
    io::Case c;
    c.material.model = "neo_hookean";
    c.specimen.f_bar = false;
    c.indenter.a = 2.48;
    c.indenter.delta = 1.0;
    c.specimen.size = {80., 80., 40.};
    c.specimen.refined_region = {6., 6., 2.5};
    c.specimen.contact_elements = 32; // h = 0.1875 um: 4.2 elements across a_c at 0.1 delta
    c.specimen.symmetry = "quarter";
    c.loading.max_depth = 1.0;
    c.loading.steps = 10;
    c.loading.unload = false;
    return c;
  }

  double sneddon_force(const io::Case &c, double depth)
  {
    const indenter::SneddonReference reference(
      indenter::SneddonReference::reduced_modulus(c.material.young_modulus,
                                                  c.material.poisson_ratio),
      c.indenter.a,
      c.indenter.delta);
    return reference.force_at_depth(depth);
  }
} // namespace

// Elastic indentation matches the closed-form half-space solution in the Hertz regime
// (h = 0.1 delta) and at h = delta within the discretisation error of nodal contact on this mesh.
TEST(ElasticIndentation, MatchesSneddonClosedForm)
{
  const io::Case c = elastic_case();
  solver::IndentationProblem problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  problem.run("");
  const auto &records = problem.records();
  ASSERT_EQ(records.size(), 11u);
  for (const unsigned int step : {1u, 10u})
    {
      const auto  &r = records[step];
      const double reference = sneddon_force(c, r.depth);
      const double error = r.force / reference - 1;
      std::cout << "[ elastic ] h/delta = " << r.depth / c.indenter.delta << "  P = " << r.force
                << " mN, closed form " << reference << " mN, error " << 100 * error << " %\n";
      // Tolerances: at h = 0.1 delta nodal contact with ~4 elements across a_c over-estimates
      // the force by a few per cent (measured +2.8 % with 4.7 elements); at h = delta the
      // finite-strain solution sits above the small-strain closed form (radial-displacement
      // excess, REFERENCES.md), so 0 to +12 % is allowed there.
      if (step == 1)
        EXPECT_LT(std::abs(error), 0.05) << "at depth " << r.depth;
      else
        {
          EXPECT_GT(error, 0.0) << "at depth " << r.depth;
          EXPECT_LT(error, 0.12) << "at depth " << r.depth;
        }
    }
}

// The indenter force equals the support reaction at every converged step, and the largest
// penetration is below the requested tolerance (exact contact by the augmented Lagrangian).
TEST(ElasticIndentation, EquilibriumAndExactContact)
{
  io::Case c = elastic_case();
  c.loading.max_depth = 0.3;
  c.loading.steps = 3;
  c.specimen.contact_elements = 24;
  solver::IndentationProblem problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  problem.run("");
  for (const auto &r : problem.records())
    {
      if (r.step == 0)
        continue;
      EXPECT_GT(r.force, 0);
      EXPECT_NEAR(r.force, r.bottom_reaction, 1e-6 * r.force) << "step " << r.step;
      EXPECT_LT(r.max_penetration, c.contact.penetration_tolerance) << "step " << r.step;
    }
}
