// Test-only access to IndentationProblem (its friend): a prescribed displacement field, the
// residual off the boundary and the stress at the quadrature points, for the patch tests.
// Units: um, mN, GPa.
#pragma once

#include "problems/IndentationProblem.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>

#include <cmath>
#include <functional>
#include <type_traits>

namespace indentsim::problems
{
  struct ProblemTestAccess
  {
    // Sets the displacement to u(X); hanging-node constraints are applied.
    template <int dim>
    static void
    set_displacement(IndentationProblem<dim> &p,
                     const std::type_identity_t<
                         std::function<dealii::Tensor<1, dim>(const dealii::Point<dim> &)>> &u)
    {
      dealii::PETScWrappers::MPI::Vector u_owned(p.solid_.locally_owned, p.communicator_);
      for (const auto &cell : p.solid_.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            {
              const dealii::Tensor<1, dim> value = u(cell->vertex(v));
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const auto dof = cell->vertex_dof_index(v, d);
                  if (p.solid_.locally_owned.is_element(dof))
                    u_owned(dof) = value[d];
                }
            }
      u_owned.compress(dealii::VectorOperation::insert);
      p.constraints_hanging_.distribute(u_owned);
      p.solution_ = u_owned;
    }

    // Assembles the residual for the current displacement (no contact) and returns its l2 norm
    // over the dofs off the boundary [mN].
    template <int dim>
    static double interior_residual_norm(IndentationProblem<dim> &p)
    {
      p.contact_->evaluate(p.solution_, -1e30); // indenter far away: no contact
      p.assemble(false);
      const dealii::IndexSet boundary_dofs =
          dealii::DoFTools::extract_boundary_dofs(p.solid_.dof_handler);
      double local = 0;
      for (const auto dof : p.solid_.locally_owned)
        if (!boundary_dofs.is_element(dof))
          local += p.residual_(dof) * p.residual_(dof);
      return std::sqrt(dealii::Utilities::MPI::sum(local, p.communicator_));
    }

    // The largest deviation of the Cauchy stress from `expected` over all quadrature points [GPa].
    template <int dim>
    static double max_stress_error(IndentationProblem<dim> &p, const dealii::Tensor<2, 3> &expected)
    {
      double error = 0;
      p.for_each_cell_stress(
          [&](const auto &, const std::vector<dealii::Tensor<2, 3>> &cauchy, const auto) {
            for (const auto &sigma : cauchy)
              error = std::max(error, (sigma - expected).norm());
          });
      return dealii::Utilities::MPI::max(error, p.communicator_);
    }
  };
} // namespace indentsim::problems
