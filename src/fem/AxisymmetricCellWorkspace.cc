#include "fem/AxisymmetricCellWorkspace.h"

#include <array>
#include <stdexcept>
#include <utility>

namespace indentsim::fem
{
  using namespace dealii;

  AxisymmetricCellWorkspace::AxisymmetricCellWorkspace(const FiniteElement<2> &fe,
                                                       const unsigned int      n_q_points)
    : vector_fe(fe)
    , scratch(n_q_points)
    , u_local(fe.n_dofs_per_cell())
    , r_local(fe.n_dofs_per_cell())
  {
    bool ordered = fe.n_components() == 2 && fe.n_dofs_per_cell() == 8 && n_q_points == 4;
    for (unsigned int a = 0; ordered && a < fe.n_dofs_per_cell(); ++a)
      ordered = fe.system_to_component_index(a) == std::make_pair(a % 2, a / 2);
    if (!ordered)
      throw std::invalid_argument("AxisymmetricCellWorkspace: the displacement element must be "
                                  "FESystem(FE_Q(1), 2) with node-wise dof numbering and 2x2 "
                                  "Gauss points");
  }

  AxisymmetricCellWorkspace::AxisymmetricCellWorkspace(const AxisymmetricCellWorkspace &other)
    : AxisymmetricCellWorkspace(other.vector_fe, other.scratch.n_q_points)
  {
  }

  void AxisymmetricCellWorkspace::reinit(const DoFHandler<2>::active_cell_iterator &cell,
                                         const GhostedVector                       &solution)
  {
    std::array<Point<2>, 4> vertices;
    for (unsigned int i = 0; i < vertices.size(); ++i)
      vertices[i] = cell->vertex(i);
    reinit_axisymmetric(scratch, vertices);
    cell->get_dof_values(solution, u_local);
  }

  materials::UpdateStatus AxisymmetricCellWorkspace::evaluate(
      const materials::MaterialModel &material, const bool use_f_bar,
      std::span<const double> state_old, std::span<double> state_new, Vector<double> &residual,
      FullMatrix<double> *tangent, std::vector<Tensor<2, 3>> *cauchy)
  {
    return axisymmetric_element_residual_and_tangent(material, use_f_bar, u_local, state_old,
                                                     state_new, scratch, residual, tangent, cauchy);
  }
} // namespace indentsim::fem
