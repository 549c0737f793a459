// The inputs of the element kernel (FiniteStrainElement.h) on one hexahedron: the gradients of
// the trilinear shape functions at the 2x2x2 Gauss points and at the centre, the weights and
// the element's displacement values. The gradients are computed here from the vertices (the
// trilinear map, as MappingQ1) rather than by FEValues, whose reuse of the previous cell's
// Jacobian for translated cells would make the round-off depend on which thread saw which
// cell before: with this, the assembly is bitwise independent of the number of threads. Shared by the indentation and tensile problems; one per assembly thread,
// so the quadrature loop allocates nothing. Units: um.
//
// run_on_owned_cells is their threaded cell loop (deal.II WorkStream on TBB): the worker runs
// on the threads with its own workspace and writes a CellContribution; the copier adds the
// contributions to the global objects on one thread, in cell order, so that the result does
// not depend on the number of threads (MultithreadInfo::n_threads()).
#pragma once

#include "fem/FiniteStrainElement.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <functional>
#include <span>
#include <type_traits>
#include <vector>

namespace indentsim::fem
{
  // A ghosted copy of a PETSc vector whose elements threads may read concurrently (reading a
  // PETSc vector goes through VecGetArray and is not thread-safe). Units of the source.
  using GhostedVector = dealii::LinearAlgebra::distributed::Vector<double>;
  // Collective: copies the owned and ghost values of `source` (a ghosted PETSc vector).
  GhostedVector to_thread_readable(const dealii::PETScWrappers::MPI::Vector &source,
                                   const dealii::IndexSet &owned, const dealii::IndexSet &relevant,
                                   MPI_Comm communicator);
  // The same into an existing vector with the layout of `source` (not collective: the
  // partitioner, whose construction is, is built once).
  void copy_to_thread_readable(const dealii::PETScWrappers::MPI::Vector &source,
                               GhostedVector                            &result);

  struct CellWorkspace
  {
    // `fe` is the displacement element, FESystem(FE_Q(1), 3) with dof a = component a % 3 of
    // node a / 3 (checked; throws std::invalid_argument otherwise).
    CellWorkspace(const dealii::FiniteElement<3> &fe, unsigned int n_q_points);
    // A fresh workspace for the same element (WorkStream copies one per thread).
    CellWorkspace(const CellWorkspace &other);
    // Evaluates the gradients on `cell` and reads its displacement values from `solution`.
    void reinit(const dealii::DoFHandler<3>::active_cell_iterator &cell,
                const GhostedVector                               &solution);
    // The element kernel (FiniteStrainElement.h) on the cell of the last reinit: residual, and
    // tangent when `tangent` is not null; Cauchy stresses at the points when asked.
    materials::UpdateStatus evaluate(const materials::MaterialModel &material, bool use_f_bar,
                                     std::span<const double> state_old, std::span<double> state_new,
                                     dealii::Vector<double>            &residual,
                                     dealii::FullMatrix<double>        *tangent,
                                     std::vector<dealii::Tensor<2, 3>> *cauchy = nullptr);

    const dealii::FiniteElement<3> &vector_fe;
    // grad_xi N_i at the Gauss points [q][i] and at the centre [i], Gauss weights [q].
    std::vector<std::vector<dealii::Tensor<1, 3>>> reference_grad;
    std::vector<dealii::Tensor<1, 3>>              reference_grad0;
    std::vector<double>                            weights;
    ElementScratch                                 scratch;
    dealii::Vector<double>                         u_local, r_local;
  };

  // What one cell adds to the global system.
  struct CellContribution
  {
    explicit CellContribution(unsigned int n_dofs = 24);
    materials::UpdateStatus                      status = materials::UpdateStatus::success;
    dealii::FullMatrix<double>                   matrix; // left unused without a matrix
    dealii::Vector<double>                       vector;
    std::vector<dealii::types::global_dof_index> dof_indices;
    unsigned int                                 cell_index = 0; // active cell index
    std::array<double, 2> sums = {{0., 0.}}; // problem-specific cell sums (reactions, volume)
  };

  // The workspace of the problem's element: the hexahedron (dim = 3) or the axisymmetric
  // quadrilateral (dim = 2, AxisymmetricCellWorkspace.h).
  template <int dim>
  struct CellWorkspaceFor;
  template <>
  struct CellWorkspaceFor<3>
  {
    using type = CellWorkspace;
  };

  template <int dim>
  using CellWorker =
      std::function<void(const typename dealii::DoFHandler<dim>::active_cell_iterator &,
                         typename CellWorkspaceFor<dim>::type &, CellContribution &)>;
  using CellCopier = std::function<void(const CellContribution &)>;

  // Calls `worker` on every locally owned cell (on all threads) and `copier` on each result (one
  // at a time, in cell order).
  template <int dim>
  void run_on_owned_cells(const dealii::DoFHandler<dim> &dof_handler, unsigned int n_q_points,
                          const std::type_identity_t<CellWorker<dim>> &worker,
                          const CellCopier                            &copier);
} // namespace indentsim::fem
