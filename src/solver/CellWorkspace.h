// FEValues at the 2x2x2 Gauss points and at the centre of a hexahedron, turned into the inputs
// of the element kernel (FiniteStrainElement.h): dF/du_a, weights and the element's
// displacement values. Shared by the indentation and tensile problems; one per assembly loop,
// so the quadrature loop allocates nothing. Units: um.
#pragma once

#include "solver/FiniteStrainElement.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

namespace indentsim::solver
{
  struct CellWorkspace
  {
    CellWorkspace(const dealii::FESystem<3> &fe, unsigned int n_q_points);
    // Evaluates the gradients on `cell` and reads its displacement values from `solution`.
    void reinit(const dealii::DoFHandler<3>::active_cell_iterator &cell,
                const dealii::PETScWrappers::MPI::Vector           &solution);

    dealii::FEValues<3>    fe_values, fe_centre;
    ElementScratch         scratch;
    dealii::Vector<double> u_local, r_local;
  };
} // namespace indentsim::solver
