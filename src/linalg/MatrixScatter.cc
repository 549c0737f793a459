#include "linalg/MatrixScatter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace indentsim::linalg
{
  using namespace dealii;

  namespace
  {
    void check(const PetscErrorCode code, const char *what)
    {
      if (code != 0)
        throw std::runtime_error(std::string("MatrixScatter: PETSc call failed: ") + what +
                                 " (error " + std::to_string(code) + ")");
    }

    // Compressed sparse rows of a sequential AIJ block (its arrays, not copies).
    struct Csr
    {
      PetscInt        n_rows = 0;
      const PetscInt *row_start = nullptr, *columns = nullptr;
      // Position of `column` in row `row`, or -1 if the pattern does not hold it.
      long find(const PetscInt row, const PetscInt column) const
      {
        const PetscInt *begin = columns + row_start[row], *end = columns + row_start[row + 1];
        const PetscInt *it = std::lower_bound(begin, end, column);
        return (it != end && *it == column) ? static_cast<long>(it - columns) : -1;
      }
    };

    bool is_mpiaij(const Mat matrix)
    {
      PetscBool result = PETSC_FALSE;
      check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(matrix), MATMPIAIJ, &result),
            "PetscObjectTypeCompare");
      return result;
    }
  } // namespace

  // Where a global entry (row, column) of an MPIAIJ matrix lives for this rank: in its diagonal
  // or off-diagonal CSR block (by bisection in the row), or, in a row of another rank, in a send
  // slot numbered in the order first asked for. Holds the blocks' row structure open while it
  // lives.
  class MatrixPattern
  {
  public:
    explicit MatrixPattern(const Mat global)
    {
      check(MatGetOwnershipRange(global, &row_begin, &row_end), "MatGetOwnershipRange");
      check(MatGetOwnershipRangeColumn(global, &column_begin, &column_end),
            "MatGetOwnershipRangeColumn");
      check(MatMPIAIJGetSeqAIJ(global, &diagonal, &off_diagonal, &off_diagonal_columns),
            "MatMPIAIJGetSeqAIJ");
      PetscBool done = PETSC_FALSE;
      check(MatGetRowIJ(diagonal, 0, PETSC_FALSE, PETSC_FALSE, &d.n_rows, &d.row_start, &d.columns,
                        &done),
            "MatGetRowIJ (diagonal block)");
      if (!done)
        throw std::runtime_error("MatrixScatter: no row structure of the diagonal block");
      check(MatGetRowIJ(off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &o.n_rows, &o.row_start,
                        &o.columns, &done),
            "MatGetRowIJ (off-diagonal block)");
      if (!done)
        {
          restore(diagonal, d);
          throw std::runtime_error("MatrixScatter: no row structure of the off-diagonal block");
        }
      if (off_diagonal_columns)
        check(MatGetSize(off_diagonal, nullptr, &n_off_diagonal_columns), "MatGetSize");
      n_diagonal = d.row_start[d.n_rows];
      n_local = static_cast<std::uint64_t>(n_diagonal) + o.row_start[o.n_rows];

      check(PetscObjectGetComm(reinterpret_cast<PetscObject>(global), &communicator),
            "PetscObjectGetComm");
      MPI_Comm_size(communicator, &n_ranks);
      MPI_Comm_rank(communicator, &this_rank);
      check(MatGetOwnershipRanges(global, &row_ranges), "MatGetOwnershipRanges");
    }

    ~MatrixPattern()
    {
      restore(diagonal, d);
      restore(off_diagonal, o);
    }

    // The position of entry (row, column) in this rank's arrays (diagonal block first), -1 if
    // they do not hold it, or n_local + the send slot of another rank's row.
    long find(const PetscInt row, const PetscInt column)
    {
      if (row < row_begin || row >= row_end)
        return slot(row, column);
      if (column >= column_begin && column < column_end)
        return d.find(row - row_begin, column - column_begin);
      const PetscInt *end = off_diagonal_columns + n_off_diagonal_columns;
      const PetscInt *it = std::lower_bound(off_diagonal_columns, end, column);
      if (it == end || *it != column)
        return -1;
      const long position =
          o.find(row - row_begin, static_cast<PetscInt>(it - off_diagonal_columns));
      return position >= 0 ? position + n_diagonal : -1;
    }

    long          n_diagonal = 0; // nonzeros of the diagonal block
    std::uint64_t n_local = 0;    // of both blocks
    MPI_Comm      communicator = MPI_COMM_SELF;
    int           n_ranks = 1, this_rank = 0;
    // Per send slot: the rank owning its row, and the entry (row, column).
    std::vector<int>                           slot_owner;
    std::vector<std::pair<PetscInt, PetscInt>> slot_entry;

  private:
    long slot(const PetscInt row, const PetscInt column)
    {
      const auto [it, inserted] =
          slot_of_entry.try_emplace({row, column}, static_cast<std::uint32_t>(slot_entry.size()));
      if (inserted)
        {
          slot_owner.push_back(static_cast<int>(
              std::upper_bound(row_ranges, row_ranges + n_ranks + 1, row) - row_ranges - 1));
          slot_entry.emplace_back(row, column);
        }
      return static_cast<long>(n_local + it->second);
    }

    static void restore(const Mat block, Csr &csr)
    {
      PetscBool done = PETSC_FALSE;
      if (csr.row_start)
        MatRestoreRowIJ(block, 0, PETSC_FALSE, PETSC_FALSE, &csr.n_rows, &csr.row_start,
                        &csr.columns, &done);
      csr.row_start = nullptr;
    }

    PetscInt        row_begin = 0, row_end = 0, column_begin = 0, column_end = 0;
    Mat             diagonal = nullptr, off_diagonal = nullptr;
    const PetscInt *off_diagonal_columns = nullptr; // compressed column -> global, ascending
    PetscInt        n_off_diagonal_columns = 0;
    Csr             d, o;
    const PetscInt *row_ranges = nullptr; // n_ranks + 1 starts of the ranks' rows
    std::map<std::pair<PetscInt, PetscInt>, std::uint32_t> slot_of_entry;
  };

  // A cell's DoFs and, per DoF, the global DoFs its row and column go to with their weights
  // (itself with weight 1, its masters, or none for a support), reused from cell to cell.
  struct MatrixScatter::CellScratch
  {
    using Targets = std::vector<std::pair<types::global_dof_index, double>>;
    explicit CellScratch(const unsigned int n)
      : dofs(n)
      , targets(n)
    {
    }
    std::vector<types::global_dof_index>                dofs;
    std::vector<Targets>                                targets;
    std::vector<std::uint32_t>                          positions;
    std::vector<std::pair<unsigned int, std::uint32_t>> diagonals;
  };

  template <int dim>
  void MatrixScatter::build(const DoFHandler<dim>                  &dof_handler,
                            const AffineConstraints<double>        &constraints,
                            const PETScWrappers::MPI::SparseMatrix &matrix)
  {
    reset(dof_handler.get_triangulation().n_active_cells(), dof_handler.get_fe().n_dofs_per_cell());
    const Mat global = matrix;
    if (!is_mpiaij(global))
      return; // every cell through MatSetValues

    MatrixPattern pattern(global);
    // Positions and send slots share the uint32 range; the slots are at most a rank's
    // interface entries, far fewer than its nonzeros.
    if (2 * pattern.n_local >= std::numeric_limits<std::uint32_t>::max())
      throw std::runtime_error("MatrixScatter: more than 2^31 nonzeros on one rank");
    n_diagonal_ = static_cast<std::uint32_t>(pattern.n_diagonal);
    n_local_ = static_cast<std::uint32_t>(pattern.n_local);

    CellScratch   scratch(n_cell_dofs_);
    unsigned long n_owned = 0, n_fast = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          ++n_owned;
          n_fast += plan_cell(cell, constraints, pattern, scratch);
        }
    if (pattern.slot_entry.size() >= std::numeric_limits<std::uint32_t>::max() - n_local_)
      throw std::runtime_error("MatrixScatter: too many entries of other ranks' rows");

    const std::vector<PetscInt> send_entries = group_send_slots(pattern);
    plan_receives(pattern, send_entries);

    positions_.shrink_to_fit();
    counts_.shrink_to_fit();
    weights_.shrink_to_fit();
    diagonals_.shrink_to_fit();
    fast_fraction_ = n_owned > 0 ? double(n_fast) / double(n_owned) : 0.0;
  }

  void MatrixScatter::reset(const unsigned int n_active_cells, const unsigned int n_cell_dofs)
  {
    release_communicator();
    plan_.assign(n_active_cells, CellPlan());
    positions_.clear();
    counts_.clear();
    weights_.clear();
    diagonals_.clear();
    send_ranks_.clear();
    send_offsets_.clear();
    send_values_.clear();
    receive_ranks_.clear();
    receive_offsets_.clear();
    receive_positions_.clear();
    receive_values_.clear();
    fast_fraction_ = 0;
    n_cell_dofs_ = n_cell_dofs;
  }

  template <class CellIterator>
  bool MatrixScatter::plan_cell(const CellIterator              &cell,
                                const AffineConstraints<double> &constraints,
                                MatrixPattern &pattern, CellScratch &scratch)
  {
    const unsigned int n = n_cell_dofs_;
    auto              &dofs = scratch.dofs;
    auto              &targets = scratch.targets;
    cell->get_dof_indices(dofs);
    bool constrained = false;
    for (unsigned int i = 0; i < n; ++i)
      {
        targets[i].clear();
        if (const auto *entries = constraints.get_constraint_entries(dofs[i]))
          {
            targets[i] = *entries; // masters and weights; none for a support
            constrained = true;
          }
        else if (constraints.is_constrained(dofs[i]))
          constrained = true; // constrained without masters
        else
          targets[i].emplace_back(dofs[i], 1.0);
      }

    // Every (row target, column target) pair of every entry, in the order add() visits them.
    bool representable = true;
    scratch.positions.clear();
    scratch.diagonals.clear();
    for (unsigned int i = 0; i < n && representable; ++i)
      {
        representable = targets[i].size() <= std::numeric_limits<std::uint8_t>::max();
        for (const auto &[row, row_weight] : targets[i])
          for (unsigned int j = 0; j < n && representable; ++j)
            for (const auto &[column, column_weight] : targets[j])
              {
                const long position =
                    pattern.find(static_cast<PetscInt>(row), static_cast<PetscInt>(column));
                representable = representable && position >= 0;
                scratch.positions.push_back(static_cast<std::uint32_t>(position));
              }
        if (constraints.is_constrained(dofs[i]))
          {
            const long position =
                pattern.find(static_cast<PetscInt>(dofs[i]), static_cast<PetscInt>(dofs[i]));
            representable = representable && position >= 0;
            scratch.diagonals.emplace_back(i, static_cast<std::uint32_t>(position));
          }
      }
    if (!representable)
      return false; // rows of another rank: MatSetValues

    CellPlan &plan = plan_[cell->active_cell_index()];
    plan.positions = static_cast<long>(positions_.size());
    positions_.insert(positions_.end(), scratch.positions.begin(), scratch.positions.end());
    if (constrained)
      {
        plan.targets = static_cast<long>(counts_.size());
        plan.weights = static_cast<long>(weights_.size());
        for (unsigned int i = 0; i < n; ++i)
          {
            counts_.push_back(static_cast<std::uint8_t>(targets[i].size()));
            for (const auto &target : targets[i])
              weights_.push_back(target.second);
          }
        plan.diagonals = static_cast<long>(diagonals_.size());
        plan.n_diagonals = static_cast<unsigned int>(scratch.diagonals.size());
        diagonals_.insert(diagonals_.end(), scratch.diagonals.begin(), scratch.diagonals.end());
      }
    return true;
  }

  std::vector<PetscInt> MatrixScatter::group_send_slots(const MatrixPattern &pattern)
  {
    // The slots were numbered in the order first met; renumber them grouped by destination
    // rank, each group keeping that order, so that each rank's values are one message.
    const int                  n_ranks = pattern.n_ranks;
    const auto                &slot_entry = pattern.slot_entry;
    std::vector<std::uint32_t> new_slot(slot_entry.size());
    std::vector<std::uint32_t> count(n_ranks, 0);
    for (const int owner : pattern.slot_owner)
      ++count[owner];
    std::vector<std::uint32_t> start(n_ranks + 1, 0);
    for (int q = 0; q < n_ranks; ++q)
      start[q + 1] = start[q] + count[q];
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < slot_entry.size(); ++k)
      new_slot[k] = next[pattern.slot_owner[k]]++;
    for (auto &position : positions_)
      if (position >= n_local_)
        position = n_local_ + new_slot[position - n_local_];
    for (auto &diagonal_entry : diagonals_)
      if (diagonal_entry.second >= n_local_)
        diagonal_entry.second = n_local_ + new_slot[diagonal_entry.second - n_local_];
    for (int q = 0; q < n_ranks; ++q)
      if (count[q] > 0)
        {
          send_ranks_.push_back(q);
          send_offsets_.push_back(start[q]);
        }
    send_offsets_.push_back(start[n_ranks]);
    send_values_.assign(slot_entry.size(), 0.0);

    std::vector<PetscInt> send_entries(2 * slot_entry.size());
    for (std::size_t k = 0; k < slot_entry.size(); ++k)
      {
        send_entries[2 * new_slot[k]] = slot_entry[k].first;
        send_entries[2 * new_slot[k] + 1] = slot_entry[k].second;
      }
    return send_entries;
  }

  void MatrixScatter::plan_receives(MatrixPattern               &pattern,
                                    const std::vector<PetscInt> &send_entries)
  {
    // Each rank learns which entries of its rows the others will send, and where they go.
    const int n_ranks = pattern.n_ranks;
    MPI_Comm_dup(pattern.communicator, &communicator_);
    std::vector<int> send_counts(n_ranks, 0), receive_counts(n_ranks, 0);
    for (std::size_t k = 0; k < send_ranks_.size(); ++k)
      send_counts[send_ranks_[k]] = static_cast<int>(send_offsets_[k + 1] - send_offsets_[k]);
    MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, communicator_);
    receive_offsets_.assign(1, 0);
    for (int q = 0; q < n_ranks; ++q)
      if (receive_counts[q] > 0)
        {
          receive_ranks_.push_back(q);
          receive_offsets_.push_back(receive_offsets_.back() + receive_counts[q]);
        }
    std::vector<PetscInt> receive_entries(2 * receive_offsets_.back());
    exchange(send_entries.data(), receive_entries.data(), 2, MPIU_INT);
    receive_positions_.resize(receive_offsets_.back());
    receive_values_.assign(receive_offsets_.back(), 0.0);
    std::pair<PetscInt, PetscInt> missing{-1, -1};
    for (std::size_t k = 0; k < receive_positions_.size(); ++k)
      {
        const long position = pattern.find(receive_entries[2 * k], receive_entries[2 * k + 1]);
        if (position < 0 || position >= static_cast<long>(n_local_))
          missing = {receive_entries[2 * k], receive_entries[2 * k + 1]};
        receive_positions_[k] = static_cast<std::uint32_t>(std::max(position, 0l));
      }
    int all_found = missing.first < 0 ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &all_found, 1, MPI_INT, MPI_MIN, communicator_);
    if (!all_found)
      throw std::runtime_error(
          "MatrixScatter: another rank adds to entries that are not in the sparsity pattern" +
          (missing.first >= 0 ? " (row " + std::to_string(missing.first) + ", column " +
                                    std::to_string(missing.second) + " on rank " +
                                    std::to_string(pattern.this_rank) + ")"
                              : std::string()));
  }

  MatrixScatter::~MatrixScatter()
  {
    release_communicator();
  }

  void MatrixScatter::release_communicator()
  {
    if (communicator_ != MPI_COMM_NULL)
      {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (!finalized)
          MPI_Comm_free(&communicator_);
        communicator_ = MPI_COMM_NULL;
      }
  }

  void MatrixScatter::exchange(const void *send, void *receive, const int width,
                               const MPI_Datatype type) const
  {
    int type_size = 0;
    MPI_Type_size(type, &type_size);
    std::vector<MPI_Request> requests(receive_ranks_.size() + send_ranks_.size());
    for (std::size_t k = 0; k < receive_ranks_.size(); ++k)
      MPI_Irecv(static_cast<char *>(receive) + std::size_t(width) * type_size * receive_offsets_[k],
                static_cast<int>(width * (receive_offsets_[k + 1] - receive_offsets_[k])), type,
                receive_ranks_[k], exchange_tag, communicator_, &requests[k]);
    for (std::size_t k = 0; k < send_ranks_.size(); ++k)
      MPI_Isend(static_cast<const char *>(send) + std::size_t(width) * type_size * send_offsets_[k],
                static_cast<int>(width * (send_offsets_[k + 1] - send_offsets_[k])), type,
                send_ranks_[k], exchange_tag, communicator_, &requests[receive_ranks_.size() + k]);
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  }

  void MatrixScatter::begin(PETScWrappers::MPI::SparseMatrix &matrix)
  {
    std::fill(send_values_.begin(), send_values_.end(), 0.0);
    if (communicator_ == MPI_COMM_NULL)
      return; // not built for an MPIAIJ matrix
    check(
        MatMPIAIJGetSeqAIJ(matrix.petsc_matrix(), &diagonal_block_, &off_diagonal_block_, nullptr),
        "MatMPIAIJGetSeqAIJ");
    check(MatSeqAIJGetArray(diagonal_block_, &diagonal_values_), "MatSeqAIJGetArray");
    check(MatSeqAIJGetArray(off_diagonal_block_, &off_diagonal_values_), "MatSeqAIJGetArray");
    open_ = true;
  }

  void MatrixScatter::add(const unsigned int        active_cell_index,
                          const FullMatrix<double> &cell_matrix)
  {
    const CellPlan      &plan = plan_[active_cell_index];
    const std::uint32_t *position = positions_.data() + plan.positions;
    const unsigned int   n = n_cell_dofs_;
    if (plan.targets < 0)
      {
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j, ++position)
            value(*position) += cell_matrix(i, j);
        return;
      }
    // Constrained DoFs: entry (i, j) goes to every (row target of i, column target of j) with
    // the product of their weights.
    const std::uint8_t            *count = counts_.data() + plan.targets;
    std::array<const double *, 64> weights{};
    AssertThrow(n <= weights.size(), dealii::ExcInternalError());
    const double *w = weights_.data() + plan.weights;
    for (unsigned int i = 0; i < n; ++i)
      {
        weights[i] = w;
        w += count[i];
      }
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int m = 0; m < count[i]; ++m)
        {
          const double row_weight = weights[i][m];
          for (unsigned int j = 0; j < n; ++j)
            {
              const double entry = row_weight * cell_matrix(i, j);
              for (unsigned int k = 0; k < count[j]; ++k, ++position)
                value(*position) += entry * weights[j][k];
            }
        }
    if (plan.n_diagonals == 0)
      return;
    // The constrained rows' diagonals, as AffineConstraints::distribute_local_to_global sets
    // them: |K_ii|, or the cell's mean |K_jj| (its l1 norm / n, or 1) if K_ii = 0.
    double mean_diagonal = 0;
    for (unsigned int i = 0; i < n; ++i)
      mean_diagonal += std::abs(cell_matrix(i, i));
    mean_diagonal /= n;
    if (mean_diagonal == 0)
      {
        mean_diagonal = cell_matrix.l1_norm() / n;
        if (mean_diagonal == 0)
          mean_diagonal = 1;
      }
    for (unsigned int k = 0; k < plan.n_diagonals; ++k)
      {
        const auto [i, p] = diagonals_[plan.diagonals + k];
        const double diagonal = std::abs(cell_matrix(i, i));
        value(p) += diagonal != 0 ? diagonal : mean_diagonal;
      }
  }

  void MatrixScatter::end()
  {
    if (open_)
      {
        // The other ranks' rows: one message per neighbouring rank each way, added where the
        // build found the entries.
        exchange(send_values_.data(), receive_values_.data(), 1, MPI_DOUBLE);
        for (std::size_t k = 0; k < receive_positions_.size(); ++k)
          value(receive_positions_[k]) += receive_values_[k];
        open_ = false;
      }
    if (diagonal_values_)
      check(MatSeqAIJRestoreArray(diagonal_block_, &diagonal_values_), "MatSeqAIJRestoreArray");
    if (off_diagonal_values_)
      check(MatSeqAIJRestoreArray(off_diagonal_block_, &off_diagonal_values_),
            "MatSeqAIJRestoreArray");
    diagonal_values_ = off_diagonal_values_ = nullptr;
    diagonal_block_ = off_diagonal_block_ = nullptr;
  }

  template void MatrixScatter::build(const DoFHandler<2> &, const AffineConstraints<double> &,
                                     const PETScWrappers::MPI::SparseMatrix &);
  template void MatrixScatter::build(const DoFHandler<3> &, const AffineConstraints<double> &,
                                     const PETScWrappers::MPI::SparseMatrix &);
} // namespace indentsim::linalg
