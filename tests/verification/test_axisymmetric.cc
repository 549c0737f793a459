// Verification of the axisymmetric model (specimen.symmetry: axisymmetric): elastic indentation
// by a sphere against Hertz and by the paper's rounded cone against Sneddon's closed form,
// equilibrium and exact contact, and the J2 case against the 3D quarter model on the same radial
// resolution. Units: um, mN, GPa.
#include "../test_cases.h"
#include "case/Case.h"
#include "indenter/SneddonReference.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

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
// a = sqrt(R h) = 2 um, 32 elements across it) gives P = 4/3 E* R^1/2 h^3/2 within 1 %.
TEST(Axisymmetric, SphereMatchesHertz)
{
  io::Case c = elastic_axisymmetric_case(8., 256); // 0.0625 um elements
  c.indenter.shape = "sphere";
  c.indenter.radius = 20.;
  c.loading.max_depth = 0.2;
  c.loading.steps = 2;
  problems::IndentationProblem<2> problem(c, MPI_COMM_WORLD, false);
  const auto  &r = run(problem);
  const double hertz = 4. / 3. * reduced_modulus(c) * std::sqrt(c.indenter.radius) *
                       std::pow(r.depth, 1.5);
  std::cout << "[ hertz ] " << problem.n_dofs() << " DOFs: P = " << r.force << " mN, Hertz "
            << hertz << " mN, error " << 100 * (r.force / hertz - 1) << " %" << std::endl;
  EXPECT_NEAR(r.depth, 0.2, 1e-12);
  EXPECT_NEAR(r.force / hertz, 1., 0.01);
  const double a = std::sqrt(c.indenter.radius * r.depth);
  EXPECT_NEAR(std::sqrt(r.contact_area / M_PI), a, 0.02 * a);
}

// The paper's rounded cone (a = 2.48, delta = 1 um) in its Hertz range, h = 0.1 delta: the force
// matches Sneddon's closed form for the blunt cone within 1 % on a fine mesh.
TEST(Axisymmetric, RoundedConeMatchesSneddon)
{
  io::Case c = elastic_axisymmetric_case(4., 128); // 0.0625 um elements
  c.loading.max_depth = 0.1;
  c.loading.steps = 1;
  problems::IndentationProblem<2> problem(c, MPI_COMM_WORLD, false);
  const auto                      &r = run(problem);
  const indenter::SneddonReference reference(reduced_modulus(c), c.indenter.a, c.indenter.delta);
  const double                     closed_form = reference.force_at_depth(r.depth);
  std::cout << "[ sneddon ] h/delta = " << r.depth / c.indenter.delta << ": P = " << r.force
            << " mN, closed form " << closed_form << " mN, error "
            << 100 * (r.force / closed_form - 1) << " %" << std::endl;
  EXPECT_NEAR(r.force / closed_form, 1., 0.01);
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

// The J2 case of test_cases::small_j2_case on the 3D quarter model and in axisymmetric mode,
// with the same contact-element size (1 um) and the same refined radius: the loading curves
// agree within 2 % at every step (the 3D mesh's square elements resolve the circular contact
// edge less evenly than the axisymmetric one).
TEST(Axisymmetric, J2AgreesWithQuarterModel)
{
  io::Case quarter_case = test_cases::small_j2_case("quarter");
  io::Case axisymmetric_case = quarter_case;
  axisymmetric_case.specimen.symmetry = "axisymmetric";
  problems::IndentationProblem<3> quarter(quarter_case, MPI_COMM_WORLD, false);
  quarter.setup();
  quarter.run("");
  problems::IndentationProblem<2> axisymmetric(axisymmetric_case, MPI_COMM_WORLD, false);
  run(axisymmetric);
  ASSERT_EQ(quarter.records().size(), axisymmetric.records().size());
  for (std::size_t i = 1; i < quarter.records().size(); ++i)
    {
      const auto &q = quarter.records()[i], &a = axisymmetric.records()[i];
      ASSERT_NEAR(q.depth, a.depth, 1e-12);
      std::cout << "[ j2 ] h = " << q.depth << " um: quarter " << q.force << " mN, axisymmetric "
                << a.force << " mN (" << 100 * (a.force / q.force - 1) << " %)" << std::endl;
      EXPECT_NEAR(a.force / q.force, 1., 0.02) << "h = " << q.depth;
    }
}
