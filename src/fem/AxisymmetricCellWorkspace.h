// The inputs of the axisymmetric element kernel (AxisymmetricElement.h) on one quadrilateral of
// the (r, z) section: the kernel's scratch filled from the cell's vertices, and the element's
// displacement values (u_r, u_z node by node). The counterpart of CellWorkspace (hexahedra) for
// run_on_owned_cells<2>; one per assembly thread. Units: um.
#pragma once

#include "fem/AxisymmetricElement.h"
#include "fem/CellWorkspace.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <span>
#include <vector>

namespace indentsim::fem
{
  struct AxisymmetricCellWorkspace
  {
    // `fe` is FESystem(FE_Q(1), 2) with dof a = component a % 2 of node a / 2 (checked; throws
    // std::invalid_argument otherwise); 2 x 2 Gauss points.
    AxisymmetricCellWorkspace(const dealii::FiniteElement<2> &fe, unsigned int n_q_points);
    AxisymmetricCellWorkspace(const AxisymmetricCellWorkspace &other);
    void reinit(const dealii::DoFHandler<2>::active_cell_iterator &cell,
                const GhostedVector                               &solution);
    // The axisymmetric kernel on the cell of the last reinit (whole-ring forces [mN]); Cauchy
    // stresses in (r, theta, z) components when asked.
    materials::UpdateStatus evaluate(const materials::MaterialModel &material, bool use_f_bar,
                                     std::span<const double> state_old, std::span<double> state_new,
                                     dealii::Vector<double>            &residual,
                                     dealii::FullMatrix<double>        *tangent,
                                     std::vector<dealii::Tensor<2, 3>> *cauchy = nullptr);

    const dealii::FiniteElement<2> &vector_fe;
    AxisymmetricScratch             scratch;
    dealii::Vector<double>          u_local, r_local;
  };

  template <>
  struct CellWorkspaceFor<2>
  {
    using type = AxisymmetricCellWorkspace;
  };
} // namespace indentsim::fem
