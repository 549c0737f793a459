// The plastic zone of an indentation step: where the equivalent plastic strain exceeds
// nonlinear::plastic_zone_threshold (nonlinear/StepRecord.h), measured at the Gauss points of
// the element kernels in their reference positions. Units: um, um^3.
#include "problems/IndentationProblem.h"

#include "case/DamageProfile.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace indentsim::problems
{
  using namespace dealii;

  // Collective. The zone's depth below the undeformed surface z = 0 and its radius from the
  // indenter's axis (3D: sqrt(x^2 + y^2); axisymmetric: r), its volume for the whole indent
  // (3D: the model's times the symmetry factor; axisymmetric: 2 pi r dA) and the part of it
  // above the last layer's bottom of a depth-graded specimen.
  template <int dim>
  void IndentationProblem<dim>::measure_plastic_zone(StepRecord &record)
  {
    const double       layered_depth = io::graded_depth(case_.material);
    const unsigned int n_state = history_.n_state();
    FEValues<dim>      fe_values(solid_.fe, QGauss<dim>(2),
                                 update_quadrature_points | update_JxW_values);
    double             depth = 0, radius = 0, volume = 0, layer_volume = 0;
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const std::span<const double> states = history_.converged(cell);
        fe_values.reinit(cell);
        for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
          {
            const double strain =
                material_->equivalent_plastic_strain(states.subspan(q * n_state, n_state));
            if (!(strain > nonlinear::plastic_zone_threshold))
              continue;
            const Point<dim> &X = fe_values.quadrature_point(q);
            const double      r = dim == 3 ? std::hypot(X[0], X[1]) : std::abs(X[0]);
            const double      below = -X[dim - 1];
            const double      dv = dim == 3 ? symmetry_factor() * fe_values.JxW(q)
                                            : 2 * std::numbers::pi * r * fe_values.JxW(q);
            depth = std::max(depth, below);
            radius = std::max(radius, r);
            volume += dv;
            if (below < layered_depth)
              layer_volume += dv;
          }
      }
    record.plastic_zone_depth = Utilities::MPI::max(depth, communicator_);
    record.plastic_zone_radius = Utilities::MPI::max(radius, communicator_);
    record.plastic_zone_volume = Utilities::MPI::sum(volume, communicator_);
    record.plastic_zone_layer_volume = Utilities::MPI::sum(layer_volume, communicator_);
  }

  template class IndentationProblem<2>;
  template class IndentationProblem<3>;
} // namespace indentsim::problems
