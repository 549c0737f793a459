// Coulomb friction of the augmented-Lagrangian node-to-surface contact (paper eq. 18) against
// closed forms: a block whose top-face nodes are held by linear springs is pressed by a rigid
// plane and the plane is then slid sideways and back. Each node sticks while the spring force
// k |u_t| stays below mu N and slips with the tangential force mu N beyond; the path back shows
// the stick-slip hysteresis. The contact tangent, with friction and on the curved surfaces of the
// rounded cone, the sphere and the rounded pyramid, is checked against differences of the
// residual. Units: um, mN, GPa.
#include "contact/NodeToSurfaceContact.h"
#include "indenter/Cone.h"
#include "indenter/Pyramid.h"
#include "indenter/RoundedCone.h"
#include "indenter/Sphere.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>

using namespace indentsim;
using namespace dealii;

namespace
{
  // A rigid plane z = -depth (the indenter occupies z >= -depth, the specimen lies below).
  class Plane : public indenter::IndenterSurface
  {
  public:
    double                      profile(double, double) const override { return 0; }
    indenter::SurfaceProjection project(const Point<3> &x, const double depth) const override
    {
      indenter::SurfaceProjection p;
      p.gap = -depth - x[2];
      p.closest_point = Point<3>(x[0], x[1], -depth);
      p.normal = Tensor<1, 3>({0., 0., -1.});
      return p;
    }
    double      projected_area(double) const override { return 0; }
    std::string name() const override { return "plane"; }
    bool        mirror_symmetric_about_xz_and_yz() const override { return true; }
  };

  // One hexahedron [0,1]^2 x [-1,0] um; its four top-face nodes are the contact nodes, each held
  // by an isotropic linear spring of stiffness k to its reference position; the bottom nodes are
  // fixed. The problem (springs + contact) is solved by Newton with Uzawa augmentations.
  class SpringBlock
  {
  public:
    SpringBlock(const indenter::IndenterSurface &surface, const double mu, const double penalty,
                const double spring = 1.0)
      : k(spring)
      , fe(FE_Q<3>(1), 3)
      , dof_handler(triangulation)
      , contact(surface, penalty, mu)
    {
      GridGenerator::hyper_rectangle(triangulation, Point<3>(0, 0, -1), Point<3>(1, 1, 0), true);
      dof_handler.distribute_dofs(fe);
      owned = dof_handler.locally_owned_dofs();
      AffineConstraints<double> none;
      none.close();
      contact.setup(dof_handler, none, 5, 2., 2., MPI_COMM_SELF); // face 5: z = 0
      DynamicSparsityPattern pattern(dof_handler.n_dofs(), dof_handler.n_dofs());
      for (unsigned int i = 0; i < dof_handler.n_dofs(); ++i)
        for (unsigned int j = 0; j < dof_handler.n_dofs(); ++j)
          pattern.add(i, j);
      matrix.reinit(owned, owned, pattern, MPI_COMM_SELF);
      u.reinit(owned, MPI_COMM_SELF);
      residual.reinit(owned, MPI_COMM_SELF);
      is_top.assign(dof_handler.n_dofs(), false);
      for (const auto &node : contact.nodes())
        for (const auto dof : node.dofs)
          is_top[dof] = true;
    }

    // Residual (springs minus contact forces) and, optionally, its tangent as a dense matrix.
    double assemble(const contact::NodeToSurfaceContact::ActiveSet mode, const double depth,
                    FullMatrix<double> *tangent)
    {
      EXPECT_TRUE(contact.evaluate(u, depth, mode));
      residual = 0;
      matrix = 0;
      AffineConstraints<double> none;
      none.close();
      contact.assemble(none, residual, tangent ? &matrix : nullptr);
      residual.compress(VectorOperation::add);
      matrix.compress(VectorOperation::add);
      const unsigned int n = dof_handler.n_dofs();
      if (tangent)
        tangent->reinit(n, n);
      double norm = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          double r = is_top[i] ? residual(i) + k * u(i) : 0.0;
          norm += r * r;
          residual_values[i] = r;
          if (tangent)
            for (unsigned int j = 0; j < n; ++j)
              (*tangent)(i, j) =
                  is_top[i] ? matrix.el(i, j) + (i == j ? k : 0.0) : (i == j ? 1.0 : 0.0);
        }
      return std::sqrt(norm);
    }

    // Solves one increment to the indenter position (depth, lateral offset), augmenting until
    // the gaps and stick slips are within 1e-12 um (at most max_passes passes); the penalty of a
    // node whose gap beyond `stiffen_above` a pass does not reduce fourfold is raised
    // (NodeToSurfaceContact::augment). Returns the passes taken.
    unsigned int solve(const double depth, const double offset_x,
                       const double       stiffen_above = std::numeric_limits<double>::infinity(),
                       const unsigned int max_passes = 60, const bool accept = true)
    {
      contact.set_lateral_offset(Tensor<1, 3>({offset_x, 0., 0.}));
      bool         augmented_enough = false;
      unsigned int pass = 0;
      for (; pass < max_passes && !augmented_enough; ++pass)
        {
          contact.start_pass();
          EXPECT_TRUE(newton(depth))
              << "Newton did not converge at depth " << depth << ", offset " << offset_x;
          const auto s = contact.summary();
          augmented_enough = s.max_penetration <= 1e-12 && s.max_stick_slip <= 1e-12;
          if (!augmented_enough)
            contact.augment(false, stiffen_above);
        }
      if (accept)
        {
          EXPECT_TRUE(augmented_enough);
          contact.accept_increment();
        }
      return pass;
    }

    // Newton with fixed multipliers (one augmentation pass) to |R| < 1e-14 mN (times k for
    // springs stiffer than 1 mN/um: the round-off of their forces); false if it does not get
    // there in 30 iterations.
    bool newton(const double depth)
    {
      const unsigned int n = dof_handler.n_dofs();
      residual_values.assign(n, 0.);
      for (unsigned int it = 0; it < 30; ++it)
        {
          FullMatrix<double> tangent;
          const double       norm =
              assemble(contact::NodeToSurfaceContact::ActiveSet::free, depth, &tangent);
          if (norm < 1e-14 * std::max(1.0, k))
            return true;
          tangent.gauss_jordan();
          Vector<double> r(residual_values.begin(), residual_values.end()), du(n);
          tangent.vmult(du, r);
          for (unsigned int i = 0; i < n; ++i)
            shift(i, -du(i));
        }
      return false;
    }

    // u_i += delta (serial PETSc vector, insert mode).
    void shift(const unsigned int i, const double delta)
    {
      const double value = u(i);
      u(i) = value + delta;
      u.compress(VectorOperation::insert);
    }

    const double                     k; // spring stiffness [mN/um]
    Triangulation<3>                 triangulation;
    FESystem<3>                      fe;
    DoFHandler<3>                    dof_handler;
    IndexSet                         owned;
    contact::NodeToSurfaceContact    contact;
    PETScWrappers::MPI::SparseMatrix matrix;
    PETScWrappers::MPI::Vector       u, residual;
    std::vector<bool>                is_top;
    std::vector<double>              residual_values;
  };

  // Every top node carries the same state: checks its displacement and the total forces.
  void expect_state(const SpringBlock &block, const double u_x, const double force_x,
                    const double force_z, const unsigned int n_stick, const char *what)
  {
    SCOPED_TRACE(what);
    const auto s = block.contact.summary();
    EXPECT_EQ(s.n_active, 4u);
    EXPECT_EQ(s.n_stick, n_stick);
    EXPECT_EQ(s.n_slip, 4u - n_stick);
    // The augmentations stop at gaps and stick slips of 1e-12 um, i.e. at nodal forces within
    // eps A 1e-12 = 2.5e-11 mN of the exact ones (four nodes: 1e-10 mN).
    EXPECT_NEAR(s.force_z, force_z, 1e-10);
    EXPECT_NEAR(s.force_on_specimen[0], force_x, 1e-10);
    EXPECT_NEAR(s.force_on_specimen[1], 0.0, 1e-10);
    for (const auto &node : block.contact.nodes())
      EXPECT_NEAR(block.u(node.dofs[0]), u_x, 1e-12);
  }
} // namespace

// Requirement: pressed by d and slid by s, a node on a spring k sticks (tangential force k s,
// node carried along with the plane) while k s <= mu k d and slips with the force mu N beyond;
// sliding back, it sticks until the traction has reversed (a travel of 2 mu d) and then slips
// the other way: the exact Coulomb response, with no slip while sticking and no penetration.
TEST(Friction, SpringBlockStickSlipAndReversal)
{
  const Plane  plane;
  const double mu = 0.3, d = 0.01;
  SpringBlock  block(plane, mu, 100.0);
  const double N = 4 * block.k * d; // total normal force [mN]

  block.solve(d, 0.0);
  expect_state(block, 0.0, 0.0, N, 4, "pressed");

  block.solve(d, 0.001); // k s = 0.001 < mu k d = 0.003: stick
  expect_state(block, 0.001, 4 * block.k * 0.001, N, 4, "stick at s = 0.001");

  block.solve(d, 0.002);
  expect_state(block, 0.002, 4 * block.k * 0.002, N, 4, "stick at s = 0.002");

  block.solve(d, 0.01); // beyond mu d: slip, the node stays at mu d behind the plane
  expect_state(block, mu * d, mu * N, N, 0, "slip at s = 0.01");

  block.solve(d, 0.006); // back by 0.004 < 2 mu d: stick again
  expect_state(block, mu * d - 0.004, 4 * block.k * (mu * d - 0.004), N, 4,
               "stick on the way back");

  block.solve(d, 0.0); // back by 0.01 > 2 mu d: slip the other way
  expect_state(block, -mu * d, -mu * N, N, 0, "reverse slip");
}

// Requirement: a contact node far stiffer than its penalty still reaches the indenter in a few
// augmentation passes, at the exact answer. Each node's spring k = 2 500 mN/um is 100 times its
// penalty stiffness eps A = 100 GPa/um x 0.25 um^2, so that a plain Uzawa update shrinks the
// penetration by k / (k + eps A) = 0.99 per pass (the apex node of a nearly sharp tip under tens
// of GPa in an indentation); where a pass has not reduced a gap fourfold, the node's penalty is
// raised fourfold. Closed form: each node sits on the plane, u_z = -d, carrying k d. After the
// increment the penalties are the initial ones again.
TEST(Augmentation, NodesStifferThanTheirPenaltyGetItRaised)
{
  const Plane        plane;
  const double       d = 0.01, spring = 2500.0;
  SpringBlock        raised(plane, 0.0, 100.0, spring);
  const unsigned int passes = raised.solve(d, 0.0, 1e-12);
  EXPECT_LE(passes, 20u); // 5 raises, then about 11 times less per pass; plain: about 2 000
  const auto s = raised.contact.summary();
  EXPECT_EQ(s.n_active, 4u);
  EXPECT_NEAR(s.force_z, 4 * spring * d, 2e-8); // gaps within 1e-12 um: k 1e-12 per node
  for (const auto &node : raised.contact.nodes())
    {
      EXPECT_NEAR(raised.u(node.dofs[2]), -d, 2e-12);
      EXPECT_EQ(node.penalty, node.penalty_initial);
      EXPECT_EQ(node.penalty_initial, 100.0);
    }

  // The plain update, with as many passes, is still far from the plane.
  SpringBlock plain(plane, 0.0, 100.0, spring);
  plain.solve(d, 0.0, std::numeric_limits<double>::infinity(), passes, false);
  EXPECT_GT(plain.contact.summary().max_penetration, 1e-4);
  std::cout << "[ augmentation ] " << passes << " passes with the raise; the plain update after "
            << passes << ": penetration " << plain.contact.summary().max_penetration << " um"
            << std::endl;
}

// Requirement: mu = 0 gives the frictionless response: no tangential force, whatever the slide.
TEST(Friction, ZeroCoefficientTransmitsNoTangentialForce)
{
  const Plane plane;
  SpringBlock block(plane, 0.0, 100.0);
  block.solve(0.01, 0.0);
  block.solve(0.01, 0.005);
  expect_state(block, 0.0, 0.0, 4 * block.k * 0.01, 0, "frictionless slide");
}

// Within a Newton pass the free active set only grows: a node active in an earlier evaluation of
// the pass stays active (held, carrying tension if it would separate), so that the semi-smooth
// iteration cannot release and recapture it; start_pass releases it, and the contact conditions
// report the held node's gap meanwhile.
TEST(Friction, ActiveNodesAreHeldUntilThePassEnds)
{
  using ActiveSet = contact::NodeToSurfaceContact::ActiveSet;
  const Plane plane;
  SpringBlock block(plane, 0.0, 100.0);
  block.contact.start_pass();
  ASSERT_TRUE(block.contact.evaluate(block.u, 0.01, ActiveSet::free)); // 0.01 um into the plane
  EXPECT_EQ(block.contact.summary().n_active, 4u);
  ASSERT_TRUE(block.contact.evaluate(block.u, -0.01, ActiveSet::free)); // plane 0.01 um above
  for (const auto &node : block.contact.nodes())
    {
      EXPECT_TRUE(node.active);
      EXPECT_NEAR(node.pressure, -100.0 * 0.01, 1e-12); // p = lambda - eps g, unclipped
    }
  EXPECT_NEAR(block.contact.summary().max_active_gap, 0.01, 1e-12);
  EXPECT_FALSE(block.contact.summary().conditions_met(1e-6));
  block.contact.augment(); // the multipliers stay >= 0
  for (const auto &node : block.contact.nodes())
    EXPECT_EQ(node.lambda, 0.0);
  block.contact.start_pass();
  ASSERT_TRUE(block.contact.evaluate(block.u, -0.01, ActiveSet::free));
  EXPECT_EQ(block.contact.summary().n_active, 0u);
  EXPECT_TRUE(block.contact.summary().conditions_met(1e-6));
}

// An iterate the line search rejects takes its statuses with it: a trial state that pushed the
// block 0.01 um into the plane neither holds its nodes for the rest of the pass nor hands them
// to a frozen set, so that the damped iterate (here the plane 0.01 um above the block) is free of
// them. Without the rejection the nodes stay held and carry the tension eps g (the test above).
TEST(Friction, RejectedIterateNeitherHoldsNorFreezesItsNodes)
{
  using ActiveSet = contact::NodeToSurfaceContact::ActiveSet;
  const Plane plane;
  SpringBlock block(plane, 0.0, 100.0);
  block.contact.start_pass();
  ASSERT_TRUE(block.contact.evaluate(block.u, -0.01, ActiveSet::free)); // accepted: open
  EXPECT_EQ(block.contact.summary().n_active, 0u);
  ASSERT_TRUE(block.contact.evaluate(block.u, 0.01, ActiveSet::free)); // trial: 0.01 um in
  EXPECT_EQ(block.contact.summary().n_active, 4u);
  block.contact.reject_last_evaluation();
  for (const ActiveSet mode : {ActiveSet::frozen, ActiveSet::free})
    {
      ASSERT_TRUE(block.contact.evaluate(block.u, -0.01, mode));
      EXPECT_EQ(block.contact.summary().n_active, 0u);
      for (const auto &node : block.contact.nodes())
        {
          EXPECT_FALSE(node.active);
          EXPECT_EQ(node.pressure, 0.0);
        }
    }
  // A trial that stays is kept: evaluated again without rejection, the nodes are held.
  ASSERT_TRUE(block.contact.evaluate(block.u, 0.01, ActiveSet::free));
  ASSERT_TRUE(block.contact.evaluate(block.u, -0.01, ActiveSet::free));
  for (const auto &node : block.contact.nodes())
    {
      EXPECT_TRUE(node.active);
      EXPECT_NEAR(node.pressure, -100.0 * 0.01, 1e-12);
    }
}

namespace
{
  // The largest difference between `tangent` and the central differences (step 1e-6 um) of the
  // block's residual at frozen contact statuses [mN/um].
  double difference_from_central_differences(SpringBlock &block, const double depth,
                                             const FullMatrix<double> &tangent)
  {
    const unsigned int n = block.dof_handler.n_dofs();
    const double       h = 1e-6;
    double             max_error = 0;
    for (unsigned int j = 0; j < n; ++j)
      {
        if (!block.is_top[j])
          continue;
        std::vector<double> r_plus, r_minus;
        for (const double sign : {1.0, -1.0})
          {
            block.shift(j, sign * h);
            block.assemble(contact::NodeToSurfaceContact::ActiveSet::frozen, depth, nullptr);
            (sign > 0 ? r_plus : r_minus) = block.residual_values;
            block.shift(j, -sign * h);
          }
        for (unsigned int i = 0; i < n; ++i)
          max_error =
              std::max(max_error, std::abs((r_plus[i] - r_minus[i]) / (2 * h) - tangent(i, j)));
      }
    return max_error;
  }
} // namespace

// Requirement: the contact tangent with friction (normal curvature, stick and slip parts) is the
// derivative of the contact residual at frozen statuses, checked against central differences of
// the assembled residual on the curved rounded-cone indenter.
TEST(Friction, TangentMatchesDifferencesOfTheResidual)
{
  const indenter::RoundedCone cone(2.48, 0.5);
  for (const double mu : {0.05, 2.0}) // mostly slipping, then sticking
    {
      SCOPED_TRACE("mu = " + std::to_string(mu));
      SpringBlock block(cone, mu, 50.0);
      block.solve(0.05, 0.0);
      // A trial state inside the increment: pushed deeper and dragged sideways.
      block.contact.set_lateral_offset(Tensor<1, 3>({0.02, -0.01, 0.}));
      for (unsigned int i = 0; i < block.dof_handler.n_dofs(); ++i)
        if (block.is_top[i])
          block.shift(i, 1e-3 * std::sin(1.0 + i));
      const double depth = 0.08;
      using ActiveSet = contact::NodeToSurfaceContact::ActiveSet;
      FullMatrix<double> tangent;
      block.assemble(ActiveSet::free, depth, &tangent);
      const auto s = block.contact.summary();
      ASSERT_GT(s.n_active, 0u);
      if (mu > 1)
        EXPECT_GT(s.n_stick, 0u);
      else
        EXPECT_GT(s.n_slip, 0u);

      double max_entry = 0;
      for (unsigned int i = 0; i < tangent.m(); ++i)
        for (unsigned int j = 0; j < tangent.n(); ++j)
          max_entry = std::max(max_entry, std::abs(tangent(i, j)));
      const double max_error = difference_from_central_differences(block, depth, tangent);
      EXPECT_LT(max_error, 1e-6 * max_entry) << "largest entry " << max_entry;
    }
}

// Requirement: the contact tangent is the derivative of the contact residual also on a pyramid
// with rounded tip and edges (Pyramid: the sharp pyramid's projection moved by R), with and
// without friction, where a node's foot lies on a face or on a rounded edge. Oracle: central
// differences of the residual at frozen statuses. The Berkovich apex (R = 0.05 um) stands over
// the block's centre, 0.01 um deeper than the surface over the node (0, 0); turned by 0, 15 and
// 60 deg the node lies under a face, turned by 44 to 46 deg under (and beside) the edge at 225
// deg, whose rounding carries its foot (a normal nearer the vertical than the faces').
TEST(PyramidContact, TangentMatchesDifferencesOfTheResidual)
{
  const double face_normal_z = std::sin(indenter::Pyramid::berkovich_face_angle_deg * M_PI / 180);
  for (const double rotation : {0.0, 15.0, 44.0, 45.0, 45.5, 46.0, 60.0})
    for (const double mu : {0.0, 2.0})
      {
        SCOPED_TRACE("rotation " + std::to_string(rotation) + " deg, mu = " + std::to_string(mu));
        const indenter::Pyramid berkovich = indenter::Pyramid::berkovich(0.05, rotation);
        SpringBlock             block(berkovich, mu, 50.0);
        block.contact.set_lateral_offset(Tensor<1, 3>({0.5, 0.5, 0.}));
        block.residual_values.assign(block.dof_handler.n_dofs(), 0.);
        for (unsigned int i = 0; i < block.dof_handler.n_dofs(); ++i)
          if (block.is_top[i])
            block.shift(i, 1e-4 * std::sin(1.0 + i));
        const double depth = berkovich.profile(-0.5, -0.5) + 0.01;
        using ActiveSet = contact::NodeToSurfaceContact::ActiveSet;
        FullMatrix<double> tangent;
        block.assemble(ActiveSet::free, depth, &tangent);
        const contact::ContactNode &corner = block.contact.nodes()[0];
        ASSERT_LT(corner.X.norm(), 1e-12);
        ASSERT_TRUE(corner.active);
        const bool under_edge = std::abs(rotation - 45) < 2;
        EXPECT_EQ(std::abs(corner.normal[2]) > face_normal_z + 1e-3, under_edge)
            << "normal " << corner.normal;
        double max_entry = 0;
        for (unsigned int i = 0; i < tangent.m(); ++i)
          for (unsigned int j = 0; j < tangent.n(); ++j)
            max_entry = std::max(max_entry, std::abs(tangent(i, j)));
        EXPECT_LT(difference_from_central_differences(block, depth, tangent), 1e-6 * max_entry)
            << "largest entry " << max_entry;
      }
}

// Requirement: the frictionless contact tangent is the exact derivative of the contact forces,
// the indenter's curvature term -p A dn/dx included. Oracle: a sphere of radius R pressed 0.05 um
// into the block touches only the node on its axis, whose normal turns as (I - n n)/rho with the
// distance rho = R - 0.05 um from the centre: that node's two tangential diagonal entries are
// the spring's k - p A / rho, and the tangent equals the central differences of the residual.
TEST(FrictionlessContact, TangentHoldsTheIndentersCurvature)
{
  const double           radius = 2.0, depth = 0.05;
  const indenter::Sphere sphere(radius);
  SpringBlock            block(sphere, 0.0, 50.0);
  const unsigned int     n = block.dof_handler.n_dofs();
  block.residual_values.assign(n, 0.);
  using ActiveSet = contact::NodeToSurfaceContact::ActiveSet;
  FullMatrix<double> tangent;
  block.assemble(ActiveSet::free, depth, &tangent);
  ASSERT_EQ(block.contact.summary().n_active, 1u);
  const contact::ContactNode *apex = nullptr;
  for (const auto &node : block.contact.nodes())
    if (node.active)
      apex = &node;
  ASSERT_NE(apex, nullptr);
  ASSERT_LT(apex->x.norm(), 1e-12);
  const double force = apex->pressure * apex->area, rho = radius - depth;
  ASSERT_GT(force, 0);

  EXPECT_LT(difference_from_central_differences(block, depth, tangent), 1e-6 * force / rho);
  for (const unsigned int c : {0u, 1u})
    EXPECT_NEAR(tangent(apex->dofs[c], apex->dofs[c]), block.k - force / rho, 1e-9 * block.k)
        << "tangential direction " << c;
}

#include "../test_cases.h"
#include "problems/IndentationProblem.h"

namespace
{
  std::vector<nonlinear::StepRecord> run_with_friction(const double mu)
  {
    io::Case c = test_cases::small_j2_case("quarter");
    c.contact.friction_coefficient = mu;
    // The answer is defined to the contact tolerance; both paths must reach the same one, whose
    // augmentation passes may differ, so the tolerance is tight enough for the 1e-7 below.
    c.contact.penetration_tolerance = 1e-9;
    problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
    problem.setup();
    problem.run("");
    return problem.records();
  }
} // namespace

// Requirement: the friction code path is continuous in mu: a vanishing coefficient (1e-9)
// reproduces the frictionless loading curve (to 1e-7 relative, with a penetration tolerance of
// 1e-9 um).
TEST(FrictionIndentation, VanishingCoefficientGivesTheFrictionlessCurve)
{
  const auto frictionless = run_with_friction(0.0);
  const auto tiny = run_with_friction(1e-9);
  ASSERT_EQ(frictionless.size(), tiny.size());
  const double scale = frictionless.back().force;
  ASSERT_GT(scale, 0);
  for (std::size_t i = 0; i < tiny.size(); ++i)
    {
      EXPECT_EQ(tiny[i].depth, frictionless[i].depth);
      EXPECT_NEAR(tiny[i].force, frictionless[i].force, 1e-7 * scale) << "step " << i;
    }
}

// Requirement: at every contact node of a converged J2 indentation with mu = 0.2 (small case, at
// each loading step), the Coulomb conditions of eq. 18 hold: |t| <= mu p with t in the tangent
// plane; a sticking node has not slipped beyond the tolerance; a slipping node carries
// |t| = mu p, opposite to its slip; and both states occur at maximum depth.
TEST(FrictionIndentation, CoulombConditionsHoldAtConvergence)
{
  const double mu = 0.2;
  io::Case     c = test_cases::small_j2_case("quarter");
  c.contact.friction_coefficient = mu;
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  unsigned int n_stick = 0, n_slip = 0;
  for (unsigned int step = 1; step <= c.loading.steps; ++step)
    {
      nonlinear::StepRecord record;
      const double          depth = c.loading.max_depth * step / c.loading.steps;
      // As run() does: an extrapolated start that fails is retried from the converged state.
      if (problem.solve_increment(depth, record) != nonlinear::IncrementStatus::converged)
        {
          problem.reject_increment();
          ASSERT_EQ(problem.solve_increment(depth, record, false),
                    nonlinear::IncrementStatus::converged)
              << "depth " << depth;
        }
      n_stick = n_slip = 0;
      for (const auto &node : problem.contact().nodes())
        {
          if (node.status == contact::ContactStatus::open)
            continue;
          const double limit = mu * node.pressure;
          EXPECT_LE(node.traction.norm(), limit * (1 + 1e-12) + 1e-15);
          EXPECT_NEAR(node.traction * node.normal, 0.0, 1e-12 * (1 + node.traction.norm()));
          if (node.status == contact::ContactStatus::stick)
            {
              ++n_stick;
              EXPECT_LE(node.slip.norm(), c.contact.penetration_tolerance);
            }
          else
            {
              ++n_slip;
              EXPECT_NEAR(node.traction.norm(), limit, 1e-12 * (1 + limit));
              if (node.slip.norm() > 1e-9)
                {
                  EXPECT_LT(node.traction * node.slip, 0.0);
                }
            }
        }
      EXPECT_EQ(n_stick, record.n_stick_nodes);
      EXPECT_EQ(n_slip, record.n_slip_nodes);
      problem.accept_increment();
    }
  std::cout << "[ friction ] at maximum depth: " << n_stick << " sticking, " << n_slip
            << " slipping nodes" << std::endl;
  EXPECT_GT(n_stick, 0u);
  EXPECT_GT(n_slip, 0u);
}

// Requirement: augmentation_jump() is the residual the next Uzawa update creates. Frictionless,
// with every node in contact, the update lambda <- p = lambda - eps g changes each nodal force by
// A eps |g| at the converged state of the pass (where |R| ~ 0): after augment() the residual at
// the same displacement must have exactly that norm. First pass (lambda = 0) of the spring block
// pressed by d: each node penetrates by p = k d / (eps A + k).
TEST(Friction, AugmentationJumpIsTheResidualOfTheNextPass)
{
  const Plane  plane;
  const double d = 0.01;
  SpringBlock  block(plane, 0.0, 100.0);
  ASSERT_TRUE(block.newton(d));
  const double jump = block.contact.augmentation_jump();
  // Each of the 4 nodes: spring force k (d - p) = eps A p for penetration p, A = 1/4 um^2.
  const double area = 0.25, penetration = block.k * d / (100.0 * area + block.k);
  EXPECT_NEAR(jump, 2 * 100.0 * area * penetration, 1e-12); // sqrt(4) nodes
  block.contact.augment();
  const double norm = block.assemble(contact::NodeToSurfaceContact::ActiveSet::free, d, nullptr);
  EXPECT_NEAR(norm, jump, 1e-12 * jump);
  // The gaps have not moved, so the next update would change the forces by the same amount.
  EXPECT_NEAR(block.contact.augmentation_jump(), jump, 1e-12 * jump);
}

// Requirement: after an augmentation at an unchanged displacement, retract() takes off exactly
// what the last assemble() added, so that retract + assemble leaves the system a fresh assembly
// gives (the element part plus the new contact part): with friction (a non-symmetric tangent)
// and with a dof under a homogeneous constraint, whose row AffineConstraints gives a diagonal
// entry of either sign of the local matrix. Without a kept contribution nothing is retracted.
TEST(Friction, RetractThenAssembleEqualsAFreshAssembly)
{
  using ActiveSet = contact::NodeToSurfaceContact::ActiveSet;
  const Plane               plane;
  SpringBlock               block(plane, 0.3, 100.0);
  AffineConstraints<double> symmetry; // u_y = 0 at one top node, as on a symmetry plane
  symmetry.add_line(block.contact.nodes()[0].dofs[1]);
  symmetry.close();
  for (const auto &node : block.contact.nodes())
    {
      block.shift(node.dofs[2], -0.002 * (1 + node.X[0])); // inside the indenter (z > -depth)
      block.shift(node.dofs[0], 0.002 * (1 + node.X[1]));
    }
  block.contact.set_lateral_offset(Tensor<1, 3>({0.001, 0., 0.}));
  const double       depth = 0.01;
  const unsigned int n = block.dof_handler.n_dofs();

  // An arbitrary "element part" in every entry of the (dense) pattern.
  const auto element_part = [n](PETScWrappers::MPI::SparseMatrix &A,
                                PETScWrappers::MPI::Vector       &r) {
    for (unsigned int i = 0; i < n; ++i)
      {
        for (unsigned int j = 0; j < n; ++j)
          A.set(i, j, 1.0 + i + 0.1 * j);
        r(i) = 0.5 - 0.01 * i;
      }
    A.compress(VectorOperation::insert);
    r.compress(VectorOperation::insert);
  };
  PETScWrappers::MPI::SparseMatrix &A = block.matrix;
  PETScWrappers::MPI::Vector       &r = block.residual;
  element_part(A, r);
  ASSERT_TRUE(block.contact.evaluate(block.u, depth, ActiveSet::free));
  EXPECT_FALSE(block.contact.retract(symmetry, r, A)); // nothing assembled yet
  block.contact.assemble(symmetry, r, &A);
  A.compress(VectorOperation::add);
  r.compress(VectorOperation::add);
  ASSERT_EQ(block.contact.summary().n_active, 4u);

  // Augment and evaluate again at the same displacement: new pressures and tractions.
  block.contact.augment();
  ASSERT_TRUE(block.contact.evaluate(block.u, depth, ActiveSet::free));
  ASSERT_TRUE(block.contact.retract(symmetry, r, A));
  EXPECT_FALSE(block.contact.retract(symmetry, r, A)); // retracted once only
  block.contact.assemble(symmetry, r, &A);
  A.compress(VectorOperation::add);
  r.compress(VectorOperation::add);

  PETScWrappers::MPI::SparseMatrix fresh_A;
  fresh_A.reinit(A);
  PETScWrappers::MPI::Vector fresh_r(block.owned, MPI_COMM_SELF);
  element_part(fresh_A, fresh_r);
  block.contact.assemble(symmetry, fresh_r, &fresh_A);
  fresh_A.compress(VectorOperation::add);
  fresh_r.compress(VectorOperation::add);

  double largest_contact_entry = 0;
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      largest_contact_entry =
          std::max(largest_contact_entry, std::abs(fresh_A.el(i, j) - (1.0 + i + 0.1 * j)));
  ASSERT_GT(largest_contact_entry, 10.0); // the contact part is there (penalty 100 GPa/um)
  for (unsigned int i = 0; i < n; ++i)
    {
      EXPECT_NEAR(r(i), fresh_r(i), 1e-12) << "residual row " << i;
      for (unsigned int j = 0; j < n; ++j)
        EXPECT_NEAR(A.el(i, j), fresh_A.el(i, j), 1e-12 * largest_contact_entry)
            << "entry " << i << ", " << j;
    }
}

namespace
{
  // The node of `contact` (set up with a sharp 70.3 deg cone) on the axis, the apex at the
  // depth 0.1 um, placed s = -2e-6 ... 2e-6 um above the apex (inside the cone for s > 0) under
  // the normal multiplier lambda = 2 GPa: checks the gap, normal, traction and forces of
  // AxisNodeUnderASharpApexIsPushedAlongTheAxis. The other contact nodes stay clear of the cone.
  void expect_axis_response(contact::NodeToSurfaceContact &contact, const IndexSet &owned)
  {
    const double depth = 0.1, lambda = 2.0; // [um], [GPa]
    const auto  &nodes = contact.nodes();
    unsigned int axis = nodes.size();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (nodes[i].X[0] == 0.0 && nodes[i].X[1] == 0.0)
        axis = i;
    ASSERT_LT(axis, nodes.size());
    ASSERT_TRUE(nodes[axis].on_axis);
    const double                  penalty = nodes[axis].penalty, area = nodes[axis].area;
    const types::global_dof_index z_dof = nodes[axis].dofs[contact.axes().size() - 1];
    PETScWrappers::MPI::Vector    u(owned, MPI_COMM_SELF);
    // The multiplier: one evaluation penetrating by lambda / eps, then the Uzawa update.
    u(z_dof) = -depth + lambda / penalty;
    u.compress(VectorOperation::insert);
    ASSERT_TRUE(contact.evaluate(u, depth));
    contact.augment();
    for (const double s : {-2e-6, -1e-6, 0.0, 1e-6, 2e-6}) // above the apex: s > 0
      {
        SCOPED_TRACE("the node " + std::to_string(s) + " um above the apex");
        u(z_dof) = -depth + s;
        u.compress(VectorOperation::insert);
        ASSERT_TRUE(contact.evaluate(u, depth));
        const auto &node = contact.nodes()[axis];
        ASSERT_TRUE(node.active);
        EXPECT_NEAR(node.gap, -s, 1e-15);
        EXPECT_EQ(node.normal[0], 0.0);
        EXPECT_EQ(node.normal[1], 0.0);
        EXPECT_EQ(node.normal[2], -1.0);
        EXPECT_EQ(node.traction.norm(), 0.0);
        const auto summary = contact.summary();
        EXPECT_EQ(summary.n_active, 1u);
        EXPECT_NEAR(summary.force_z, area * (lambda + penalty * s), 1e-12);
        EXPECT_EQ(summary.force_on_specimen[0], 0.0);
        EXPECT_EQ(summary.force_on_specimen[1], 0.0);
      }
  }
} // namespace

// Requirement: a node that the model holds on the indenter's axis (the axisymmetric model's
// axis, the quarter model's edge x = y = 0) is pushed against a sharp apex (a cone with
// tip_radius 0) along the axis, by a force that is continuous and linear in its position just
// outside the indenter and just inside it alike: its gap is the vertical distance to the apex,
// its normal the axis, and it does not slip. Oracle: the Alart-Curnier pressure
// p = lambda - eps g with g = -(z - z_apex) exactly, and symmetry (no lateral force, no
// traction). The closest-point projection of that node jumps from the apex (normal along the
// axis) to a flank (normal tilted by the half-angle) as it crosses the apex, and Newton's method
// then cycles between the two sides without converging (a sharp 70.3 deg cone on a power-law
// material with friction 0.15: at 0.975 um in axisymmetric mode, and 103 cut-backs to 0.89 um
// in the quarter model).
TEST(Friction, AxisNodeUnderASharpApexIsPushedAlongTheAxis)
{
  const indenter::Cone cone(70.3, 0.0);
  for (const double mu : {0.0, 0.15})
    {
      SCOPED_TRACE("mu = " + std::to_string(mu));
      {
        SCOPED_TRACE("axisymmetric: one (r, z) cell [0, 1] x [-1, 0] um, top edge 3");
        Triangulation<2> triangulation;
        GridGenerator::hyper_rectangle(triangulation, Point<2>(0, -1), Point<2>(1, 0), true);
        FESystem<2>   fe(FE_Q<2>(1), 2);
        DoFHandler<2> dof_handler(triangulation);
        dof_handler.distribute_dofs(fe);
        AffineConstraints<double> none;
        none.close();
        contact::NodeToSurfaceContact contact(cone, 100.0, mu);
        contact.setup(dof_handler, none, 3, 2.0, MPI_COMM_SELF);
        ASSERT_EQ(contact.nodes().size(), 2u);
        expect_axis_response(contact, dof_handler.locally_owned_dofs());
      }
      {
        SCOPED_TRACE("quarter model: one cell [0, 1]^2 x [-1, 0] um, top face 5");
        Triangulation<3> triangulation;
        GridGenerator::hyper_rectangle(triangulation, Point<3>(0, 0, -1), Point<3>(1, 1, 0), true);
        FESystem<3>   fe(FE_Q<3>(1), 3);
        DoFHandler<3> dof_handler(triangulation);
        dof_handler.distribute_dofs(fe);
        AffineConstraints<double> none;
        none.close();
        contact::NodeToSurfaceContact contact(cone, 100.0, mu);
        contact.setup(dof_handler, none, 5, 2.0, 2.0, MPI_COMM_SELF, /*axis_held=*/true);
        ASSERT_EQ(contact.nodes().size(), 4u);
        expect_axis_response(contact, dof_handler.locally_owned_dofs());
        // A model that does not hold the node on the axis (the full model) keeps the
        // closest-point projection.
        contact::NodeToSurfaceContact free_contact(cone, 100.0, mu);
        free_contact.setup(dof_handler, none, 5, 2.0, 2.0, MPI_COMM_SELF);
        for (const auto &node : free_contact.nodes())
          EXPECT_FALSE(node.on_axis);
      }
    }
}
