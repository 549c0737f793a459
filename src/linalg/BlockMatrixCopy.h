// A copy of the Newton matrix in PETSc's block format (MPIBAIJ, 3 x 3 nodal blocks) for the
// Krylov method and the multigrid smoothers, whose time is spent in matrix-vector products.
// Units follow the matrix (mN/um).
//
// Why: the assembly writes an MPIAIJ matrix (MatrixScatter, deal.II's constraints, the contact
// terms), and ML builds its hierarchy from it; but a product with the block format reads one
// column index per 3 x 3 block instead of one per entry (or per row group), with a 3 x 3 kernel:
// the same iterations and residuals in less time (docs/performance.md).
//
// The copy's layout is found once per sparsity pattern: the BAIJ matrix is preallocated from
// the AIJ pattern, every AIJ entry is inserted with its own position number as its value, and
// the numbers read back from the BAIJ arrays are the map. Refreshing the values is then one
// gather per entry. Entries of a block that the AIJ pattern lacks stay zero.
//
// Needs the unknowns of each node numbered together (3 consecutive rows, starting at a
// multiple of 3) on every rank; LinearSolver checks that before it uses this class.
#pragma once

#include <petscmat.h>

#include <cstdint>
#include <vector>

namespace indentsim::linalg
{
  class BlockMatrixCopy
  {
  public:
    BlockMatrixCopy() = default;
    ~BlockMatrixCopy();
    BlockMatrixCopy(const BlockMatrixCopy &) = delete;
    BlockMatrixCopy &operator=(const BlockMatrixCopy &) = delete;

    // The block copy of `source` (MPIAIJ, block size 3) with its current values: built on the
    // first call and whenever the source's matrix object or its nonzero pattern changed;
    // otherwise only the values are copied. Collective.
    Mat update(Mat source);

    void clear();

  private:
    void build(Mat source);

    PetscObjectId    source_id_ = 0; // the source the map belongs to (0: none)
    Mat              copy_ = nullptr;
    PetscObjectState source_nonzero_state_ = 0;
    // For each value of the copy's diagonal / off-diagonal local block (in its storage order):
    // >= 0 the position in the source's diagonal block values, <= -2 the position -2 - k in
    // its off-diagonal block values, -1 an entry outside the source's pattern (zero).
    std::vector<std::int32_t> diagonal_map_, off_diagonal_map_;
  };
} // namespace indentsim::linalg
