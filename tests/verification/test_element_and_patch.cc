// Verification of the finite-strain hexahedron: element tangent against finite differences of
// the element residual (with and without F-bar, elastic and plastic), and patch tests on a mesh
// with hanging nodes. Units: um, mN, GPa.
#include "../problem_test_access.h"
#include "case/Case.h"
#include "fem/CellWorkspace.h"
#include "fem/FiniteStrainElement.h"
#include "materials/MaterialFactory.h"
#include "problems/IndentationProblem.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#include <random>

using namespace dealii;
using namespace indentsim;

namespace
{
  io::MaterialParameters paper_material(const std::string &model)
  {
    io::MaterialParameters m;
    m.model = model;
    return m; // Table 1: E 69 GPa, nu 0.26, sigma_y0 0.305 GPa, H 0.5 GPa
  }

  // Fills the element scratch of a randomly distorted unit-size hexahedron.
  void distorted_element(fem::ElementScratch &scratch)
  {
    Triangulation<3> tria;
    GridGenerator::hyper_rectangle(tria, Point<3>(0, 0, 0), Point<3>(2., 1.5, 1.));
    GridTools::distort_random(0.15, tria, false, 42);
    const FE_Q<3> fe(1);
    FEValues<3>   fe_values(fe, QGauss<3>(2), update_gradients | update_JxW_values);
    FEValues<3>   fe_centre(fe, QGauss<3>(1), update_gradients);
    fe_values.reinit(tria.begin_active());
    fe_centre.reinit(tria.begin_active());
    for (unsigned int q = 0; q < 8; ++q)
      {
        scratch.JxW[q] = fe_values.JxW(q);
        for (unsigned int i = 0; i < 8; ++i)
          scratch.grad[q][i] = fe_values.shape_grad(i, q);
      }
    for (unsigned int i = 0; i < 8; ++i)
      scratch.grad0[i] = fe_centre.shape_grad(i, 0);
  }

  // Largest entry-wise difference between the element tangent and central differences of the
  // element residual, relative to the largest tangent entry.
  double element_tangent_error(const std::string &model, bool f_bar, double amplitude)
  {
    const auto          material = materials::create_material(paper_material(model));
    const unsigned int  n_state = material->n_state_variables();
    std::vector<double> state_old(8 * n_state), state_new(8 * n_state);
    for (unsigned int q = 0; q < 8; ++q)
      material->initial_state(std::span<double>(state_old).subspan(q * n_state, n_state));

    fem::ElementScratch scratch(8, 8);
    distorted_element(scratch);
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> dist(-amplitude, amplitude);
    Vector<double>                         u(24), r(24), r_plus(24), r_minus(24);
    for (auto &v : u)
      v = dist(rng);
    FullMatrix<double> K(24, 24);
    EXPECT_EQ(fem::element_residual_and_tangent(*material, f_bar, u, state_old, state_new, scratch,
                                                r, &K),
              materials::UpdateStatus::success);

    double       error = 0, scale = 0;
    const double step = 1e-7;
    for (unsigned int b = 0; b < 24; ++b)
      {
        Vector<double> up(u), um(u);
        up[b] += step;
        um[b] -= step;
        fem::element_residual_and_tangent(*material, f_bar, up, state_old, state_new, scratch,
                                          r_plus, nullptr);
        fem::element_residual_and_tangent(*material, f_bar, um, state_old, state_new, scratch,
                                          r_minus, nullptr);
        for (unsigned int a = 0; a < 24; ++a)
          {
            error = std::max(error, std::abs(K(a, b) - (r_plus[a] - r_minus[a]) / (2 * step)));
            scale = std::max(scale, std::abs(K(a, b)));
          }
      }
    return error / scale;
  }
} // namespace

// The element tangent is the exact derivative of the element residual (neo-Hookean, with and
// without F-bar), so Newton converges quadratically.
TEST(FiniteStrainElement, TangentMatchesFiniteDifferencesNeoHookean)
{
  EXPECT_LT(element_tangent_error("neo_hookean", false, 0.2), 1e-6);
  EXPECT_LT(element_tangent_error("neo_hookean", true, 0.2), 1e-6);
}

// Same for J2 at a plastic state reached in one increment from virgin material (F-bar on/off).
TEST(FiniteStrainElement, TangentMatchesFiniteDifferencesJ2Plastic)
{
  EXPECT_LT(element_tangent_error("j2", false, 0.05), 1e-5);
  EXPECT_LT(element_tangent_error("j2", true, 0.05), 1e-5);
}

namespace
{
  io::Case patch_case(const std::string &model, bool f_bar)
  {
    io::Case c;
    c.material = paper_material(model);
    c.specimen.size = {{40., 40., 20.}};
    c.specimen.refined_region = {{16., 16., 4.}};
    c.specimen.contact_elements = 8;
    c.specimen.symmetry = "full";
    c.specimen.f_bar = f_bar;
    return c;
  }

  // Neo-Hookean Cauchy stress (paper eq. 2-3) in closed form: sigma = [mu (b - 1) +
  // lambda/2 (J^2 - 1) 1] / J.
  Tensor<2, 3> neo_hookean_cauchy(const Tensor<2, 3> &F, double E, double nu)
  {
    const double       mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    const double       J = determinant(F);
    const Tensor<2, 3> I = unit_symmetric_tensor<3>();
    return (mu * (F * transpose(F) - I) + 0.5 * lambda * (J * J - 1) * I) / J;
  }
} // namespace

// An affine displacement is reproduced exactly on a mesh with hanging nodes: no residual at
// interior nodes (transitions included) and the closed-form homogeneous stress everywhere.
TEST(PatchTest, AffineDisplacementOnHangingNodeMesh)
{
  for (const bool f_bar : {false, true})
    {
      const io::Case               c = patch_case("neo_hookean", f_bar);
      problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
      problem.setup();
      ASSERT_GT(problem.n_hanging_node_constraints(), 0u)
          << "the patch mesh must have hanging nodes";

      Tensor<2, 3> G;
      G[0][0] = 0.02, G[0][1] = -0.01, G[0][2] = 0.015, G[1][0] = 0.005, G[1][1] = -0.03,
      G[1][2] = 0.01, G[2][0] = -0.012, G[2][1] = 0.02, G[2][2] = 0.025;
      problems::ProblemTestAccess::set_displacement(problem,
                                                    [&](const Point<3> &X) { return G * X; });
      const Tensor<2, 3> F = unit_symmetric_tensor<3>() + G;
      const Tensor<2, 3> sigma = neo_hookean_cauchy(F, 69.0, 0.26);

      // Nodal forces scale like |sigma| h^2 ~ 2 GPa * 4 um^2 = 8 mN.
      EXPECT_LT(problems::ProblemTestAccess::interior_residual_norm(problem), 1e-9 * 8.0)
          << "f_bar " << f_bar;
      EXPECT_LT(problems::ProblemTestAccess::max_stress_error(problem, sigma), 1e-11)
          << "f_bar " << f_bar;
    }
}

// The same holds for homogeneous plastic flow (J2): the stress is uniform and the interior
// nodes stay in equilibrium across the hanging-node transitions.
TEST(PatchTest, AffinePlasticFlowOnHangingNodeMesh)
{
  const io::Case               c = patch_case("j2", true);
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  Tensor<2, 3> G;
  G[0][0] = 0.03, G[1][1] = -0.02, G[0][1] = 0.01, G[2][2] = -0.012;
  problems::ProblemTestAccess::set_displacement(problem, [&](const Point<3> &X) { return G * X; });
  EXPECT_LT(problems::ProblemTestAccess::interior_residual_norm(problem), 1e-9 * 8.0);
}

// The gradients and weights that CellWorkspace computes from the vertices (a constant Jacobian
// for parallelepipeds, the trilinear map point by point otherwise) against FEValues with
// deal.II's MappingQ1, on an axis-parallel box, a sheared and rotated parallelepiped and a
// randomly distorted hexahedron; and the displacement values read from the vector.
TEST(CellWorkspace, GradientsMatchFEValuesOnBoxesParallelepipedsAndDistortedCells)
{
  for (const unsigned int shape : {0u, 1u, 2u})
    {
      Triangulation<3> tria;
      GridGenerator::hyper_rectangle(tria, Point<3>(0.5, -1, 2), Point<3>(2.5, 0.5, 3));
      if (shape == 1)
        GridTools::transform(
            [](const Point<3> &p) {
              return Point<3>(0.8 * p[0] + 0.3 * p[1] - 0.2 * p[2], 0.1 * p[0] + 1.1 * p[1],
                              0.25 * p[0] - 0.4 * p[1] + 0.9 * p[2]);
            },
            tria);
      if (shape == 2)
        GridTools::distort_random(0.2, tria, false, 11);
      const FESystem<3> fe(FE_Q<3>(1), 3);
      DoFHandler<3>     dof_handler(tria);
      dof_handler.distribute_dofs(fe);
      fem::GhostedVector u(dof_handler.n_dofs());
      for (unsigned int k = 0; k < u.size(); ++k)
        u[k] = std::sin(1.7 * k);

      fem::CellWorkspace workspace(fe, 8);
      const auto         cell = dof_handler.begin_active();
      workspace.reinit(cell, u);
      FEValues<3> fe_values(fe, QGauss<3>(2), update_gradients | update_JxW_values);
      FEValues<3> fe_centre(fe, QGauss<3>(1), update_gradients);
      fe_values.reinit(cell);
      fe_centre.reinit(cell);
      double error = 0, scale = 0;
      for (unsigned int q = 0; q < 8; ++q)
        {
          EXPECT_NEAR(workspace.scratch.JxW[q], fe_values.JxW(q), 1e-13 * fe_values.JxW(q))
              << "shape " << shape;
          for (unsigned int i = 0; i < 8; ++i)
            {
              // node i is dof 3 i (component 0)
              const Tensor<1, 3> expected = fe_values.shape_grad_component(3 * i, q, 0);
              error = std::max(error, (workspace.scratch.grad[q][i] - expected).norm());
              scale = std::max(scale, expected.norm());
            }
        }
      for (unsigned int i = 0; i < 8; ++i)
        error = std::max(
            error,
            (workspace.scratch.grad0[i] - fe_centre.shape_grad_component(3 * i, 0, 0)).norm());
      EXPECT_LT(error, 1e-13 * scale) << "shape " << shape;
      std::vector<types::global_dof_index> dofs(24);
      cell->get_dof_indices(dofs);
      for (unsigned int a = 0; a < 24; ++a)
        EXPECT_EQ(workspace.u_local[a], u[dofs[a]]);
    }
}
