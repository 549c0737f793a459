// Verification of the axisymmetric model (specimen.symmetry: axisymmetric): elastic indentation
// by a sphere against Hertz and by the paper's rounded cone against Sneddon's closed form,
// equilibrium and exact contact, and the J2 case against the 3D quarter model on the same radial
// resolution. Units: um, mN, GPa.
#include "../test_cases.h"
#include "case/Case.h"
#include "indenter/IndenterFactory.h"
#include "indenter/SneddonReference.h"
#include "mesh/MeshDesign.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

using namespace indentsim;

namespace
{
  double reduced_modulus(const io::Case &c)
  {
    return indenter::SneddonReference::reduced_modulus(c.material.young_modulus,
                                                       c.material.poisson_ratio);
  }

  // An elastic (neo-Hookean) cylinder of radius 500 um and height 500 um, refined over
  // r <= refined_radius with `n` contact elements across 2 refined_radius.
  io::Case elastic_axisymmetric_case(const double refined_radius, const unsigned int n)
  {
    io::Case c = test_cases::elastic_rounded_cone_case();
    c.specimen.symmetry = "axisymmetric";
    c.specimen.size = {{1000., 1000., 500.}};
    c.specimen.refined_region = {{2 * refined_radius, 2 * refined_radius, refined_radius}};
    c.specimen.contact_elements = n;
    return c;
  }

  const problems::StepRecord &run(problems::IndentationProblem<2> &problem)
  {
    problem.setup();
    problem.run("");
    return problem.records().back();
  }
} // namespace

// Hertz: a sphere of radius R = 20 um pressed to h = 0.2 um (h/R = 0.01, contact radius
// a = sqrt(R h) = 2 um, 16 elements across it) against P = 4/3 E* R^1/2 h^3/2. The explicit mesh
// is uniform over its refined region and coarsens outside it; the coarse outer cells stiffen the
// far field, so the error falls as the refined region grows (measured +1.90 % over r <= 8 um,
// +1.25 % over r <= 32 um with the same 0.125 um elements).
TEST(Axisymmetric, SphereMatchesHertz)
{
  std::vector<double> errors;
  for (const double refined_radius : {8., 16.})
    {
      io::Case c = elastic_axisymmetric_case(refined_radius, 16 * refined_radius);
      c.indenter.shape = "sphere";
      c.indenter.radius = 20.;
      c.loading.max_depth = 0.2;
      c.loading.steps = 2;
      problems::IndentationProblem<2> problem(c, MPI_COMM_WORLD, false);
      const auto                     &r = run(problem);
      const double                    hertz =
          4. / 3. * reduced_modulus(c) * std::sqrt(c.indenter.radius) * std::pow(r.depth, 1.5);
      errors.push_back(r.force / hertz - 1);
      std::cout << "[ hertz ] refined radius " << refined_radius << " um, " << problem.n_dofs()
                << " DOFs: P = " << r.force << " mN, Hertz " << hertz << " mN, error "
                << 100 * errors.back() << " %" << std::endl;
      EXPECT_NEAR(r.depth, 0.2, 1e-12);
      const double a = std::sqrt(c.indenter.radius * r.depth);
      EXPECT_NEAR(std::sqrt(r.contact_area / M_PI), a, 0.02 * a);
    }
  EXPECT_GT(errors[0], errors[1]);
  EXPECT_GT(errors[1], 0.);
  EXPECT_LT(errors[1], 0.02);
}

// The paper's rounded cone (a = 2.48, delta = 1 um) in its Hertz range, h = 0.1 delta
// (a_c = 0.78 um, 12 elements across it): the force matches Sneddon's closed form for the blunt
// cone within 2 % (the same outer-mesh stiffening as for the sphere: measured +1.28 % over a
// refined radius of 16 um).
TEST(Axisymmetric, RoundedConeMatchesSneddon)
{
  io::Case c = elastic_axisymmetric_case(8., 256); // 0.0625 um elements
  c.loading.max_depth = 0.1;
  c.loading.steps = 1;
  problems::IndentationProblem<2>  problem(c, MPI_COMM_WORLD, false);
  const auto                      &r = run(problem);
  const indenter::SneddonReference reference(reduced_modulus(c), c.indenter.a, c.indenter.delta);
  const double                     closed_form = reference.force_at_depth(r.depth);
  std::cout << "[ sneddon ] h/delta = " << r.depth / c.indenter.delta << ": P = " << r.force
            << " mN, closed form " << closed_form << " mN, error "
            << 100 * (r.force / closed_form - 1) << " %" << std::endl;
  EXPECT_GT(r.force / closed_form, 1.);
  EXPECT_LT(r.force / closed_form, 1.02);
}

namespace
{
  // The case with the automatic mesh (specimen.contact_elements: auto) designed for it, with
  // n elements per radius (specimen.elements_per_radius; 0: the default).
  io::Case with_automatic_mesh(io::Case c, const unsigned int n = 0)
  {
    c.specimen.contact_elements = io::automatic_contact_elements;
    c.specimen.elements_per_radius = n;
    mesh::design_mesh(c, *indenter::create_indenter(c.indenter), /*size_given=*/false);
    return c;
  }
} // namespace

// A fine automatic mesh (n = 16) against the elastic closed forms within 1 %, where the excess
// is the fixed bottom at 160 contact radii (about +0.4 %, mesh/MeshDesign.h) and the
// finite-strain excess, which grows with a/R: Hertz at h/R = 0.0025 (a/R = 0.05) and Sneddon's
// blunt cone at h = 0.0125 delta (a/R = 0.045; +1.04 % at a/R = 0.064, +1.5 % at 0.13).
// Measured: see docs/validation.md (the default n = 10: +1.08 % and +1.13 %). The force balances the bottom reaction, part of which arrives through
// hanging nodes (the octree coarsens toward the bottom).
TEST(Axisymmetric, AutomaticMeshMatchesHertzAndSneddon)
{
  io::Case sphere = test_cases::elastic_rounded_cone_case();
  sphere.specimen.symmetry = "axisymmetric";
  sphere.indenter.shape = "sphere";
  sphere.indenter.radius = 20.;
  sphere.loading.max_depth = 0.05;
  sphere.loading.steps = 1;
  io::Case cone = test_cases::elastic_rounded_cone_case();
  cone.specimen.symmetry = "axisymmetric";
  cone.loading.max_depth = 0.0125;
  cone.loading.steps = 1;

  const io::Case                  c = with_automatic_mesh(sphere, 16);
  problems::IndentationProblem<2> hertz_problem(c, MPI_COMM_WORLD, false);
  const auto                     &r = run(hertz_problem);
  const double                    hertz =
      4. / 3. * reduced_modulus(c) * std::sqrt(c.indenter.radius) * std::pow(r.depth, 1.5);
  std::cout << "[ hertz, automatic mesh ] " << hertz_problem.n_dofs() << " DOFs: P = " << r.force
            << " mN, Hertz " << hertz << " mN, error " << 100 * (r.force / hertz - 1) << " %"
            << std::endl;
  EXPECT_GT(r.force / hertz, 1.);
  EXPECT_LT(r.force / hertz, 1.01);
  EXPECT_NEAR(r.bottom_reaction, r.force, 1e-6 * r.force);

  const io::Case                   k = with_automatic_mesh(cone, 16);
  problems::IndentationProblem<2>  cone_problem(k, MPI_COMM_WORLD, false);
  const auto                      &q = run(cone_problem);
  const indenter::SneddonReference reference(reduced_modulus(k), k.indenter.a, k.indenter.delta);
  const double                     closed_form = reference.force_at_depth(q.depth);
  std::cout << "[ sneddon, automatic mesh ] " << cone_problem.n_dofs() << " DOFs: P = " << q.force
            << " mN, closed form " << closed_form << " mN, error "
            << 100 * (q.force / closed_form - 1) << " %" << std::endl;
  EXPECT_GT(q.force / closed_form, 1.);
  EXPECT_LT(q.force / closed_form, 1.01);
  EXPECT_NEAR(q.bottom_reaction, q.force, 1e-6 * q.force);
}

// The indenter force equals the support reaction at every step, and no node penetrates by more
// than the contact tolerance, with and without friction.
TEST(Axisymmetric, EquilibriumAndExactContact)
{
  for (const double mu : {0.0, 0.3})
    {
      io::Case c = elastic_axisymmetric_case(4., 32);
      c.contact.friction_coefficient = mu;
      c.loading.max_depth = 0.5;
      c.loading.steps = 3;
      problems::IndentationProblem<2> problem(c, MPI_COMM_WORLD, false);
      run(problem);
      for (const auto &r : problem.records())
        {
          if (r.step == 0)
            continue;
          EXPECT_GT(r.force, 0);
          EXPECT_NEAR(r.force, r.bottom_reaction, 1e-6 * r.force) << "mu " << mu;
          EXPECT_LT(r.max_penetration, c.contact.penetration_tolerance) << "mu " << mu;
        }
    }
}

// The J2 case of test_cases::small_j2_case to 3 um on the 3D quarter model and in axisymmetric
// mode with the same 1 um contact elements over the same 24 um refined width. Both curves step
// as rings of nodes (axisymmetric) or the square grid's nodes (quarter) reach the tip, at
// different depths, so from 1.5 um on (5 elements across the contact radius) they agree
// pointwise within 4 % only (measured at most 3.8 %); their least-squares curvature
// C = sum P h^2 / sum h^4 agrees within 1 % (measured 0.57 %).
TEST(Axisymmetric, J2AgreesWithQuarterModel)
{
  io::Case quarter_case = test_cases::small_j2_case("quarter");
  quarter_case.specimen.refined_region = {{24., 24., 6.}};
  quarter_case.specimen.contact_elements = 24;
  quarter_case.loading.max_depth = 3.0;
  quarter_case.loading.steps = 12;
  io::Case axisymmetric_case = quarter_case;
  axisymmetric_case.specimen.symmetry = "axisymmetric";
  problems::IndentationProblem<3> quarter(quarter_case, MPI_COMM_WORLD, false);
  quarter.setup();
  quarter.run("");
  problems::IndentationProblem<2> axisymmetric(axisymmetric_case, MPI_COMM_WORLD, false);
  run(axisymmetric);
  ASSERT_EQ(quarter.records().size(), axisymmetric.records().size());
  double q_moment = 0, a_moment = 0, h4 = 0;
  for (std::size_t i = 1; i < quarter.records().size(); ++i)
    {
      const auto &q = quarter.records()[i], &a = axisymmetric.records()[i];
      ASSERT_NEAR(q.depth, a.depth, 1e-12);
      std::cout << "[ j2 ] h = " << q.depth << " um: quarter " << q.force << " mN, axisymmetric "
                << a.force << " mN (" << 100 * (a.force / q.force - 1) << " %)" << std::endl;
      if (q.depth < 1.5)
        continue;
      EXPECT_NEAR(a.force / q.force, 1., 0.04) << "h = " << q.depth;
      const double h2 = q.depth * q.depth;
      q_moment += q.force * h2;
      a_moment += a.force * h2;
      h4 += h2 * h2;
    }
  std::cout << "[ j2 ] C = P/h^2 (least squares, h >= 1.5 um): quarter " << q_moment / h4
            << " GPa, axisymmetric " << a_moment / h4 << " GPa" << std::endl;
  EXPECT_NEAR(a_moment / q_moment, 1., 0.01);
}

namespace
{
  // The elastic axisymmetric case loaded to 1 um in 13 geometric steps from 1/64 um (the
  // indenter set by the test; the automatic mesh designed by with_automatic_mesh).
  io::Case elastic_geometric_case()
  {
    io::Case c = test_cases::elastic_rounded_cone_case();
    c.specimen.symmetry = "axisymmetric";
    c.loading.max_depth = 1.0;
    c.loading.steps = 13;
    c.loading.unload = false;
    c.loading.spacing = "geometric";
    c.loading.first_fraction = 1.0 / 64;
    return c;
  }
} // namespace

// Dimensional analysis: a neo-Hookean solid has no length scale and a cone none either, so under a
// cone P = C h^2 at every depth (finite strain included). The paper's rounded cone is the cone
// z = r/a shifted down by delta beyond its tip, so P = C (h + delta)^2 up to O((delta/h)^2). On
// the automatic mesh designed for h_max (the same number of elements across the contact radius
// at every depth from h_max/8 on) with geometric increments (h_k = h_max rho^(k - steps), checked
// exactly), C must be the same at every recorded depth from h_max/8 to h_max, but for the fixed
// specimen: its size is 160 contact radii at h_max and 8 times more at h_max/8, and the
// stiffening of a finite specimen grows with a/L (+1.25 % at a/L = 1/160, Hertz, validation.md),
// so C may rise by about 1 % over the range; measured +0.88 %.
TEST(Axisymmetric, ConeForceGrowsAsDepthSquaredUnderGeometricSteps)
{
  io::Case c = elastic_geometric_case();
  c.indenter.shape = "rounded_cone";
  c.indenter.a = 2.48;
  c.indenter.delta = 0.005;
  const io::Case                  k = with_automatic_mesh(c);
  problems::IndentationProblem<2> problem(k, MPI_COMM_WORLD, false);
  run(problem);
  const double        rho = std::pow(64.0, 1.0 / 12);
  std::vector<double> C;
  unsigned int        geometric_step = 0; // cut-backs insert steps; the sequence must hold
  for (const auto &r : problem.records())
    {
      if (r.step == 0 || r.depth < 1.0 / 8 - 1e-12)
        continue;
      while (std::pow(rho, double(geometric_step) - 12) < r.depth * (1 - 1e-9))
        ++geometric_step;
      EXPECT_NEAR(r.depth, std::pow(rho, double(geometric_step) - 12), 1e-12);
      C.push_back(r.force / std::pow(r.depth + c.indenter.delta, 2));
    }
  ASSERT_EQ(C.size(), 7u);
  const auto [low, high] = std::minmax_element(C.begin(), C.end());
  std::cout << "[ cone, P / (h + delta)^2 ] " << problem.n_dofs() << " DOFs, " << C.size()
            << " depths from h_max/8: C from " << *low << " to " << *high << " GPa (spread "
            << 100 * (*high / *low - 1) << " %)" << std::endl;
  EXPECT_LT(*high / *low - 1, 0.015);
}

// The augmented Lagrangian at the edge of a sharp cone's contact (elastic, automatic mesh for
// 1 um with n = 16 and the top face's cells halved twice, geometric steps): in the last
// increment, to 1 um, nodes at the contact edge alternate between penetrating and standing off
// under their multipliers at the plain Uzawa updates, which then take 15 passes. The damped
// update of the later passes (NodeToSurfaceContact::augment) converges it in 6. The test checks
// that this increment needs those later passes (so that it exercises them) and that it gets
// through in at most 8, without a cut-back anywhere in the run.
TEST(Axisymmetric, AugmentationConvergesWhereAContactEdgeNodeAlternates)
{
  io::Case c = elastic_geometric_case();
  c.indenter.shape = "cone";
  c.indenter.half_angle_deg = 70.3;
  c.indenter.tip_radius = 0;
  io::Case k = with_automatic_mesh(c, 16);
  k.specimen.grading.surface_halvings = 2;
  problems::IndentationProblem<2> problem(k, MPI_COMM_WORLD, false);
  run(problem);
  const auto &records = problem.records();
  ASSERT_EQ(records.size(), 14u);
  for (const auto &r : records)
    EXPECT_EQ(r.cutbacks, 0u) << "step " << r.step << " at " << r.depth << " um";
  EXPECT_NEAR(records.back().depth, 1.0, 1e-12);
  EXPECT_GE(records.back().augmentations, 4u) << "the increment no longer needs damped passes";
  EXPECT_LE(records.back().augmentations, 8u) << "the damped passes no longer converge it";
  std::cout << "[ contact edge ] step 13 to " << records.back().depth
            << " um: " << records.back().augmentations << " augmentations, "
            << records.back().newton_iterations << " Newton iterations" << std::endl;
}

// Newton's relative tolerance is measured against forces the body carries (the run's largest
// indenter force, the bottom face's reaction), not against the increment's first residual or
// an iterate's contact force, which grow with the contact penalty times the iterate's
// penetration. With a loose tolerance (1e-4) and a penalty of 1e6 GPa/um (about 1000 times the
// automatic one here), every accepted J2 increment must still be in equilibrium: the indenter
// force equals the bottom face's reaction to 2e-4 of the largest force (a tolerance relative to
// the first residual lets them differ by 38 %). The neo-Hookean solid, whose solution does not
// depend on the path (the stiff run may cut increments back), gives the same force with either
// penalty at every depth both runs reached.
TEST(Axisymmetric, ConvergedCurveDoesNotDependOnThePenalty)
{
  const auto largest_force = [](const auto &records) {
    double largest = 0;
    for (const auto &r : records)
      largest = std::max(largest, std::abs(r.force));
    return largest;
  };
  io::Case j2 = test_cases::small_j2_case("axisymmetric");
  j2.loading.max_depth = 2.0;
  j2.loading.steps = 16;
  j2.solver.residual_tolerance = 1e-4;
  j2.contact.penalty = 1e6;
  problems::IndentationProblem<2> stiff_j2(j2, MPI_COMM_WORLD, false);
  run(stiff_j2);
  EXPECT_NEAR(stiff_j2.records().back().depth, 2.0, 1e-12);
  const double j2_largest = largest_force(stiff_j2.records());
  double       imbalance = 0;
  for (const auto &r : stiff_j2.records())
    imbalance = std::max(imbalance, std::abs(r.force - r.bottom_reaction));
  std::cout << "[ penalty ] J2, penalty 1e6: largest |indenter force - bottom reaction| "
            << imbalance / j2_largest << " of the largest force " << j2_largest << " mN"
            << std::endl;
  EXPECT_LT(imbalance, 2e-4 * j2_largest);

  io::Case elastic = j2;
  elastic.material.model = "neo_hookean";
  elastic.contact.penalty = 0; // automatic
  io::Case stiff = elastic;
  stiff.contact.penalty = 1e6;
  problems::IndentationProblem<2> automatic_run(elastic, MPI_COMM_WORLD, false);
  run(automatic_run);
  problems::IndentationProblem<2> stiff_run(stiff, MPI_COMM_WORLD, false);
  run(stiff_run);
  const double largest = largest_force(automatic_run.records());
  double       deviation = 0;
  unsigned int compared = 0;
  for (const auto &a : automatic_run.records())
    for (const auto &b : stiff_run.records())
      if (a.depth > 0 && std::abs(a.depth - b.depth) < 1e-12)
        {
          deviation = std::max(deviation, std::abs(a.force - b.force));
          ++compared;
        }
  std::cout << "[ penalty ] neo-Hookean: " << compared << " depths compared, largest difference "
            << deviation / largest << " of the largest force " << largest << " mN" << std::endl;
  EXPECT_EQ(compared, 16u);
  EXPECT_LT(deviation, 2e-4 * largest);
}
