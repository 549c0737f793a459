// Verification of the tensile test (problems/TensileProblem): homogeneous uniaxial tension of J2
// against the independent reference of python/reference_j2_uniaxial.py, of neo-Hookean against
// the closed form, the crystal polycrystal's reproducibility and orientation handling, the
// cut-back, and 1 versus 2 MPI ranks (MpiTensile, run under mpirun -np 2 by CTest).
// Units: um, mN, GPa.
#include "case/Case.h"
#include "case/CaseFile.h"
#include "materials/MaterialFactory.h"
#include "problems/TensileProblem.h"

#include "../unit/material_test_utilities.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace indentsim;

namespace
{
  io::Case tensile_case(const std::string &model)
  {
    io::Case c;
    c.test = "tensile";
    c.material.model = model;
    c.specimen.f_bar = (model != "neo_hookean");
    c.specimen.elements_per_side = 2;
    c.specimen.grains = "single";
    c.loading.max_strain = 0.2;
    c.loading.steps = 100;
    return c;
  }

  std::vector<problems::TensileRecord> run_tensile(const io::Case &c,
                                                   const MPI_Comm  communicator = MPI_COMM_SELF)
  {
    problems::TensileProblem problem(c, communicator, false);
    problem.setup();
    problem.run("", "", false);
    return problem.records();
  }
} // namespace

// Homogeneous J2 tension (Table 1, single grain, 2x2x2 elements, to log strain 0.2) must
// reproduce the independent uniaxial reference to 1e-6 relative at every step, with the Cauchy
// yield measure in 100 steps (every reference row) and the Kirchhoff one in 10 (monotonic
// uniaxial J2 is step-size independent): boundary conditions, reaction, volume and true stress.
TEST(Tensile, J2MatchesIndependentUniaxialReference)
{
  for (const auto &[measure, steps] : {std::pair{"cauchy", 100u}, std::pair{"kirchhoff", 10u}})
    {
      const auto reference = indentsim::testing::read_j2_uniaxial_reference(
          std::string(measure) == "cauchy" ? "j2_uniaxial_reference.csv"
                                           : "j2_uniaxial_reference_kirchhoff.csv");
      ASSERT_EQ(reference.size(), 101u);
      io::Case c = tensile_case("j2");
      c.material.yield_stress_measure = measure;
      c.loading.steps = steps;
      const auto records = run_tensile(c);
      ASSERT_EQ(records.size(), steps + 1);
      const unsigned int rows_per_step = 100 / steps;
      double             worst = 0;
      for (std::size_t i = 1; i < records.size(); ++i)
        {
          const auto &r = records[i];
          const auto &row = reference[i * rows_per_step];
          EXPECT_NEAR(r.log_strain, row.log_strain, 1e-14) << "step " << i;
          EXPECT_NEAR(r.engineering_strain, std::expm1(row.log_strain), 1e-14);
          EXPECT_EQ(r.cutbacks, 0u);
          const double error = std::abs(r.true_stress - row.cauchy_stress) / row.cauchy_stress;
          worst = std::max(worst, error);
          EXPECT_LT(error, 1e-6) << measure << ", step " << i;
          // The reaction is sigma_zz times the current top area, 2 x 2 um contracted by lt^2.
          const double force = row.cauchy_stress * 4 * row.lateral_stretch * row.lateral_stretch;
          EXPECT_NEAR(r.force, force, 1e-6 * force) << measure << ", step " << i;
        }
      std::cout << "[ measured ] J2 (" << measure << ", " << steps
                << " steps) tensile cube vs reference: max relative stress error " << worst << '\n';
    }
}

// Neo-Hookean uniaxial tension to log strain 0.05 matches the 1-D closed form: lateral stretch
// from zero lateral Kirchhoff stress mu (lt^2 - 1) + lambda/2 (J^2 - 1) = 0, J = l lt^2 (solved by
// a scalar Newton here), then sigma_zz = (mu (l^2 - 1) + lambda/2 (J^2 - 1)) / J.
TEST(Tensile, NeoHookeanMatchesClosedForm)
{
  io::Case c = tensile_case("neo_hookean");
  c.loading.max_strain = 0.05;
  c.loading.steps = 5;
  const auto records = run_tensile(c);
  ASSERT_EQ(records.size(), 6u);

  const double E = c.material.young_modulus, nu = c.material.poisson_ratio;
  const double mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double stretch = std::exp(0.05);
  double       lateral = 1;
  for (int it = 0; it < 50; ++it)
    {
      const double J = stretch * lateral * lateral;
      const double g = mu * (lateral * lateral - 1) + lambda / 2 * (J * J - 1);
      const double dg = 2 * mu * lateral + lambda * J * 2 * stretch * lateral;
      lateral -= g / dg;
    }
  const double J = stretch * lateral * lateral;
  const double sigma = (mu * (stretch * stretch - 1) + lambda / 2 * (J * J - 1)) / J;

  const auto  &last = records.back();
  const double error = std::abs(last.true_stress - sigma) / sigma;
  std::cout << "[ measured ] neo-Hookean tensile cube at log strain 0.05: " << last.true_stress
            << " GPa, closed form " << sigma << " GPa, relative error " << error << '\n';
  EXPECT_NEAR(last.log_strain, 0.05, 1e-14);
  EXPECT_LT(error, 1e-9);
  // The force is sigma times the current cross-section (2 um x 2 um contracted by lt^2).
  EXPECT_NEAR(last.force, sigma * 4 * lateral * lateral, 1e-9 * last.force);
}

// A Newton failure cuts the increment back and still reaches the nominal strain with the same
// result; when the halvings are exhausted the run stops with an exception, never with NaN.
TEST(Tensile, FailedIncrementIsCutBack)
{
  io::Case c = tensile_case("neo_hookean");
  c.loading.max_strain = 0.2;
  c.loading.steps = 1;
  c.solver.max_newton_iterations = 2; // enough for increments of 0.025, not for 0.2
  c.loading.max_cutbacks = 8;
  const auto records = run_tensile(c);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_GE(records[1].cutbacks, 3u) << "at least 0.2 -> 0.1 -> 0.05 -> 0.025";
  EXPECT_NEAR(records[1].log_strain, 0.2, 1e-14);

  io::Case reference_case = c;
  reference_case.solver.max_newton_iterations = 25;
  reference_case.loading.steps = 20;
  const auto reference = run_tensile(reference_case);
  EXPECT_NEAR(records[1].true_stress, reference.back().true_stress,
              1e-9 * reference.back().true_stress);

  c.loading.max_cutbacks = 2;
  EXPECT_THROW(run_tensile(c), std::runtime_error);
}

// Random grains: the same seed gives the identical curve, another seed another polycrystal.
TEST(Tensile, CrystalGrainsAreReproducible)
{
  io::Case c = tensile_case("crystal");
  c.specimen.grains = "per_element";
  c.specimen.seed = 1;
  c.loading.max_strain = 0.02;
  c.loading.steps = 5;
  const auto first = run_tensile(c);
  const auto again = run_tensile(c);
  c.specimen.seed = 2;
  const auto other = run_tensile(c);
  ASSERT_EQ(first.size(), 6u);
  ASSERT_EQ(again.size(), first.size());
  ASSERT_EQ(other.size(), first.size());
  double largest_difference = 0;
  for (std::size_t i = 1; i < first.size(); ++i)
    {
      EXPECT_EQ(first[i].true_stress, again[i].true_stress) << "step " << i;
      EXPECT_EQ(first[i].force, again[i].force) << "step " << i;
      largest_difference =
          std::max(largest_difference, std::abs(other[i].true_stress / first[i].true_stress - 1));
    }
  std::cout << "[ measured ] crystal 8 grains, seed 1 vs 2: largest relative stress difference "
            << largest_difference << '\n';
  EXPECT_GT(largest_difference, 1e-3);
}

// The orientation reaches every material point: a single crystal pulled along [001] is
// unchanged by a 90 degree rotation about the tensile axis (cubic symmetry) but differs from
// one pulled along [111] (smaller Schmid factors, so a higher flow stress).
TEST(Tensile, SingleCrystalOrientationIsApplied)
{
  io::Case c = tensile_case("crystal");
  c.specimen.elements_per_side = 1;
  c.loading.max_strain = 0.02;
  c.loading.steps = 5;
  c.solver.residual_tolerance = 1e-13; // the two paths' rounding differs: converge both tightly
  c.material.orientation.euler_bunge_deg = {{0., 0., 0.}};
  const auto along_001 = run_tensile(c);
  c.material.orientation.euler_bunge_deg = {{90., 0., 0.}};
  const auto rotated = run_tensile(c);
  c.material.orientation.kind = "surface_normal";
  c.material.orientation.surface_normal = {1., 1., 1.};
  c.material.orientation.reference_direction = {1., -1., 0.};
  const auto   along_111 = run_tensile(c);
  const double last_001 = along_001.back().true_stress;
  EXPECT_NEAR(rotated.back().true_stress, last_001, 1e-9 * last_001);
  std::cout << "[ measured ] single crystal at log strain 0.02: [001] " << last_001
            << " GPa, [111] " << along_111.back().true_stress << " GPa\n";
  EXPECT_GT(along_111.back().true_stress, 1.2 * last_001);
}

// The hexagonal crystal of examples/titanium_hcp_0001_n24.yaml (a hardening block per family)
// pulled along c: unchanged by a 60 degree rotation about c (the lattice's 6-fold axis), and
// the same orientation in Miller-Bravais indices, (0001) with [2 -1 -1 0] along x, is the crystal
// frame itself. Pulled along a1 (the plane (2 -1 -1 0) normal to the axis) the soft prismatic
// systems slip (Schmid factor 0.43, tau0 = 0.15 GPa); along c only the hard pyramidal <c+a>
// ones can (tau0 = 1.11 GPa), so the flow stress is several times higher.
TEST(Tensile, HexagonalSingleCrystalFollowsItsSymmetry)
{
  io::Case c = tensile_case("crystal");
  c.specimen.elements_per_side = 1;
  c.loading.max_strain = 0.02;
  c.loading.steps = 5;
  c.solver.residual_tolerance = 1e-13;
  c.material =
      io::read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/titanium_hcp_0001_n24.yaml")
          .material;
  io::MaterialParameters &m = c.material;
  m.orientation.kind = "euler_bunge_deg";
  m.orientation.euler_bunge_deg = {{0., 0., 0.}};
  const double along_c = run_tensile(c).back().true_stress;
  m.orientation.euler_bunge_deg = {{60., 0., 0.}};
  EXPECT_NEAR(run_tensile(c).back().true_stress, along_c, 1e-9 * along_c);
  m.orientation.kind = "surface_normal";
  m.orientation.surface_normal = {0., 0., 0., 1.};
  m.orientation.reference_direction = {2., -1., -1., 0.};
  EXPECT_NEAR(run_tensile(c).back().true_stress, along_c, 1e-12 * along_c);
  m.orientation.surface_normal = {2., -1., -1., 0.};
  m.orientation.reference_direction = {0., 0., 0., 1.};
  const double along_a = run_tensile(c).back().true_stress;
  std::cout << "[ measured ] hcp single crystal at log strain 0.02: along c " << along_c
            << " GPa, along a1 " << along_a << " GPa\n";
  EXPECT_GT(along_c, 3 * along_a);
}

// One rank and all ranks of MPI_COMM_WORLD give the same polycrystal curve: the grains follow
// the element positions, not the partition (runs under mpirun -np 2).
TEST(MpiTensile, OneVersusManyRanksGiveTheSameCurve)
{
  io::Case c = tensile_case("crystal");
  c.specimen.elements_per_side = 3;
  c.specimen.grains = "per_element";
  c.loading.max_strain = 0.02;
  c.loading.steps = 8;
  // Converged tighter than the default 1e-8, so that the comparison measures the parallel
  // assembly and solve rather than where each Newton iteration happened to stop.
  c.solver.residual_tolerance = 1e-11;
  const auto serial = run_tensile(c, MPI_COMM_SELF);
  const auto parallel = run_tensile(c, MPI_COMM_WORLD);
  ASSERT_EQ(serial.size(), parallel.size());
  double worst = 0;
  for (std::size_t i = 1; i < serial.size(); ++i)
    {
      const auto &s = serial[i], &p = parallel[i];
      EXPECT_GT(s.true_stress, 0);
      EXPECT_EQ(s.cutbacks, p.cutbacks) << "step " << i;
      EXPECT_NEAR(p.log_strain, s.log_strain, 1e-15);
      EXPECT_NEAR(p.true_stress, s.true_stress, 1e-10 * s.true_stress) << "step " << i;
      EXPECT_NEAR(p.force, s.force, 1e-10 * s.force) << "step " << i;
      worst = std::max(worst, std::abs(p.true_stress / s.true_stress - 1));
    }
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "[ measured ] tensile (" << c.material.model << ", 27 grains) on "
              << dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
              << " ranks vs 1: largest relative stress difference " << worst << '\n';
}
