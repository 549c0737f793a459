// The constrained system that the matrix tests assemble: the unit cube of 4 x 4 x 4 cells,
// refined `rounds` times near the corner at the origin (hanging nodes on faces and edges),
// vector Q1 (three components per node, numbered together), the face z = 0 supported, and
// the sparsity pattern of deal.II's condensed assembly (a constrained row holds its diagonal).
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

namespace indentsim::test_meshes
{
  struct ConstrainedCube
  {
    dealii::parallel::distributed::Triangulation<3> triangulation;
    dealii::FESystem<3>                             fe{dealii::FE_Q<3>(1), 3};
    dealii::DoFHandler<3>                           dof_handler;
    dealii::IndexSet                                owned, relevant;
    dealii::AffineConstraints<double>               constraints;
    dealii::DynamicSparsityPattern                  sparsity;

    ConstrainedCube(const MPI_Comm communicator, const unsigned int rounds)
      : triangulation(communicator)
      , dof_handler(triangulation)
    {
      using namespace dealii;
      GridGenerator::subdivided_hyper_cube(triangulation, 4, 0., 1., /*colorize=*/true);
      for (unsigned int round = 0; round < rounds; ++round)
        {
          for (const auto &cell : triangulation.active_cell_iterators())
            if (cell->is_locally_owned() && cell->center().norm() < 0.45)
              cell->set_refine_flag();
          triangulation.execute_coarsening_and_refinement();
        }
      dof_handler.distribute_dofs(fe);
      owned = dof_handler.locally_owned_dofs();
      relevant = DoFTools::extract_locally_relevant_dofs(dof_handler);
      constraints.reinit(relevant);
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      VectorTools::interpolate_boundary_values(dof_handler, 4, Functions::ZeroFunction<3>(3),
                                               constraints); // the face z = 0
      constraints.close();
      sparsity.reinit(relevant.size(), relevant.size(), relevant);
      DoFTools::make_sparsity_pattern(dof_handler, sparsity, constraints, false);
      SparsityTools::distribute_sparsity_pattern(sparsity, owned, communicator, relevant);
    }
  };
} // namespace indentsim::test_meshes
