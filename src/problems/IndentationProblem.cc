#include "problems/IndentationProblem.h"

#include "case/CaseFile.h"
#include "case/DamageProfile.h"
#include "fem/FiniteStrainElement.h"
#include "indenter/IndenterFactory.h"
#include "io/Version.h"
#include "materials/MaterialFactory.h"
#include "output/Checkpoint.h"

#include <deal.II/base/function.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q_eulerian.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace indentsim::problems
{
  using namespace dealii;
  using fem::CellContribution;
  using fem::copy_to_thread_readable;
  using fem::GhostedVector;
  using fem::run_on_owned_cells;
  using fem::to_thread_readable;
  using linalg::LinearSolver;
  using output::RunStatistics;

  template <int dim>
  IndentationProblem<dim>::IndentationProblem(
      const io::Case &the_case, const MPI_Comm communicator, const bool verbose,
      std::shared_ptr<const indenter::IndenterSurface> indenter)
    : case_(the_case)
    , communicator_(communicator)
    , pcout_(std::cout, verbose && Utilities::MPI::this_mpi_process(communicator) == 0)
    , solid_(communicator, Triangulation<dim>::limit_level_difference_at_vertices)
    , material_(materials::create_material(the_case.material))
    , indenter_(indenter ? std::move(indenter) : indenter::create_indenter(the_case.indenter))
    , use_f_bar_(the_case.specimen.f_bar)
    , linear_solver_(communicator)
  {
  }

  template <int dim>
  IndentationProblem<dim>::~IndentationProblem() = default;

  template <int dim>
  unsigned int IndentationProblem<dim>::n_cells() const
  {
    return solid_.n_cells();
  }
  template <int dim>
  unsigned int IndentationProblem<dim>::n_dofs() const
  {
    return solid_.n_dofs();
  }

  template <int dim>
  unsigned int IndentationProblem<dim>::n_constrained_dofs() const
  {
    return solid_.n_constrained_dofs(constraints_all_);
  }

  template <int dim>
  unsigned int IndentationProblem<dim>::n_hanging_node_constraints() const
  {
    return solid_.n_constrained_dofs(constraints_hanging_);
  }

  // The bottom's z reaction is the internal force its supported DoFs receive: from the cells
  // that touch the bottom, and through the hanging-node constraints from hanging DoFs whose
  // masters lie on the bottom (an automatic mesh coarsens toward the bottom, so a coarse cell's
  // side edge can end there).
  template <int dim>
  void IndentationProblem<dim>::collect_reaction_weights()
  {
    reaction_weights_.clear();
    const IndexSet bottom_z = DoFTools::extract_boundary_dofs(
        solid_.dof_handler, solid_.component_mask(dim - 1), {mesh::boundary::bottom});
    for (const types::global_dof_index dof : bottom_z)
      reaction_weights_[dof] = 1;
    for (const auto &line : constraints_hanging_.get_lines())
      {
        double weight = 0;
        for (const auto &[master, coefficient] : line.entries)
          if (bottom_z.is_element(master))
            weight += coefficient;
        if (weight != 0)
          reaction_weights_[line.index] = weight;
      }
  }

  // Hanging-node constraints, then the supports (bottom face, symmetry planes or the axis) on top
  // of them, as step-42 layers them.
  template <int dim>
  void IndentationProblem<dim>::make_constraints()
  {
    constraints_hanging_.clear();
    constraints_hanging_.reinit(solid_.locally_relevant);
    DoFTools::make_hanging_node_constraints(solid_.dof_handler, constraints_hanging_);
    constraints_hanging_.close();

    constraints_all_.clear();
    constraints_all_.reinit(solid_.locally_relevant);
    constraints_all_.merge(constraints_hanging_);
    const Functions::ZeroFunction<dim> zero(dim);
    VectorTools::interpolate_boundary_values(solid_.dof_handler, mesh::boundary::bottom, zero,
                                             constraints_all_);
    collect_reaction_weights();
    if constexpr (dim == 2)
      {
        // The axis r = 0: u_r = 0 (the section's nodes there stay on the axis).
        VectorTools::interpolate_boundary_values(solid_.dof_handler, mesh::boundary::axis, zero,
                                                 constraints_all_, solid_.component_mask(0));
        constraints_all_.close();
        return;
      }
    if (mesh_info_.quarter)
      {
        VectorTools::interpolate_boundary_values(solid_.dof_handler, mesh::boundary::x_min, zero,
                                                 constraints_all_, solid_.component_mask(0));
        VectorTools::interpolate_boundary_values(solid_.dof_handler, mesh::boundary::y_min, zero,
                                                 constraints_all_, solid_.component_mask(1));
      }
    // The surface node under the apex stays on the indentation axis (u_x = u_y = 0; in the
    // quarter model the symmetry planes impose it already). Node-to-surface contact only keeps
    // nodes out of the indenter; a sharp tip pushing an anisotropic crystal's apex node aside
    // would pass between the nodes unchecked (on (111) the surface under the tip
    // lags microns behind the apex). Holding that one node is the usual remedy.
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int v : cell->vertex_indices())
          if (cell->vertex(v).norm() < 1e-9 * case_.specimen.size[0])
            for (const unsigned int component : {0u, 1u})
              {
                const types::global_dof_index dof = cell->vertex_dof_index(v, component);
                if (!constraints_all_.is_constrained(dof))
                  constraints_all_.add_line(dof);
              }
    constraints_all_.close();
  }

  // The residual's round-off level [mN]. F = I + grad u carries an absolute error of the unit
  // round-off, so every element's stress is known to about 1e-16 mu, and its nodal forces to
  // that times its volume over its size; over the large cells of the far field this sums to
  // about 1e-16 mu A, A the model's bottom face (the volume over the depth). Measured: the
  // residual of the paper's axisymmetric case on its automatic mesh (A = 2.6e7 um^2) stalls
  // near 4e-7 mN (6e-16 mu A), that of a sharp cone's first increment on an elastic solid near
  // 1.2e-14 mu A; the floor taken, 1e-13 mu A (7e-5 mN for the paper's case), is 8e-8 of the
  // paper's final force.
  template <int dim>
  double IndentationProblem<dim>::residual_round_off() const
  {
    const auto  &size = case_.specimen.size;
    const double bottom_area =
        dim == 2 ? std::numbers::pi * size[0] * size[0] / 4 : size[0] * size[1] / symmetry_factor();
    return 1e-13 * material_->reference_modulus() * bottom_area;
  }

  template <int dim>
  void IndentationProblem<dim>::setup()
  {
    const RunStatistics::Scope timer(statistics_.setup);
    mesh_info_ = mesh::build_indentation_mesh(solid_.triangulation, case_.specimen);
    balance_plastic_zone();
    solid_.distribute_dofs();

    make_constraints();

    solid_.reinit_matrix(constraints_all_, matrix_);
    matrix_.compress(VectorOperation::insert); // final pattern, off-diagonal columns compressed
    scatter_.build(solid_.dof_handler, constraints_all_, matrix_);

    solid_.reinit_ghosted(solution_);
    solution_readable_.reinit(solid_.locally_owned, solid_.locally_relevant, communicator_);
    solid_.reinit_ghosted(solution_converged_);
    solid_.reinit_owned(solution_previous_);
    solid_.reinit_owned(residual_);

    // 2 x 2 x 2 (hexahedra) or 2 x 2 (axisymmetric quadrilaterals) Gauss points per cell.
    history_.reinit(solid_.triangulation.n_active_cells(), 1u << dim,
                    material_->n_state_variables());
    initialise_material_states();

    // contact.penalty: 0 (automatic) gives eps_i = 30 E / L_i on each node (L_i its faces' mean
    // edge): eps_i L_i / E sets the rate of the augmentation passes, alike on every node of a
    // graded mesh.
    contact_ = std::make_unique<contact::NodeToSurfaceContact>(*indenter_, case_.contact.penalty,
                                                               case_.contact.friction_coefficient);
    if (!(case_.contact.penalty > 0))
      contact_->set_local_penalty(30. * material_->reference_modulus());
    contact_->set_predictor_activation_depth(case_.contact.penetration_tolerance);
    absolute_tolerance_ = std::max(case_.solver.absolute_tolerance, residual_round_off());
    if constexpr (dim == 3)
      contact_->setup(solid_.dof_handler, constraints_hanging_, mesh::boundary::top,
                      mesh_info_.refined_half_x, mesh_info_.refined_half_y, communicator_,
                      /*axis_held=*/mesh_info_.quarter);
    else
      contact_->setup(solid_.dof_handler, constraints_hanging_, mesh::boundary::top,
                      mesh_info_.refined_half_x, communicator_);

    mirror_planes_ = shared_mirror_planes();
    linear_solver_.setup(solid_.dof_handler,
                         LinearSolver::choose_kind(case_.solver.linear_solver, dim, n_dofs()),
                         material_->symmetric_tangent() && contact_->symmetric_tangent());

    pcout_ << "Mesh: " << n_cells() << " cells, " << n_dofs() << " DOFs, " << n_constrained_dofs()
           << " constrained DOFs (hanging nodes and supports), "
           << "contact element size " << mesh_info_.contact_element_size << " um, "
           << Utilities::MPI::n_mpi_processes(communicator_) << " MPI rank(s)\n"
           << "Contact: penalty " << contact_->penalty_range().first << " to "
           << contact_->penalty_range().second << " GPa/um, contact-surface area "
           << contact_->total_area() << " um^2 (model)\n"
           << "Linear solver: " << linear_solver_.description() << "\n"
           << "Matrix assembly: " << std::fixed << std::setprecision(1)
           << 100 * scatter_.fast_fraction() << std::defaultfloat
           << " % of rank 0's cells by precomputed positions" << std::endl;
  }

  // A single crystal: one lattice orientation everywhere (isotropic models ignore it). A
  // depth-graded material (material.layers or damage_profile) takes at each Gauss point the layer of its depth
  // below the undeformed surface z = 0, the last coordinate in 3D and in the (r, z) section; the
  // points are those of the element kernels (2 x 2 (x 2) Gauss points in deal.II's order).
  template <int dim>
  void IndentationProblem<dim>::initialise_material_states()
  {
    const dealii::Tensor<2, 3> orientation = materials::create_orientation(case_.material);
    for (std::size_t i = 0; i < history_.n_points(); ++i)
      material_->oriented_initial_state(history_.converged_point(i), orientation);
    if (io::graded_depth(case_.material) > 0)
      {
        const unsigned int    n_state = history_.n_state();
        dealii::FEValues<dim> fe_values(solid_.fe, dealii::QGauss<dim>(2),
                                        dealii::update_quadrature_points);
        for (const auto &cell : solid_.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              const std::span<double> states = history_.converged(cell);
              for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
                material_->initial_state_at_depth(states.subspan(q * n_state, n_state), orientation,
                                                  -fe_values.quadrature_point(q)[dim - 1]);
            }
      }
    history_.converged_changed();
  }

  template <int dim>
  void IndentationProblem<dim>::balance_plastic_zone()
  {
    const double extra_cost = material_->relative_plastic_cost() - 1.0;
    if (Utilities::MPI::n_mpi_processes(communicator_) == 1 || !(extra_cost > 0))
      return;
    // The plastic zone under a blunt or conical indenter is about a hemisphere of 2.5 contact
    // radii (Johnson's expanding-cavity picture: c/a = 2-3 for the paper's cone), centred at the
    // contact; the contact radius at the deepest point follows from the indenter's area
    // function. Its cells are weighted by the cost of a plastic point, the others by 1 (in
    // units of 1000, p4est's integer weights), and p4est repartitions the cells in its
    // space-filling-curve order. The partition changes no result beyond round-off.
    const double a_c =
        std::sqrt(indenter_->projected_area(case_.loading.max_depth) / std::numbers::pi);
    const double radius = 2.5 * a_c;
    const auto   weight =
        [radius,
         extra_cost](const typename parallel::distributed::Triangulation<dim>::cell_iterator &cell,
                     const typename parallel::distributed::Triangulation<dim>::CellStatus) {
          return static_cast<unsigned int>(
              1000 * (1.0 + (cell->center().norm() < radius ? extra_cost : 0.0)));
        };
    auto connection = solid_.triangulation.signals.weight.connect(weight);
    solid_.triangulation.repartition();
    connection.disconnect();
  }

  template <int dim>
  typename IndentationProblem<dim>::AssemblyResult
  IndentationProblem<dim>::assemble(const bool                                          with_matrix,
                                    contact::NodeToSurfaceContact::DepthCoupling *const coupling)
  {
    AssemblyResult result;
    ++statistics_.assemblies;
    if (!with_matrix)
      ++statistics_.residual_only_assemblies;
    std::optional<RunStatistics::Scope> timer(std::in_place, statistics_.assembly);
    if (with_matrix)
      matrix_ = 0;
    residual_ = 0;
    double local_reaction = 0;

    copy_to_thread_readable(solution_, solution_readable_);
    const GhostedVector &u = solution_readable_;
    const auto           worker = [&](const typename DoFHandler<dim>::active_cell_iterator &cell,
                            Workspace &workspace, CellContribution &contribution) {
      workspace.reinit(cell, u);
      contribution.status = workspace.evaluate(*material_, use_f_bar_, history_.converged(cell),
                                                         history_.current(cell), contribution.vector,
                                               with_matrix ? &contribution.matrix : nullptr);
      cell->get_dof_indices(contribution.dof_indices);
      contribution.cell_index = cell->active_cell_index();
      // Bottom reaction: the internal force that reaches the supported z DoFs.
      contribution.sums[0] = 0;
      for (unsigned int a = 0; a < solid_.fe.n_dofs_per_cell(); ++a)
        if (const auto w = reaction_weights_.find(contribution.dof_indices[a]);
            w != reaction_weights_.end())
          contribution.sums[0] += w->second * contribution.vector[a];
    };
    const auto copier = [&](const CellContribution &contribution) {
      if (contribution.status != materials::UpdateStatus::success)
        {
          result.status = contribution.status;
          return; // keep going so that every rank reaches the collective calls
        }
      if (with_matrix && scatter_.is_fast(contribution.cell_index))
        {
          scatter_.add(contribution.cell_index, contribution.matrix);
          constraints_all_.distribute_local_to_global(contribution.vector, contribution.dof_indices,
                                                      residual_);
        }
      else if (with_matrix)
        constraints_all_.distribute_local_to_global(contribution.matrix, contribution.vector,
                                                    contribution.dof_indices, matrix_, residual_);
      else
        constraints_all_.distribute_local_to_global(contribution.vector, contribution.dof_indices,
                                                    residual_);
      local_reaction += contribution.sums[0];
    };
    {
      const RunStatistics::Scope cell_loop_timer(statistics_.cell_loop);
      if (with_matrix)
        scatter_.begin(matrix_);
      run_on_owned_cells(solid_.dof_handler, history_.n_q_points(), worker, copier);
    }
    // After the cell loop's timer: end() waits for the other ranks, so that the cell loop's
    // spread over the ranks shows their imbalance.
    if (with_matrix)
      scatter_.end();
    timer.emplace(statistics_.contact);
    contact_->assemble(constraints_all_, residual_, with_matrix ? &matrix_ : nullptr,
                       with_matrix ? coupling : nullptr);
    timer.emplace(statistics_.assembly);
    if (with_matrix)
      matrix_.compress(VectorOperation::add);
    residual_.compress(VectorOperation::add);

    // A bottom node's reaction is the sum of its cells' internal forces, so the sum over the
    // locally owned cells, summed over ranks, is the total reaction.
    result.bottom_reaction = Utilities::MPI::sum(local_reaction, communicator_);
    const unsigned int failed = Utilities::MPI::max(
        static_cast<unsigned int>(result.status != materials::UpdateStatus::success),
        communicator_);
    if (failed && result.status == materials::UpdateStatus::success)
      result.status = materials::UpdateStatus::local_newton_failed;
    return result;
  }

  template <int dim>
  bool IndentationProblem<dim>::reassemble_contact()
  {
    const RunStatistics::Scope timer(statistics_.contact);
    if (!contact_->retract(constraints_all_, residual_, matrix_))
      return false;
    contact_->assemble(constraints_all_, residual_, &matrix_);
    matrix_.compress(VectorOperation::add);
    residual_.compress(VectorOperation::add);
    ++statistics_.contact_only_assemblies;
    return true;
  }

  template <int dim>
  double IndentationProblem<dim>::depth_guess_for_force(const double target_force) const
  {
    if (target_force > force_converged_ && force_converged_ > 0 && depth_converged_ > 0)
      {
        // Loading: indentation curves follow F ~ h^m (m = 2 for a cone, 1.5 for a sphere in the
        // Hertz range): m from the last two states in log-log, else 1.5.
        double m = 1.5;
        if (force_previous_ > 0 && depth_previous_ > 0 && depth_converged_ > depth_previous_ &&
            force_converged_ > force_previous_)
          m = std::log(force_converged_ / force_previous_) /
              std::log(depth_converged_ / depth_previous_);
        m = std::clamp(std::isfinite(m) ? m : 1.5, 1.0, 3.0);
        return depth_converged_ * std::pow(target_force / force_converged_, 1 / m);
      }
    // Unloading (or reloading at low force): secant of the last two converged states, limited
    // to twice their depth step, when they moved the same way; at a reversal (plastic loading to
    // elastic unloading) the last slope says nothing, and the Newton update finds the depth.
    const bool same_direction =
        (target_force - force_converged_) * (force_converged_ - force_previous_) > 0;
    if (has_previous_ && same_direction)
      {
        const double slope =
            (depth_converged_ - depth_previous_) / (force_converged_ - force_previous_);
        const double step = slope * (target_force - force_converged_);
        const double limit = 2 * std::abs(depth_converged_ - depth_previous_);
        if (std::isfinite(step))
          return depth_converged_ + std::clamp(step, -limit, limit);
      }
    return depth_converged_;
  }

  template <int dim>
  contact::ContactPatch IndentationProblem<dim>::contact_patch() const
  {
    // The indicator phi (first dof of each contact node) and a marker (second dof) distinguishing
    // contact nodes from the rest, made readable on the ghost vertices of the owned faces.
    PETScWrappers::MPI::Vector indicator(solid_.locally_owned, communicator_);
    for (const contact::ContactNode &node : contact_->nodes())
      {
        indicator(node.dofs[0]) =
            node.active ? node.pressure : node.lambda - node.penalty * node.gap;
        indicator(node.dofs[1]) = 1;
      }
    indicator.compress(VectorOperation::insert);
    PETScWrappers::MPI::Vector ghosted(solid_.locally_owned, solid_.locally_relevant,
                                       communicator_);
    ghosted = indicator;

    contact::ContactPatch local;
    const auto            add = [&local](const contact::ContactPatch &patch) {
      local.area += patch.area;
      local.max_radius = std::max(local.max_radius, patch.max_radius);
      local.max_abs_x = std::max(local.max_abs_x, patch.max_abs_x);
      local.max_abs_y = std::max(local.max_abs_y, patch.max_abs_y);
    };
    // The indicator and position of a face's vertex v (its first coordinate: r in the
    // axisymmetric model); false if it is not a contact node.
    const auto read_vertex = [&](const auto &face, const unsigned int v, double &phi) {
      phi = ghosted(face->vertex_dof_index(v, 0));
      return ghosted(face->vertex_dof_index(v, 1)) == 1;
    };
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          {
            if (!face->at_boundary() || face->boundary_id() != mesh::boundary::top)
              continue;
            bool all_contact_nodes = true;
            if constexpr (dim == 3)
              {
                // deal.II numbers a face's vertices lexicographically; cyclic order is 0, 1, 3, 2.
                constexpr unsigned int  cyclic[4] = {0, 1, 3, 2};
                std::array<Point<2>, 4> xy;
                std::array<double, 4>   phi;
                for (unsigned int k = 0; k < 4; ++k)
                  {
                    const unsigned int v = cyclic[k];
                    all_contact_nodes = read_vertex(face, v, phi[k]) && all_contact_nodes;
                    for (unsigned int d = 0; d < 2; ++d)
                      xy[k][d] = face->vertex(v)[d] + solution_(face->vertex_dof_index(v, d));
                  }
                if (all_contact_nodes)
                  add(contact::quad_contact_patch(xy, phi));
              }
            else
              {
                std::array<double, 2> r, phi;
                for (unsigned int v = 0; v < 2; ++v)
                  {
                    all_contact_nodes = read_vertex(face, v, phi[v]) && all_contact_nodes;
                    r[v] = face->vertex(v)[0] + solution_(face->vertex_dof_index(v, 0));
                  }
                if (all_contact_nodes)
                  add(contact::segment_contact_patch(r, phi));
              }
          }
    contact::ContactPatch global;
    global.area = Utilities::MPI::sum(local.area, communicator_);
    global.max_radius = Utilities::MPI::max(local.max_radius, communicator_);
    global.max_abs_x = Utilities::MPI::max(local.max_abs_x, communicator_);
    global.max_abs_y = Utilities::MPI::max(local.max_abs_y, communicator_);
    return global;
  }

  template <int dim>
  void IndentationProblem<dim>::accept_increment()
  {
    history_.accept();
    solution_previous_ = solution_converged_;
    solution_converged_ = solution_;
    depth_previous_ = depth_converged_;
    depth_converged_ = depth_trial_;
    force_previous_ = force_converged_;
    force_converged_ = force_trial_;
    converged_force_scale_ = std::max(converged_force_scale_, trial_force_scale_);
    has_previous_ = true;
    contact_->accept_increment();
  }

  template <int dim>
  void IndentationProblem<dim>::reject_increment()
  {
    history_.reject();
    solution_ = solution_converged_;
    contact_->reject_increment();
  }

  template <int dim>
  void IndentationProblem<dim>::for_each_cell_stress(
      const std::function<void(const typename DoFHandler<dim>::active_cell_iterator &,
                               const std::vector<Tensor<2, 3>> &, std::span<const double>)> &visit)
  {
    Workspace                 workspace(solid_.fe, history_.n_q_points());
    std::vector<Tensor<2, 3>> cauchy(history_.n_q_points());
    std::vector<double>       state(history_.cell_length());
    const GhostedVector       u =
        to_thread_readable(solution_, solid_.locally_owned, solid_.locally_relevant, communicator_);
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        workspace.reinit(cell, u);
        workspace.evaluate(*material_, use_f_bar_, history_.converged(cell), state,
                           workspace.r_local, nullptr, &cauchy);
        visit(cell, cauchy, state);
      }
  }
  template class IndentationProblem<2>;
  template class IndentationProblem<3>;
} // namespace indentsim::problems
