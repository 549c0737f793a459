#include "solver/MatrixScatter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace indentsim::solver
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
  } // namespace

  void MatrixScatter::build(const DoFHandler<3>                           &dof_handler,
                            const AffineConstraints<double>               &constraints,
                            const PETScWrappers::MPI::SparseMatrix        &matrix)
  {
    plan_.assign(dof_handler.get_triangulation().n_active_cells(), CellPlan());
    positions_.clear();
    counts_.clear();
    weights_.clear();
    diagonals_.clear();
    fast_fraction_ = 0;
    n_cell_dofs_ = dof_handler.get_fe().n_dofs_per_cell();

    const Mat global = matrix;
    PetscBool is_mpiaij = PETSC_FALSE;
    check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(global), MATMPIAIJ, &is_mpiaij),
          "PetscObjectTypeCompare");
    if (!is_mpiaij)
      return; // every cell through MatSetValues

    PetscInt row_begin = 0, row_end = 0, column_begin = 0, column_end = 0;
    check(MatGetOwnershipRange(global, &row_begin, &row_end), "MatGetOwnershipRange");
    check(MatGetOwnershipRangeColumn(global, &column_begin, &column_end),
          "MatGetOwnershipRangeColumn");
    Mat             diagonal = nullptr, off_diagonal = nullptr;
    const PetscInt *off_diagonal_columns = nullptr; // compressed column -> global, ascending
    check(MatMPIAIJGetSeqAIJ(global, &diagonal, &off_diagonal, &off_diagonal_columns),
          "MatMPIAIJGetSeqAIJ");
    Csr       d, o;
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
      throw std::runtime_error("MatrixScatter: no row structure of the off-diagonal block");
    PetscInt n_off_diagonal_columns = 0;
    if (off_diagonal_columns)
      check(MatGetSize(off_diagonal, nullptr, &n_off_diagonal_columns), "MatGetSize");
    const long n_diagonal = d.row_start[d.n_rows];
    const long n_off = o.row_start[o.n_rows];
    if (n_diagonal + n_off >= static_cast<long>(std::numeric_limits<std::uint32_t>::max()))
      throw std::runtime_error("MatrixScatter: more than 2^32 nonzeros on one rank");
    n_diagonal_ = static_cast<std::uint32_t>(n_diagonal);

    // Position of global entry (row, column), or -1 if this rank does not hold it.
    const auto find = [&](const PetscInt row, const PetscInt column) -> long {
      if (row < row_begin || row >= row_end)
        return -1;
      if (column >= column_begin && column < column_end)
        return d.find(row - row_begin, column - column_begin);
      const PetscInt *end = off_diagonal_columns + n_off_diagonal_columns;
      const PetscInt *it = std::lower_bound(off_diagonal_columns, end, column);
      if (it == end || *it != column)
        return -1;
      const long position =
        o.find(row - row_begin, static_cast<PetscInt>(it - off_diagonal_columns));
      return position >= 0 ? position + n_diagonal : -1;
    };

    using Targets = std::vector<std::pair<types::global_dof_index, double>>;
    const unsigned int                   n = n_cell_dofs_;
    std::vector<types::global_dof_index> dofs(n);
    std::vector<Targets>                 targets(n);
    std::vector<std::uint32_t>           cell_positions;
    std::vector<std::pair<unsigned int, std::uint32_t>> cell_diagonals;
    unsigned long                        n_owned = 0, n_fast = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        ++n_owned;
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
        bool representable = true;
        cell_positions.clear();
        cell_diagonals.clear();
        for (unsigned int i = 0; i < n && representable; ++i)
          {
            representable = targets[i].size() <= std::numeric_limits<std::uint8_t>::max();
            for (const auto &[row, row_weight] : targets[i])
              for (unsigned int j = 0; j < n && representable; ++j)
                for (const auto &[column, column_weight] : targets[j])
                  {
                    const long position =
                      find(static_cast<PetscInt>(row), static_cast<PetscInt>(column));
                    representable = representable && position >= 0;
                    cell_positions.push_back(static_cast<std::uint32_t>(position));
                  }
            if (constraints.is_constrained(dofs[i]))
              {
                const long position =
                  find(static_cast<PetscInt>(dofs[i]), static_cast<PetscInt>(dofs[i]));
                representable = representable && position >= 0;
                cell_diagonals.emplace_back(i, static_cast<std::uint32_t>(position));
              }
          }
        if (!representable)
          continue; // rows of another rank: MatSetValues
        CellPlan &plan = plan_[cell->active_cell_index()];
        plan.positions = static_cast<long>(positions_.size());
        positions_.insert(positions_.end(), cell_positions.begin(), cell_positions.end());
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
            plan.n_diagonals = static_cast<unsigned int>(cell_diagonals.size());
            diagonals_.insert(diagonals_.end(), cell_diagonals.begin(), cell_diagonals.end());
          }
        ++n_fast;
      }
    check(MatRestoreRowIJ(diagonal, 0, PETSC_FALSE, PETSC_FALSE, &d.n_rows, &d.row_start,
                          &d.columns, &done),
          "MatRestoreRowIJ (diagonal block)");
    check(MatRestoreRowIJ(off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &o.n_rows, &o.row_start,
                          &o.columns, &done),
          "MatRestoreRowIJ (off-diagonal block)");
    positions_.shrink_to_fit();
    counts_.shrink_to_fit();
    weights_.shrink_to_fit();
    diagonals_.shrink_to_fit();
    fast_fraction_ = n_owned > 0 ? double(n_fast) / double(n_owned) : 0.0;
  }

  void MatrixScatter::begin(PETScWrappers::MPI::SparseMatrix &matrix)
  {
    if (positions_.empty())
      return;
    check(MatMPIAIJGetSeqAIJ(matrix.petsc_matrix(), &diagonal_block_, &off_diagonal_block_, nullptr),
          "MatMPIAIJGetSeqAIJ");
    check(MatSeqAIJGetArray(diagonal_block_, &diagonal_values_), "MatSeqAIJGetArray");
    check(MatSeqAIJGetArray(off_diagonal_block_, &off_diagonal_values_), "MatSeqAIJGetArray");
  }

  void MatrixScatter::add(const unsigned int active_cell_index, const FullMatrix<double> &cell_matrix)
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
    const std::uint8_t *count = counts_.data() + plan.targets;
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
    if (diagonal_values_)
      check(MatSeqAIJRestoreArray(diagonal_block_, &diagonal_values_), "MatSeqAIJRestoreArray");
    if (off_diagonal_values_)
      check(MatSeqAIJRestoreArray(off_diagonal_block_, &off_diagonal_values_),
            "MatSeqAIJRestoreArray");
    diagonal_values_ = off_diagonal_values_ = nullptr;
    diagonal_block_ = off_diagonal_block_ = nullptr;
  }
} // namespace indentsim::solver
