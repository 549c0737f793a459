// The fast matrix assembly (linalg/MatrixScatter) against deal.II's
// AffineConstraints::distribute_local_to_global with MatSetValues, the oracle: the same cell
// matrices on a mesh with hanging nodes and supports must give the same global matrix, on one
// rank and (test Mpi.*) on two, where the cells at the ranks' boundary send their entries in
// the other rank's rows to it (a wrong slot, position or message would show in those rows).
#include "linalg/MatrixScatter.h"

#include "../test_constrained_cube.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <gtest/gtest.h>

#include <cmath>

namespace
{
  using namespace dealii;
  using namespace indentsim;

  // A deterministic, nonsymmetric cell matrix with entries in [-1, 1]; every fifth cell has a
  // zero first diagonal entry (the mean-diagonal branch of the constrained rows).
  FullMatrix<double> cell_matrix(const unsigned int cell, const unsigned int n)
  {
    FullMatrix<double> K(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        K(i, j) = std::sin(1.3 * cell + 0.7 * i + 0.37 * j * j + 0.11 * i * j);
    if (cell % 5 == 0)
      K(0, 0) = 0;
    return K;
  }

  void check_scatter_against_constraints(const MPI_Comm communicator)
  {
    // Refined twice near one corner: hanging nodes on faces and edges.
    const test_meshes::ConstrainedCube cube(communicator, 2);
    const auto                        &dof_handler = cube.dof_handler;
    const auto                        &fe = cube.fe;
    const auto                        &owned = cube.owned;
    const auto                        &constraints = cube.constraints;
    const auto                        &dsp = cube.sparsity;
    ASSERT_GT(constraints.n_constraints(), 0u);

    PETScWrappers::MPI::SparseMatrix expected, scattered;
    expected.reinit(owned, owned, dsp, communicator);
    scattered.reinit(owned, owned, dsp, communicator);
    scattered.compress(VectorOperation::insert);
    PETScWrappers::MPI::Vector rhs(owned, communicator);

    indentsim::linalg::MatrixScatter scatter;
    scatter.build(dof_handler, constraints, scattered);
    EXPECT_EQ(scatter.fast_fraction(), 1.0);

    const unsigned int                   n = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    Vector<double>                       local_vector(n);
    unsigned long                        n_constrained_cells = 0;
    for (unsigned int pass = 0; pass < 2; ++pass) // twice: the arrays accumulate
      {
        scatter.begin(scattered);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dofs);
              const FullMatrix<double> K = cell_matrix(cell->active_cell_index() + pass, n);
              constraints.distribute_local_to_global(K, local_vector, dofs, expected, rhs);
              if (scatter.is_fast(cell->active_cell_index()))
                scatter.add(cell->active_cell_index(), K);
              else
                constraints.distribute_local_to_global(K, dofs, scattered);
              if (pass == 0 && std::any_of(dofs.begin(), dofs.end(), [&](auto dof) {
                    return constraints.is_constrained(dof);
                  }))
                ++n_constrained_cells;
            }
        scatter.end();
      }
    expected.compress(VectorOperation::add);
    scattered.compress(VectorOperation::add);
    EXPECT_GT(Utilities::MPI::sum(n_constrained_cells, communicator), 0u);

    // Entry by entry over the owned rows (the same pattern in both).
    double       largest = 0, difference = 0;
    unsigned int n_entries = 0;
    for (const auto row : owned)
      {
        auto a = expected.begin(row);
        auto b = scattered.begin(row);
        for (; a != expected.end(row); ++a, ++b)
          {
            ASSERT_NE(b, scattered.end(row));
            ASSERT_EQ(a->column(), b->column());
            largest = std::max(largest, std::abs(a->value()));
            difference = std::max(difference, std::abs(a->value() - b->value()));
            ++n_entries;
          }
        EXPECT_EQ(b, scattered.end(row));
      }
    EXPECT_GT(n_entries, 0u);
    EXPECT_GT(largest, 1.0);
    EXPECT_LE(difference, 1e-14 * largest) << "largest entry " << largest;
  }
} // namespace

TEST(MatrixScatter, MatchesDistributeLocalToGlobalWithHangingNodesAndSupports)
{
  check_scatter_against_constraints(MPI_COMM_SELF);
}

TEST(Mpi, MatrixScatterMatchesDistributeLocalToGlobalOnEveryRank)
{
  check_scatter_against_constraints(MPI_COMM_WORLD);
}
