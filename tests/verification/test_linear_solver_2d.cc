// The linear solver on a 2D DoFHandler (the axisymmetric problems' systems): the iterative kind,
// with the z translation as the AMG's only near-null mode and 2 x 2 nodal blocks, solves an
// axisymmetric elastic system to the direct solver's answer. Units: um, mN, GPa.
#include "linalg/LinearSolver.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace dealii;
using indentsim::linalg::LinearSolver;

namespace
{
  // An axisymmetric elastic cylinder in (r, z) = [0, 50] x [0, 50] um (E = 69 GPa, nu = 0.26):
  // u_r = 0 on the axis, u_z = 0 at the bottom, a downward body force; strains (rr, zz, theta
  // theta, rz) with the hoop strain u_r / r, weight 2 pi r.
  struct AxisymmetricSystem
  {
    parallel::distributed::Triangulation<2> triangulation{MPI_COMM_WORLD};
    FESystem<2>                             fe{FE_Q<2>(1), 2};
    DoFHandler<2>                           dof_handler{triangulation};
    AffineConstraints<double>               constraints;
    PETScWrappers::MPI::SparseMatrix        matrix;
    PETScWrappers::MPI::Vector              rhs;

    AxisymmetricSystem()
    {
      GridGenerator::hyper_rectangle(triangulation, Point<2>(0, 0), Point<2>(50, 50), true);
      triangulation.refine_global(5); // 32 x 32 cells, 2 178 DOFs
      dof_handler.distribute_dofs(fe);
      const IndexSet owned = dof_handler.locally_owned_dofs();
      IndexSet       relevant;
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      constraints.reinit(relevant);
      VectorTools::interpolate_boundary_values(dof_handler, 0, Functions::ZeroFunction<2>(2),
                                               constraints,
                                               fe.component_mask(FEValuesExtractors::Scalar(0)));
      VectorTools::interpolate_boundary_values(dof_handler, 2, Functions::ZeroFunction<2>(2),
                                               constraints,
                                               fe.component_mask(FEValuesExtractors::Scalar(1)));
      constraints.close();
      DynamicSparsityPattern pattern(relevant);
      DoFTools::make_sparsity_pattern(dof_handler, pattern, constraints, false);
      SparsityTools::distribute_sparsity_pattern(pattern, owned, MPI_COMM_WORLD, relevant);
      matrix.reinit(owned, owned, pattern, MPI_COMM_WORLD);
      rhs.reinit(owned, MPI_COMM_WORLD);
      assemble();
    }

    void assemble()
    {
      const double       E = 69, nu = 0.26;
      const double       lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
      QGauss<2>          quadrature(2);
      FEValues<2>        fe_values(fe, quadrature,
                                   update_values | update_gradients | update_quadrature_points |
                                       update_JxW_values);
      const unsigned     n = fe.n_dofs_per_cell();
      FullMatrix<double> cell_matrix(n, n);
      Vector<double>     cell_rhs(n);
      std::vector<types::global_dof_index> dofs(n);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            cell_matrix = 0;
            cell_rhs = 0;
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                const double r = fe_values.quadrature_point(q)[0];
                const double weight = 2 * M_PI * r * fe_values.JxW(q);
                // B rows: rr, zz, theta theta, rz.
                std::vector<std::array<double, 4>> B(n);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    const unsigned int c = fe.system_to_component_index(i).first;
                    const Tensor<1, 2> g = fe_values.shape_grad(i, q);
                    const double       N = fe_values.shape_value(i, q);
                    B[i] = c == 0 ? std::array<double, 4>{g[0], 0, N / r, g[1]}
                                  : std::array<double, 4>{0, g[1], 0, g[0]};
                  }
                const double D[4][4] = {{lambda + 2 * mu, lambda, lambda, 0},
                                        {lambda, lambda + 2 * mu, lambda, 0},
                                        {lambda, lambda, lambda + 2 * mu, 0},
                                        {0, 0, 0, mu}};
                for (unsigned int i = 0; i < n; ++i)
                  {
                    for (unsigned int j = 0; j < n; ++j)
                      for (unsigned int k = 0; k < 4; ++k)
                        for (unsigned int l = 0; l < 4; ++l)
                          cell_matrix(i, j) += B[i][k] * D[k][l] * B[j][l] * weight;
                    if (fe.system_to_component_index(i).first == 1)
                      cell_rhs(i) -= 1e-3 * fe_values.shape_value(i, q) * weight;
                  }
              }
            cell->get_dof_indices(dofs);
            constraints.distribute_local_to_global(cell_matrix, cell_rhs, dofs, matrix, rhs);
          }
      matrix.compress(VectorOperation::add);
      rhs.compress(VectorOperation::add);
    }

    PETScWrappers::MPI::Vector solve(const LinearSolver::Kind kind)
    {
      LinearSolver solver(MPI_COMM_WORLD);
      solver.setup(dof_handler, kind, true);
      PETScWrappers::MPI::Vector x(dof_handler.locally_owned_dofs(), MPI_COMM_WORLD);
      const LinearSolver::Result result = solver.solve(matrix, x, rhs, 1e-10);
      EXPECT_TRUE(result.converged) << result.reason;
      if (kind == LinearSolver::Kind::iterative)
        {
          EXPECT_GT(result.iterations, 1u);
        }
      return x;
    }
  };
} // namespace

// An iterative solve on a 2D DoFHandler (near-null space: the z translation; 2 x 2 blocks)
// reaches the direct solver's solution to 1e-8 relative.
TEST(Solvers, TwoDimensionalSystemIterativeMatchesDirect)
{
  AxisymmetricSystem system;
  const auto         direct = system.solve(LinearSolver::Kind::direct);
  auto               difference = system.solve(LinearSolver::Kind::iterative);
  ASSERT_GT(direct.l2_norm(), 0);
  difference -= direct;
  EXPECT_LT(difference.l2_norm(), 1e-8 * direct.l2_norm());
}
