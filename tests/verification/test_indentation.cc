// Verification of the indentation solver: elastic indentation by the paper's rounded cone
// against Sneddon's closed form (docs/development.md), equilibrium of contact force and support
// reaction, and the exactness of the augmented-Lagrangian contact. Units: um, mN, GPa.
#include "../test_cases.h"
#include "case/Case.h"
#include "indenter/SneddonReference.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace indentsim;

namespace
{
  io::Case elastic_case()
  {
    return test_cases::elastic_rounded_cone_case();
  }

  double sneddon_force(const io::Case &c, double depth)
  {
    const indenter::SneddonReference reference(
        indenter::SneddonReference::reduced_modulus(c.material.young_modulus,
                                                    c.material.poisson_ratio),
        c.indenter.a, c.indenter.delta);
    return reference.force_at_depth(depth);
  }
} // namespace

namespace
{
  // Runs the elastic case and returns the relative error of the force against the closed form
  // at the final depth (increments may be cut back, so the last record is used).
  double elastic_force_error(const io::Case &c)
  {
    problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
    problem.setup();
    problem.run("");
    const auto &r = problem.records().back();
    EXPECT_NEAR(r.depth, c.loading.max_depth, 1e-12);
    const double reference = sneddon_force(c, r.depth);
    const double error = r.force / reference - 1;
    std::cout << "[ elastic ] h/delta = " << r.depth / c.indenter.delta << ", " << problem.n_dofs()
              << " DOFs, contact element " << problem.mesh_info().contact_element_size
              << " um:  P = " << r.force << " mN, closed form " << reference << " mN, error "
              << 100 * error << " %" << std::endl;
    return error;
  }
} // namespace

// Hertz regime (h = 0.1 delta): the force matches the closed form within 5 %; nodal contact
// with 4.7 elements across the contact radius (a_c = 0.78 um, h = 0.167 um) over-estimates it by
// about 3 % (measured +3.1 % here and +2.8 % on a larger refined region with the same element
// size); 5 % is the bound for this mesh only, not for coarser ones.
TEST(ElasticIndentation, HertzRegimeMatchesClosedForm)
{
  io::Case c = elastic_case();
  c.specimen.refined_region = {{4., 4., 2.}};
  c.specimen.contact_elements = 24;
  c.loading.max_depth = 0.1;
  c.loading.steps = 1;
  EXPECT_LT(std::abs(elastic_force_error(c)), 0.05);
}

// At h = delta (a_c = 2.8 um, 11 elements across it) the finite-strain solution lies above the
// small-strain closed form by the radial-displacement excess of blunt cones (docs/development.md:
// 0 to +10 % for sharp cones); 0 to +12 % is accepted.
TEST(ElasticIndentation, AtTipRadiusScaleMatchesClosedForm)
{
  io::Case c = elastic_case();
  c.specimen.refined_region = {{10., 10., 3.}};
  c.specimen.contact_elements = 40;
  c.loading.max_depth = 1.0;
  c.loading.steps = 5;
  const double error = elastic_force_error(c);
  EXPECT_GT(error, 0.0);
  EXPECT_LT(error, 0.12);
}

// The indenter force equals the support reaction at every converged step, and the largest
// penetration is below the requested tolerance (exact contact by the augmented Lagrangian).
TEST(ElasticIndentation, EquilibriumAndExactContact)
{
  io::Case c = elastic_case();
  c.loading.max_depth = 0.3;
  c.loading.steps = 3;
  c.specimen.contact_elements = 24;
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
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

// Contact output: the projected contact area, interpolated between nodes, follows Sneddon's
// contact radius a_c(h) of the elastic problem step by step: its equivalent radius sqrt(A/pi)
// stays within 0.2 elements of a_c (measured at most 0.027 um = 0.11 elements, from 3.9 to 8.4
// elements across a_c), where a node-based area moves by whole elements. The perimeter's
// largest radius lies less than 0.6 elements outside (measured +0.08 um).
TEST(ElasticIndentation, InterpolatedContactAreaFollowsClosedForm)
{
  io::Case c = elastic_case();
  c.specimen.refined_region = {{6., 6., 2.5}};
  c.specimen.contact_elements = 24; // 0.25 um
  c.loading.max_depth = 0.6;
  c.loading.steps = 4;
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  problem.run("");
  const indenter::SneddonReference reference(
      indenter::SneddonReference::reduced_modulus(c.material.young_modulus,
                                                  c.material.poisson_ratio),
      c.indenter.a, c.indenter.delta);
  const double element = problem.mesh_info().contact_element_size;
  double       previous_area = 0;
  for (const auto &r : problem.records())
    {
      if (r.step == 0)
        continue;
      const double a_c = reference.contact_radius_at_depth(r.depth);
      const double equivalent_radius = std::sqrt(r.contact_area / M_PI);
      std::cout << "[ contact ] h = " << r.depth << " um: sqrt(A/pi) " << equivalent_radius
                << " um, largest radius " << r.contact_radius << " um, closed form " << a_c
                << " um, element " << element << " um" << std::endl;
      EXPECT_NEAR(equivalent_radius, a_c, 0.2 * element) << "h = " << r.depth;
      EXPECT_GE(r.contact_radius, equivalent_radius);
      EXPECT_LT(r.contact_radius, a_c + 0.6 * element) << "h = " << r.depth;
      EXPECT_GT(r.contact_area, previous_area);
      previous_area = r.contact_area;
    }
}

// Symmetry: the quarter model (symmetry planes x = 0, y = 0) and the full model give the same
// load-penetration curve for this axisymmetric isotropic problem (J2, plastic). Tolerance 1e-3:
// the two models may take different cut-backs, and the increment path changes the plastic
// solution slightly (measured 3e-5 here).
TEST(Symmetry, QuarterModelEqualsFullModel)
{
  io::Case                     c = test_cases::small_j2_case("quarter");
  problems::IndentationProblem<3> quarter(c, MPI_COMM_WORLD, false);
  quarter.setup();
  quarter.run("");
  c.specimen.symmetry = "full";
  problems::IndentationProblem<3> full(c, MPI_COMM_WORLD, false);
  full.setup();
  full.run("");
  const auto &q = quarter.records().back(), &f = full.records().back();
  ASSERT_NEAR(q.depth, 1.0, 1e-12);
  ASSERT_NEAR(f.depth, 1.0, 1e-12);
  EXPECT_GT(q.force, 0);
  EXPECT_NEAR(q.force, f.force, 1e-3 * f.force);
  // Both ran augmentation passes that kept the element system and replaced only the contact
  // part (NodeToSurfaceContact::retract, checked entry by entry in the friction tests), the
  // quarter model with contact nodes on its symmetry planes (constrained dofs).
  EXPECT_GT(quarter.statistics().contact_only_assemblies, 0u);
  EXPECT_GT(full.statistics().contact_only_assemblies, 0u);
}
