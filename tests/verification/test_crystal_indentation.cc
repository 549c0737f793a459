// Verification of single-crystal indentation (paper section 4): the quarter model against the
// full model where the crystal has the mirror planes x = 0 and y = 0, the cubic symmetry of the
// load-penetration curve, and global equilibrium. Units: um, mN, GPa.
#include "../test_cases.h"
#include "case/Case.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <iostream>
#include <memory>

using namespace indentsim;

namespace
{
  // A smaller crystal case than small_crystal_case (8 x 8 contact elements of 1 um), driven
  // through a fixed sequence of increments so that two models follow the same loading path
  // (rate-independent plasticity depends on the path; the load stepper's cut-backs would make
  // the paths differ).
  io::Case tiny_crystal_case(const std::string &symmetry, const std::array<double, 3> &euler)
  {
    io::Case c = test_cases::small_crystal_case(symmetry, euler);
    c.specimen.size = {{30., 30., 15.}};
    c.specimen.refined_region = {{8., 8., 2.}};
    c.specimen.contact_elements = 8;
    return c;
  }

  // Loads several models along one common path to `max_depth` in `n_increments` nominal
  // increments: when any model fails an increment, all reject it and the increment is halved.
  // Returns the forces [model][accepted increment].
  std::vector<std::vector<double>> forces_along_common_path(const std::vector<io::Case> &cases,
                                                            const double                 max_depth,
                                                            const unsigned int n_increments)
  {
    std::vector<std::unique_ptr<problems::IndentationProblem<3>>> problems;
    for (const auto &c : cases)
      {
        problems.push_back(
            std::make_unique<problems::IndentationProblem<3>>(c, MPI_COMM_WORLD, false));
        problems.back()->setup();
      }
    std::vector<std::vector<double>> forces(cases.size());
    double                           depth = 0, increment = max_depth / n_increments;
    while (depth < max_depth * (1 - 1e-12) && increment > max_depth / n_increments / 64)
      {
        const double                       target = std::min(max_depth, depth + increment);
        bool                               all_converged = true;
        std::vector<nonlinear::StepRecord> records(cases.size());
        for (unsigned int m = 0; m < cases.size() && all_converged; ++m)
          all_converged = problems[m]->solve_increment(target, records[m]) ==
                          nonlinear::IncrementStatus::converged;
        for (auto &problem : problems)
          all_converged ? problem->accept_increment() : problem->reject_increment();
        if (!all_converged)
          {
            increment /= 2;
            continue;
          }
        depth = target;
        for (unsigned int m = 0; m < cases.size(); ++m)
          {
            EXPECT_NEAR(records[m].force, records[m].bottom_reaction,
                        1e-6 * std::max(records[m].force, 1.0))
                << "model " << m << " depth " << depth;
            forces[m].push_back(records[m].force);
          }
      }
    EXPECT_NEAR(depth, max_depth, 1e-12);
    return forces;
  }
} // namespace

// For the (001) plane with Euler angles (0, 0, 0) the planes x = 0 and y = 0 are mirror planes
// of the cubic lattice, so the quarter model must reproduce the full model along the same
// loading path; a rotation of the crystal by 90 degrees about the indentation axis (Euler
// (90, 0, 0)) is a symmetry of the cubic lattice and of the square mesh, so the curve must not
// change. Indenter force and bottom reaction balance at every increment.
TEST(CrystalIndentation, QuarterFullAndCubicSymmetryAgree)
{
  const io::Case quarter = tiny_crystal_case("quarter", {{0., 0., 0.}});
  const io::Case full = tiny_crystal_case("full", {{0., 0., 0.}});
  const io::Case rotated = tiny_crystal_case("quarter", {{90., 0., 0.}});
  const auto     forces = forces_along_common_path({quarter, full, rotated}, 0.6, 6);
  const auto    &q = forces[0], &f = forces[1], &r = forces[2];
  ASSERT_FALSE(f.empty());
  std::cout << "[ measured ] crystal (001) force at 0.6 um: quarter " << q.back() << " full "
            << f.back() << " rotated " << r.back() << " mN, " << f.size() << " increments"
            << std::endl;
  EXPECT_GT(f.back(), 0);
  for (unsigned int k = 0; k < f.size(); ++k)
    {
      EXPECT_NEAR(q[k], f[k], 1e-6 * f.back()) << "increment " << k + 1;
      EXPECT_NEAR(r[k], q[k], 1e-6 * f.back()) << "increment " << k + 1;
    }
}

// The indentation of (111) (no mirror planes: full model) must not let the sharp tip slip past
// the surface node under it: that node stays on the axis and, in contact with the apex, sits at
// the indenter depth (node-to-surface contact alone let the tip pass between the nodes, leaving
// the surface 2.8 um above the apex at 6 um depth on the paper's mesh).
TEST(CrystalIndentation, SurfaceUnderSharpTipFollowsTheApexFor111)
{
  io::Case c = tiny_crystal_case("full", {{0., 0., 0.}});
  c.material.orientation.kind = "surface_normal";
  c.material.orientation.surface_normal = {1., 1., 1.};
  c.material.orientation.reference_direction = {1., -1., 0.};
  const double depth = 0.4;
  c.loading.max_depth = depth;
  c.loading.steps = 4;
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  problem.run("");
  ASSERT_NEAR(problem.records().back().depth, depth, 1e-12);
  // Displacement of the top-surface vertex at the origin, from the rank that owns its dofs.
  double     apex_displacement[3] = {0, 0, 0}, found = 0;
  const auto owned = problem.solution().locally_owned_elements();
  for (const auto &cell : problem.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int v : cell->vertex_indices())
        if (cell->vertex(v).norm() < 1e-9 && owned.is_element(cell->vertex_dof_index(v, 0)) &&
            found == 0)
          {
            found = 1;
            for (unsigned int d = 0; d < 3; ++d)
              apex_displacement[d] = problem.solution()[cell->vertex_dof_index(v, d)];
          }
  found = dealii::Utilities::MPI::sum(found, MPI_COMM_WORLD);
  for (double &u : apex_displacement)
    u = dealii::Utilities::MPI::sum(u, MPI_COMM_WORLD);
  ASSERT_EQ(found, 1);
  EXPECT_EQ(apex_displacement[0], 0.0);
  EXPECT_EQ(apex_displacement[1], 0.0);
  EXPECT_NEAR(apex_displacement[2], -depth, c.contact.penetration_tolerance);
}
