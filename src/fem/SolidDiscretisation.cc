#include "fem/SolidDiscretisation.h"

#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values_extractors.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

namespace indentsim::fem
{
  using namespace dealii;

  template <int dim>
  SolidDiscretisation<dim>::SolidDiscretisation(
      const MPI_Comm communicator, const typename Triangulation<dim>::MeshSmoothing mesh_smoothing)
    : communicator(communicator)
    , triangulation(communicator, mesh_smoothing,
                    parallel::distributed::Triangulation<dim>::default_setting)
    , fe(FE_Q<dim>(1), dim)
    , dof_handler(triangulation)
  {
  }

  template <int dim>
  SolidDiscretisation<dim>::~SolidDiscretisation()
  {
    // The DoF handler lets go of the triangulation before the triangulation is destroyed.
    dof_handler.clear();
  }

  template <int dim>
  void SolidDiscretisation<dim>::distribute_dofs()
  {
    dof_handler.distribute_dofs(fe);
    locally_owned = dof_handler.locally_owned_dofs();
    locally_relevant = DoFTools::extract_locally_relevant_dofs(dof_handler);
  }

  template <int dim>
  void SolidDiscretisation<dim>::reinit_matrix(const AffineConstraints<double>  &constraints,
                                               PETScWrappers::MPI::SparseMatrix &matrix) const
  {
    // keep_constrained_dofs = false: constrained rows and columns hold only their diagonal,
    // which is all that distribute_local_to_global writes into them.
    DynamicSparsityPattern dsp(locally_relevant);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp, locally_owned, communicator, locally_relevant);
    matrix.reinit(locally_owned, locally_owned, dsp, communicator);
  }

  template <int dim>
  void SolidDiscretisation<dim>::reinit_ghosted(PETScWrappers::MPI::Vector &vector) const
  {
    vector.reinit(locally_owned, locally_relevant, communicator);
  }

  template <int dim>
  void SolidDiscretisation<dim>::reinit_owned(PETScWrappers::MPI::Vector &vector) const
  {
    vector.reinit(locally_owned, communicator);
  }

  template <int dim>
  ComponentMask SolidDiscretisation<dim>::component_mask(const unsigned int component) const
  {
    return fe.component_mask(FEValuesExtractors::Scalar(component));
  }

  template <int dim>
  unsigned int SolidDiscretisation<dim>::n_cells() const
  {
    return triangulation.n_global_active_cells();
  }

  template <int dim>
  unsigned int SolidDiscretisation<dim>::n_dofs() const
  {
    return dof_handler.n_dofs();
  }

  template <int dim>
  unsigned int
  SolidDiscretisation<dim>::n_constrained_dofs(const AffineConstraints<double> &constraints) const
  {
    unsigned int local = 0;
    for (const auto &line : constraints.get_lines())
      if (locally_owned.is_element(line.index))
        ++local;
    return Utilities::MPI::sum(local, communicator);
  }
  template struct SolidDiscretisation<2>;
  template struct SolidDiscretisation<3>;
} // namespace indentsim::fem
