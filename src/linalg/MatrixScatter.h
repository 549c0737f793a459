// Adds cell matrices to the global PETSc matrix through precomputed positions in its CSR
// arrays, instead of MatSetValues. Units of the matrix (mN/um for the indentation tangent).
//
// Why: the copier of the threaded cell loop (CellWorkspace.h) runs on one thread at a time,
// and MatSetValues searches every one of a cell's 576 entries in its row: as much CPU time as
// the element kernels, and being serial it bounds the assembly. With the positions found once per sparsity pattern, a cell costs 576 indexed
// additions.
//
// Entries in rows of other ranks (cells at the boundaries between ranks' cells) are added into
// a send buffer instead, at slots found once per pattern, and end() sends each neighbouring rank
// its slots' values in one message; the owner adds them at positions it found once, which
// avoids the sorting of PETSc's stash in MatAssemblyBegin. A cell whose owned entries are missing from the pattern would still take that
// slow path (none does with deal.II's sparsity patterns). Constraints are resolved as that function does: a constrained DoF's row and
// column are distributed to its masters with their weights (hanging nodes) or dropped
// (supports), and the constrained row gets |K_ii| on its diagonal (the mean |K_jj| of the cell
// if K_ii = 0). Cells without constrained DoFs make their additions in the same order as
// MatSetValues, bitwise the same matrix; the others differ by the order of summation (tested
// against distribute_local_to_global).
//
// Use: build once after the matrix is created (positions for this rank's owned cells;
// collective), then per assembly: begin() after zeroing the matrix, add() per cell from the
// copier, end() before anything else touches the matrix (compress). begin() and end() are
// collective over the matrix's communicator (end() exchanges the interface entries).
#pragma once

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_sparse_matrix.h>

#include <mpi.h>
#include <petscmat.h>

#include <cstdint>
#include <vector>

namespace indentsim::linalg
{
  class MatrixPattern; // where this rank finds a global entry (MatrixScatter.cc)

  class MatrixScatter
  {
  public:
    MatrixScatter() = default;
    MatrixScatter(const MatrixScatter &) = delete;
    MatrixScatter &operator=(const MatrixScatter &) = delete;
    ~MatrixScatter();
    // Positions for the locally owned cells of `dof_handler` in `matrix` (assembled at least
    // once, with its final sparsity pattern; PETSc MPIAIJ), and the exchange plan of the
    // entries in other ranks' rows. Collective over the matrix's communicator; throws
    // std::runtime_error on every rank if a rank's pattern lacks an entry another one sends.
    template <int dim>
    void build(const dealii::DoFHandler<dim>                  &dof_handler,
               const dealii::AffineConstraints<double>        &constraints,
               const dealii::PETScWrappers::MPI::SparseMatrix &matrix);

    // True if `cell` (active cell index) takes the fast path.
    bool is_fast(unsigned int active_cell_index) const
    {
      return active_cell_index < plan_.size() && plan_[active_cell_index].positions >= 0;
    }
    // Fraction of this rank's owned cells on the fast path (diagnostics).
    double fast_fraction() const { return fast_fraction_; }

    // Opens the CSR value arrays of `matrix` (the one passed to build). Between begin() and
    // end(), other cells may still be added with MatSetValues (it writes the same arrays).
    void begin(dealii::PETScWrappers::MPI::SparseMatrix &matrix);
    // Adds the cell matrix of a fast cell (is_fast(active_cell_index)), dofs in cell order.
    void add(unsigned int active_cell_index, const dealii::FullMatrix<double> &cell_matrix);
    void end();

  private:
    // Where a fast cell's entries go. Positions are diagonal-block positions, or n_diagonal_ +
    // off-diagonal-block positions.
    struct CellPlan
    {
      long positions = -1; // first of the cell's positions in positions_; -1: slow path
      long targets = -1;   // first of its n_cell_dofs_ target counts and their weights in
                           // counts_ / weights_; -1: no constrained DoF (one target each)
      long         weights = -1;
      long         diagonals = -1; // first (local DoF, position) of its constrained rows' diagonals
      unsigned int n_diagonals = 0;
    };
    double &value(std::uint32_t position)
    {
      return position < n_diagonal_ ? diagonal_values_[position]
             : position < n_local_  ? off_diagonal_values_[position - n_diagonal_]
                                    : send_values_[position - n_local_];
    }
    void release_communicator();

    // The steps of build(): empties the plan; plans one owned cell (false: it takes the slow
    // path); groups the send slots by destination rank (returns the (row, column) of each slot
    // in the new order); learns from the other ranks what they send and where it goes.
    struct CellScratch;
    void reset(unsigned int n_active_cells, unsigned int n_cell_dofs);
    template <class CellIterator>
    bool plan_cell(const CellIterator &cell, const dealii::AffineConstraints<double> &constraints,
                   MatrixPattern &pattern, CellScratch &scratch);
    std::vector<PetscInt> group_send_slots(const MatrixPattern &pattern);
    void plan_receives(MatrixPattern &pattern, const std::vector<PetscInt> &send_entries);
    // Sends slots [send_offsets_[k], send_offsets_[k + 1]) of `send` (width values of `type`
    // per slot) to send_ranks_[k] and receives likewise into `receive`.
    void exchange(const void *send, void *receive, int width, MPI_Datatype type) const;
    static constexpr int exchange_tag = 4711;

    std::vector<CellPlan>      plan_;      // per active cell
    std::vector<std::uint32_t> positions_; // unconstrained cell: n x n; constrained cell: for
                                           // each row target of each DoF, each column target
    std::vector<std::uint8_t> counts_;     // targets per DoF of constrained cells (0: support)
    std::vector<double>       weights_;    // the targets' weights
    std::vector<std::pair<unsigned int, std::uint32_t>> diagonals_;
    std::uint32_t n_diagonal_ = 0; // nonzeros of the diagonal block
    std::uint32_t n_local_ = 0;    // of both blocks; positions from here are send slots

    // Interface entries: slots [send_offsets_[k], send_offsets_[k + 1]) go to send_ranks_[k];
    // values from receive_ranks_[k] arrive in receive_values_ and are added at
    // receive_positions_ (positions in this rank's blocks).
    MPI_Comm                   communicator_ = MPI_COMM_NULL; // a duplicate, own tag space
    bool                       open_ = false;                 // between begin() and end()
    std::vector<int>           send_ranks_, receive_ranks_;
    std::vector<std::size_t>   send_offsets_, receive_offsets_;
    std::vector<double>        send_values_, receive_values_;
    std::vector<std::uint32_t> receive_positions_;
    unsigned int               n_cell_dofs_ = 0;
    double                     fast_fraction_ = 0;

    Mat          diagonal_block_ = nullptr, off_diagonal_block_ = nullptr;
    PetscScalar *diagonal_values_ = nullptr, *off_diagonal_values_ = nullptr;
  };
} // namespace indentsim::linalg
