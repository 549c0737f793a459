#include "solver/CellWorkspace.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values_extractors.h>

namespace indentsim::solver
{
  using namespace dealii;

  CellWorkspace::CellWorkspace(const FESystem<3> &fe, const unsigned int n_q_points)
    : fe_values(fe, QGauss<3>(2), update_gradients | update_JxW_values)
    , fe_centre(fe, QGauss<3>(1), update_gradients)
    , scratch(fe.n_dofs_per_cell(), n_q_points)
    , u_local(fe.n_dofs_per_cell())
    , r_local(fe.n_dofs_per_cell())
  {}

  void CellWorkspace::reinit(const DoFHandler<3>::active_cell_iterator &cell,
                             const PETScWrappers::MPI::Vector          &solution)
  {
    const FEValuesExtractors::Vector displacement(0);
    fe_values.reinit(cell);
    fe_centre.reinit(cell);
    for (unsigned int q = 0; q < scratch.n_q_points; ++q)
      {
        scratch.JxW[q] = fe_values.JxW(q);
        for (unsigned int a = 0; a < scratch.n_dofs; ++a)
          scratch.G[q][a] = fe_values[displacement].gradient(a, q);
      }
    for (unsigned int a = 0; a < scratch.n_dofs; ++a)
      scratch.G0[a] = fe_centre[displacement].gradient(a, 0);
    cell->get_dof_values(solution, u_local);
  }
} // namespace indentsim::solver
