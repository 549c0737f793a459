// The displacement discretisation both problems (indentation and tensile) share: a distributed
// mesh of hexahedra (dim = 3) or of quadrilaterals in the (r, z) half-plane (dim = 2, the
// axisymmetric model), (bi/tri)linear vector elements FESystem(FE_Q(1), dim), their DoFs with the owned and
// relevant index sets, and the PETSc matrix and vectors laid out on them. The problems add what
// is theirs: the mesh, the constraints, the material states, the loads. Units: um.
//
// As in deal.II's step-42 and step-44, the objects are plain members that the problem reads and
// passes to the library; this type only owns them and performs the setup steps that were the same
// in every problem.
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

namespace indentsim::fem
{
  template <int dim>
  struct SolidDiscretisation
  {
    // `mesh_smoothing` as parallel::distributed::Triangulation takes it (the indentation mesh
    // limits the level difference at vertices; the tensile cube needs none).
    SolidDiscretisation(MPI_Comm                                           communicator,
                        typename dealii::Triangulation<dim>::MeshSmoothing mesh_smoothing =
                            dealii::Triangulation<dim>::none);
    ~SolidDiscretisation();

    // After the mesh is built: numbers the DoFs and fills the index sets.
    void distribute_dofs();
    // Gives `matrix` the sparsity of the cell couplings condensed with `constraints` (which
    // must hold every constraint that assembly will distribute).
    void reinit_matrix(const dealii::AffineConstraints<double>  &constraints,
                       dealii::PETScWrappers::MPI::SparseMatrix &matrix) const;
    // Owned-and-ghost layout (read by the cells) and owned-only layout (assembled into).
    void reinit_ghosted(dealii::PETScWrappers::MPI::Vector &vector) const;
    void reinit_owned(dealii::PETScWrappers::MPI::Vector &vector) const;

    // The mask selecting displacement component `component` (3D: 0 = x, 1 = y, 2 = z; axisymmetric: 0 = r, 1 = z).
    dealii::ComponentMask component_mask(unsigned int component) const;

    unsigned int n_cells() const;
    unsigned int n_dofs() const;
    // Collective: the number of DoFs constrained by `constraints`, each counted once by its
    // owner.
    unsigned int n_constrained_dofs(const dealii::AffineConstraints<double> &constraints) const;

    MPI_Comm                                          communicator;
    dealii::parallel::distributed::Triangulation<dim> triangulation;
    const dealii::FESystem<dim>                       fe;
    dealii::DoFHandler<dim>                           dof_handler;
    dealii::IndexSet                                  locally_owned, locally_relevant;
  };
} // namespace indentsim::fem
