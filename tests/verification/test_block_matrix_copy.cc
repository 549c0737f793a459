// The block copy of the Newton matrix (linalg/BlockMatrixCopy, PETSc BAIJ with 3 x 3 nodal
// blocks) against the assembled AIJ matrix itself, the oracle: entry by entry over every owned
// row (the copy's entries outside the AIJ pattern must be zero) and in a product with a
// vector, after the first build, after new values, and for another matrix. The mesh has
// hanging nodes and supports, whose rows hold only their diagonal: partial blocks. One rank
// here, two in Mpi.*.
#include "linalg/BlockMatrixCopy.h"

#include "../test_constrained_cube.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace
{
  using namespace dealii;

  // Compares the copy with the source row by row: the same value wherever the source has an
  // entry, zero elsewhere. Returns the largest source entry.
  double expect_same_entries(const Mat source, const Mat copy)
  {
    PetscInt row_begin, row_end;
    EXPECT_EQ(MatGetOwnershipRange(source, &row_begin, &row_end), 0);
    double largest = 0, difference = 0;
    long   n_padding = 0;
    for (PetscInt row = row_begin; row < row_end; ++row)
      {
        std::map<PetscInt, double> expected;
        PetscInt                   n;
        const PetscInt            *columns;
        const PetscScalar         *values;
        MatGetRow(source, row, &n, &columns, &values);
        for (PetscInt k = 0; k < n; ++k)
          expected[columns[k]] = values[k];
        MatRestoreRow(source, row, &n, &columns, &values);
        MatGetRow(copy, row, &n, &columns, &values);
        std::size_t found = 0;
        for (PetscInt k = 0; k < n; ++k)
          {
            const auto it = expected.find(columns[k]);
            if (it == expected.end())
              {
                difference = std::max(difference, std::abs(values[k]));
                ++n_padding;
                continue;
              }
            ++found;
            largest = std::max(largest, std::abs(it->second));
            difference = std::max(difference, std::abs(values[k] - it->second));
          }
        MatRestoreRow(copy, row, &n, &columns, &values);
        EXPECT_EQ(found, expected.size()) << "row " << row;
      }
    EXPECT_EQ(difference, 0.0);
    // The constrained rows (diagonal only) are padded to whole blocks.
    MPI_Comm communicator;
    PetscObjectGetComm(reinterpret_cast<PetscObject>(source), &communicator);
    EXPECT_GT(Utilities::MPI::sum(n_padding, communicator), 0);
    return largest;
  }

  // `copy` may hold the copy of another matrix: it must notice and build anew.
  void check_block_copy(const MPI_Comm communicator, const unsigned int rounds,
                        indentsim::linalg::BlockMatrixCopy &copy)
  {
    const indentsim::test_meshes::ConstrainedCube cube(communicator, rounds);
    const auto                                   &dof_handler = cube.dof_handler;
    const auto                                   &fe = cube.fe;
    const auto                                   &owned = cube.owned;
    const auto                                   &constraints = cube.constraints;
    ASSERT_GT(constraints.n_constraints(), 0u);
    PETScWrappers::MPI::SparseMatrix matrix;
    matrix.reinit(owned, owned, cube.sparsity, communicator);

    const unsigned int                   n = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    const auto                           assemble = [&](const double phase) {
      matrix = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            FullMatrix<double> K(n, n);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                K(i, j) = std::sin(phase + 1.3 * cell->active_cell_index() + 0.7 * i +
                                                             0.37 * j * j + 0.11 * i * j);
            cell->get_dof_indices(dofs);
            constraints.distribute_local_to_global(K, dofs, matrix);
          }
      matrix.compress(VectorOperation::add);
    };

    PETScWrappers::MPI::Vector x(owned, communicator), y_source(owned, communicator),
        y_copy(owned, communicator);
    for (const auto i : owned)
      x(i) = std::cos(0.1 * i);
    x.compress(VectorOperation::insert);

    for (const double phase : {0.0, 0.9}) // the build, then new values in the same pattern
      {
        assemble(phase);
        const Mat source = static_cast<Mat>(matrix);
        const Mat block = copy.update(source);
        ASSERT_NE(block, nullptr);
        MatType type;
        MatGetType(block, &type);
        EXPECT_STREQ(type, MATMPIBAIJ);
        PetscInt block_size = 0;
        MatGetBlockSize(block, &block_size);
        EXPECT_EQ(block_size, 3);
        const double largest = expect_same_entries(source, block);
        EXPECT_GT(largest, 0.5);
        MatMult(source, static_cast<const Vec &>(x), static_cast<const Vec &>(y_source));
        MatMult(block, static_cast<const Vec &>(x), static_cast<const Vec &>(y_copy));
        const double reference = y_source.l2_norm();
        y_copy -= y_source;
        EXPECT_GT(reference, 1.0);
        EXPECT_LE(y_copy.l2_norm(), 1e-13 * reference) << "phase " << phase;
      }
  }
} // namespace

// One copy object for two matrices in turn (the second with another pattern).
TEST(BlockMatrixCopy, MatchesTheAssembledMatrixWithHangingNodesAndSupports)
{
  indentsim::linalg::BlockMatrixCopy copy;
  for (const unsigned int rounds : {1u, 2u})
    check_block_copy(MPI_COMM_SELF, rounds, copy);
}

TEST(Mpi, BlockMatrixCopyMatchesTheAssembledMatrixOnEveryRank)
{
  indentsim::linalg::BlockMatrixCopy copy;
  for (const unsigned int rounds : {1u, 2u})
    check_block_copy(MPI_COMM_WORLD, rounds, copy);
}
