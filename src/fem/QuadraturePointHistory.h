// The material states of the quadrature points (materials/MaterialModel.h): the converged
// state of the last accepted increment and the current one of the Newton iteration, each a flat
// array [active_cell_index][q][variable]. Shared by the indentation and tensile problems.
#pragma once

#include <deal.II/dofs/dof_handler.h>

#include <cstddef>
#include <span>
#include <vector>

namespace indentsim::fem
{
  class QuadraturePointHistory
  {
  public:
    // `n_state` variables at each of `n_q_points` points of `n_cells` cells, all zero.
    void reinit(std::size_t n_cells, unsigned int n_q_points, unsigned int n_state)
    {
      n_q_points_ = n_q_points;
      n_state_ = n_state;
      converged_.assign(n_cells * n_q_points * n_state, 0.0);
      current_ = converged_;
    }

    unsigned int n_q_points() const { return n_q_points_; }
    unsigned int n_state() const { return n_state_; }
    std::size_t  n_points() const { return n_state_ > 0 ? converged_.size() / n_state_ : 0; }

    // One point's converged state, by its number over all cells (initialisation).
    std::span<double> converged_point(const std::size_t point)
    {
      return std::span<double>(converged_).subspan(point * n_state_, n_state_);
    }
    // A cell's converged and current states, [q][variable].
    template <class CellIterator>
    std::span<const double> converged(const CellIterator &cell) const
    {
      return std::span<const double>(converged_).subspan(offset(cell), cell_length());
    }
    template <class CellIterator>
    std::span<double> converged(const CellIterator &cell)
    {
      return std::span<double>(converged_).subspan(offset(cell), cell_length());
    }
    template <class CellIterator>
    std::span<double> current(const CellIterator &cell)
    {
      return std::span<double>(current_).subspan(offset(cell), cell_length());
    }
    std::size_t cell_length() const { return std::size_t(n_q_points_) * n_state_; }

    // The current states become the converged ones (the current array keeps a copy: the
    // material updates read it as the hint of the next iteration).
    void accept()
    {
      converged_.swap(current_);
      current_ = converged_;
    }
    // Back to the converged states.
    void reject() { current_ = converged_; }
    // After the converged states were set from outside (initial orientation, checkpoint).
    void converged_changed() { current_ = converged_; }

    // The whole converged array (checkpoints).
    const std::vector<double> &converged_values() const { return converged_; }
    std::vector<double>       &converged_values() { return converged_; }

  private:
    template <class CellIterator>
    std::size_t offset(const CellIterator &cell) const
    {
      return cell->active_cell_index() * cell_length();
    }

    unsigned int        n_q_points_ = 8, n_state_ = 0;
    std::vector<double> converged_, current_;
  };
} // namespace indentsim::fem
