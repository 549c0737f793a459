#include "fem/CellWorkspace.h"

#include "fem/AxisymmetricCellWorkspace.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/filtered_iterator.h>

#include <array>
#include <deal.II/fe/fe_values_extractors.h>
#include <stdexcept>
#include <utility>

namespace indentsim::fem
{
  using namespace dealii;

  CellWorkspace::CellWorkspace(const FiniteElement<3> &fe, const unsigned int n_q_points)
    : vector_fe(fe)
    , scratch(GeometryInfo<3>::vertices_per_cell, n_q_points)
    , u_local(fe.n_dofs_per_cell())
    , r_local(fe.n_dofs_per_cell())
  {
    const QGauss<3> gauss(2);
    bool ordered = fe.n_components() == 3 && fe.n_dofs_per_cell() == 3 * scratch.n_nodes &&
                   gauss.size() == n_q_points;
    for (unsigned int a = 0; ordered && a < fe.n_dofs_per_cell(); ++a)
      ordered = fe.system_to_component_index(a) == std::make_pair(a % 3, a / 3);
    if (!ordered)
      throw std::invalid_argument("CellWorkspace: the displacement element must be "
                                  "FESystem(FE_Q(1), 3) with node-wise dof numbering and 2x2x2 "
                                  "Gauss points");
    // FE_Q(1) shape function i belongs to vertex i.
    const FE_Q<3>  trilinear(1);
    const Point<3> centre(0.5, 0.5, 0.5);
    reference_grad.assign(n_q_points, std::vector<Tensor<1, 3>>(scratch.n_nodes));
    reference_grad0.resize(scratch.n_nodes);
    for (unsigned int i = 0; i < scratch.n_nodes; ++i)
      {
        for (unsigned int q = 0; q < n_q_points; ++q)
          reference_grad[q][i] = trilinear.shape_grad(i, gauss.point(q));
        reference_grad0[i] = trilinear.shape_grad(i, centre);
      }
    weights = gauss.get_weights();
  }

  GhostedVector to_thread_readable(const PETScWrappers::MPI::Vector &source, const IndexSet &owned,
                                   const IndexSet &relevant, const MPI_Comm communicator)
  {
    GhostedVector result(owned, relevant, communicator);
    copy_to_thread_readable(source, result);
    return result;
  }

  void copy_to_thread_readable(const PETScWrappers::MPI::Vector &source, GhostedVector &result)
  {
    IndexSet relevant = result.get_partitioner()->locally_owned_range();
    relevant.add_indices(result.get_partitioner()->ghost_indices());
    std::vector<types::global_dof_index> indices(relevant.begin(), relevant.end());
    std::vector<double>                  values(indices.size());
    source.extract_subvector_to(indices.begin(), indices.end(), values.begin());
    for (std::size_t k = 0; k < indices.size(); ++k)
      result(indices[k]) = values[k];
  }

  CellWorkspace::CellWorkspace(const CellWorkspace &other)
    : CellWorkspace(other.vector_fe, other.scratch.n_q_points)
  {
  }

  CellContribution::CellContribution(const unsigned int n_dofs)
    : matrix(n_dofs, n_dofs)
    , vector(n_dofs)
    , dof_indices(n_dofs)
  {
  }

  template <int dim>
  void run_on_owned_cells(const DoFHandler<dim> &dof_handler, const unsigned int n_q_points,
                          const std::type_identity_t<CellWorker<dim>> &worker,
                          const CellCopier                            &copier)
  {
    using Workspace = typename CellWorkspaceFor<dim>::type;
    const auto cells =
        filter_iterators(dof_handler.active_cell_iterators(), IteratorFilters::LocallyOwnedCell());
    const unsigned int n_dofs = dof_handler.get_fe().n_dofs_per_cell();
    WorkStream::run(cells.begin(), cells.end(), worker, copier,
                    Workspace(dof_handler.get_fe(), n_q_points), CellContribution(n_dofs));
  }

  template void run_on_owned_cells<2>(const DoFHandler<2> &, unsigned int, const CellWorker<2> &,
                                      const CellCopier &);
  template void run_on_owned_cells<3>(const DoFHandler<3> &, unsigned int, const CellWorker<3> &,
                                      const CellCopier &);

  namespace
  {
    // grad_X N_i = J^-T grad_xi N_i with J = dX/dxi = sum_i X_i (x) grad_xi N_i; returns det J.
    double physical_gradients(const std::array<Point<3>, 8>   &vertices,
                              const std::vector<Tensor<1, 3>> &reference,
                              std::vector<Tensor<1, 3>>       &gradients)
    {
      Tensor<2, 3> J;
      for (unsigned int i = 0; i < vertices.size(); ++i)
        for (unsigned int k = 0; k < 3; ++k)
          J[k] += vertices[i][k] * reference[i];
      const double       det = determinant(J);
      const Tensor<2, 3> J_inv_T = transpose(invert(J));
      for (unsigned int i = 0; i < vertices.size(); ++i)
        gradients[i] = J_inv_T * reference[i];
      return det;
    }
  } // namespace

  void CellWorkspace::reinit(const DoFHandler<3>::active_cell_iterator &cell,
                             const GhostedVector                       &solution)
  {
    std::array<Point<3>, 8> vertices;
    for (unsigned int i = 0; i < vertices.size(); ++i)
      vertices[i] = cell->vertex(i);
    // A parallelepiped (every cell of the indentation and tensile meshes: boxes bisected) has
    // the constant Jacobian J = [v1 - v0, v2 - v0, v4 - v0] (lexicographic vertices): one
    // inverse instead of nine. Other cells take the trilinear map point by point.
    const Tensor<1, 3> a = vertices[1] - vertices[0], b = vertices[2] - vertices[0],
                       c = vertices[4] - vertices[0];
    const double tolerance = 1e-13 * (a.norm() + b.norm() + c.norm());
    const bool   parallelepiped = (vertices[3] - vertices[0] - a - b).norm() <= tolerance &&
                                (vertices[5] - vertices[0] - a - c).norm() <= tolerance &&
                                (vertices[6] - vertices[0] - b - c).norm() <= tolerance &&
                                (vertices[7] - vertices[0] - a - b - c).norm() <= tolerance;
    if (parallelepiped)
      {
        Tensor<2, 3> J;
        for (unsigned int k = 0; k < 3; ++k)
          {
            J[k][0] = a[k];
            J[k][1] = b[k];
            J[k][2] = c[k];
          }
        const double       det = determinant(J);
        const Tensor<2, 3> J_inv_T = transpose(invert(J));
        for (unsigned int q = 0; q < scratch.n_q_points; ++q)
          {
            for (unsigned int i = 0; i < scratch.n_nodes; ++i)
              scratch.grad[q][i] = J_inv_T * reference_grad[q][i];
            scratch.JxW[q] = det * weights[q];
          }
        for (unsigned int i = 0; i < scratch.n_nodes; ++i)
          scratch.grad0[i] = J_inv_T * reference_grad0[i];
      }
    else
      {
        for (unsigned int q = 0; q < scratch.n_q_points; ++q)
          scratch.JxW[q] =
              physical_gradients(vertices, reference_grad[q], scratch.grad[q]) * weights[q];
        physical_gradients(vertices, reference_grad0, scratch.grad0);
      }
    cell->get_dof_values(solution, u_local);
  }

  materials::UpdateStatus
  CellWorkspace::evaluate(const materials::MaterialModel &material, const bool use_f_bar,
                          std::span<const double> state_old, std::span<double> state_new,
                          Vector<double> &residual, FullMatrix<double> *tangent,
                          std::vector<Tensor<2, 3>> *cauchy)
  {
    return element_residual_and_tangent(material, use_f_bar, u_local, state_old, state_new, scratch,
                                        residual, tangent, cauchy);
  }
} // namespace indentsim::fem
