#include "contact/NodeToSurfaceContact.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

namespace indentsim::contact
{
  using namespace dealii;

  NodeToSurfaceContact::NodeToSurfaceContact(const indenter::IndenterSurface &surface,
                                             const double                     penalty,
                                             const double                     friction_coefficient)
    : surface_(surface)
    , penalty_(penalty)
    , mu_(friction_coefficient)
  {
  }

  void NodeToSurfaceContact::set_local_penalty(const double stiffness)
  {
    local_penalty_stiffness_ = stiffness;
  }

  std::pair<double, double> NodeToSurfaceContact::penalty_range() const
  {
    double smallest = std::numeric_limits<double>::max(), largest = 0;
    for (const ContactNode &node : nodes_)
      {
        smallest = std::min(smallest, node.penalty_initial);
        largest = std::max(largest, node.penalty_initial);
      }
    return {Utilities::MPI::min(smallest, communicator_),
            Utilities::MPI::max(largest, communicator_)};
  }

  void NodeToSurfaceContact::set_lateral_offset(const Tensor<1, 3> &offset)
  {
    offset_ = Tensor<1, 3>({offset[0], offset[1], 0.});
  }

  void NodeToSurfaceContact::setup(const DoFHandler<3>             &dof_handler,
                                   const AffineConstraints<double> &hanging_node_constraints,
                                   const types::boundary_id top_boundary, const double half_x,
                                   const double half_y, const MPI_Comm communicator,
                                   const bool axis_held)
  {
    communicator_ = communicator;
    nodes_.clear();
    const IndexSet &owned = dof_handler.locally_owned_dofs();

    // Tributary areas by nodal (Lobatto) quadrature of the top faces: each vertex of a
    // rectangular face receives a quarter of its area. Faces owned by other ranks contribute to
    // our nodes through the compress(add).
    PETScWrappers::MPI::Vector area(owned, communicator), edge_sum(owned, communicator),
        faces(owned, communicator);
    std::map<types::global_dof_index, ContactNode> found;
    const double                                   tol = 1e-8 * (half_x + half_y);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary() || face->boundary_id() != top_boundary)
              continue;
            const Point<3> c = face->center();
            if (std::abs(c[0]) > half_x + tol || std::abs(c[1]) > half_y + tol)
              continue;
            const double quarter_area = face->measure() / 4.;
            for (const unsigned int v : face->vertex_indices())
              {
                const types::global_dof_index dof_x = face->vertex_dof_index(v, 0);
                area(face->vertex_dof_index(v, 2)) += quarter_area;
                edge_sum(face->vertex_dof_index(v, 2)) += std::sqrt(face->measure());
                faces(face->vertex_dof_index(v, 2)) += 1;
                if (!owned.is_element(dof_x) || hanging_node_constraints.is_constrained(dof_x))
                  continue;
                ContactNode node;
                for (unsigned int d = 0; d < 3; ++d)
                  node.dofs[d] = face->vertex_dof_index(v, d);
                node.X = face->vertex(v);
                node.x_converged = node.X;
                node.on_axis =
                    axis_held && std::abs(node.X[0]) <= tol && std::abs(node.X[1]) <= tol;
                found.emplace(dof_x, node);
              }
          }
      }
    store_nodes(found, area, edge_sum, faces);
  }

  void NodeToSurfaceContact::setup(const DoFHandler<2>             &dof_handler,
                                   const AffineConstraints<double> &hanging_node_constraints,
                                   const types::boundary_id top_boundary, const double half_x,
                                   const MPI_Comm communicator)
  {
    communicator_ = communicator;
    axes_ = {0, 2};
    nodes_.clear();
    const IndexSet &owned = dof_handler.locally_owned_dofs();
    // Ring areas: integral of N_i 2 pi r ds over the edge from r_i to r_j of length L is
    // 2 pi L (2 r_i + r_j) / 6 (the row sum of the consistent weighted mass): the node on the
    // axis keeps the area of its half edge's ring.
    PETScWrappers::MPI::Vector area(owned, communicator), edge_sum(owned, communicator),
        faces(owned, communicator);
    std::map<types::global_dof_index, ContactNode> found;
    const double                                   tol = 1e-8 * half_x;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const auto &face : cell->face_iterators())
          {
            if (!face->at_boundary() || face->boundary_id() != top_boundary ||
                face->center()[0] > half_x + tol)
              continue;
            const double length = face->measure();
            for (const unsigned int v : {0u, 1u})
              {
                const double r_i = face->vertex(v)[0], r_j = face->vertex(1 - v)[0];
                area(face->vertex_dof_index(v, 1)) +=
                    2 * std::numbers::pi * length * (2 * r_i + r_j) / 6;
                edge_sum(face->vertex_dof_index(v, 1)) += length;
                faces(face->vertex_dof_index(v, 1)) += 1;
                const types::global_dof_index dof_r = face->vertex_dof_index(v, 0);
                if (!owned.is_element(dof_r) || hanging_node_constraints.is_constrained(dof_r))
                  continue;
                ContactNode node;
                node.dofs = {dof_r, face->vertex_dof_index(v, 1), numbers::invalid_dof_index};
                node.X = Point<3>(r_i, 0., face->vertex(v)[1]);
                node.x_converged = node.X;
                node.on_axis = r_i <= tol;
                found.emplace(dof_r, node);
              }
          }
      }
    store_nodes(found, area, edge_sum, faces);
  }

  void NodeToSurfaceContact::store_nodes(std::map<types::global_dof_index, ContactNode> &found,
                                         PETScWrappers::MPI::Vector                     &area,
                                         PETScWrappers::MPI::Vector                     &edge_sum,
                                         PETScWrappers::MPI::Vector                     &faces)
  {
    area.compress(VectorOperation::add);
    edge_sum.compress(VectorOperation::add);
    faces.compress(VectorOperation::add);
    // The sums sit on the dof of the last (z) component.
    const unsigned int z = axes_.size() - 1;
    for (auto &[first_dof, node] : found)
      {
        node.area = area(node.dofs[z]);
        const double mean_edge = edge_sum(node.dofs[z]) / faces(node.dofs[z]);
        node.penalty_initial =
            local_penalty_stiffness_ > 0 ? local_penalty_stiffness_ / mean_edge : penalty_;
        node.penalty = node.penalty_initial;
        nodes_.push_back(node);
      }
  }

  namespace
  {
    // Component d of the nodal force per unit area, p n + t, of a response [GPa].
    template <class Response>
    double nodal_force(const Response &response, const unsigned int d)
    {
      return response.pressure * response.projection.normal[d] + response.traction[d];
    }
  } // namespace

  indenter::SurfaceProjection NodeToSurfaceContact::axis_projection(const Point<3> &x,
                                                                    const double    depth) const
  {
    indenter::SurfaceProjection projection;
    projection.closest_point =
        Point<3>(x[0], x[1], surface_.profile(x[0] - offset_[0], x[1] - offset_[1]) - depth);
    projection.gap = projection.closest_point[2] - x[2];
    projection.normal[2] = -1;
    return projection;
  }

  NodeToSurfaceContact::NodeResponse
  NodeToSurfaceContact::respond(const ContactNode &node, const Point<3> &x, const int normal_active,
                                const ContactStatus *fixed_status, const double depth) const
  {
    NodeResponse response;
    if (node.on_axis)
      response.projection = axis_projection(x, depth);
    else
      {
        response.projection = surface_.project(x - offset_, depth);
        response.projection.closest_point += offset_;
      }
    if (!response.projection.converged || !std::isfinite(response.projection.gap))
      return response;
    const Tensor<1, 3> &n = response.projection.normal;
    const double        augmented = node.lambda - node.penalty * response.projection.gap;
    const bool          active = normal_active >= 0 ? normal_active == 1 : augmented > 0;
    if (!active)
      return response;
    response.pressure = augmented;
    if (mu_ == 0.0)
      {
        response.status = ContactStatus::slip;
        return response;
      }
    // Relative slip over the increment against the rigid indenter, whose position is
    // w = (offset_x, offset_y, -depth), and its part in the tangent plane.
    Tensor<1, 3> s = (x - node.x_converged) - (offset_ - offset_converged_);
    s[2] += depth - depth_converged_;
    response.slip = s - (s * n) * n;
    const Tensor<1, 3> multiplier = node.traction_multiplier - (node.traction_multiplier * n) * n;
    const Tensor<1, 3> trial = multiplier - node.penalty * response.slip;
    const double       limit = mu_ * std::max(response.pressure, 0.0);
    const double       trial_norm = trial.norm();
    // A slipping node whose trial traction turns against its last traction has passed through
    // the stick zone between the two directions: it sticks. Without this rule the semi-smooth
    // Newton iteration jumps from one side of the cone to the other when the penalty is stiffer
    // than the specimen under the node (the spring-block test then cycles forever).
    const bool reversed = node.status == ContactStatus::slip && trial * node.traction < 0;
    const bool stick =
        fixed_status ? *fixed_status == ContactStatus::stick : (trial_norm <= limit || reversed);
    if (stick)
      {
        response.status = ContactStatus::stick;
        response.traction = trial;
      }
    else
      {
        // Return onto the Coulomb cone, eq. 18.
        response.status = ContactStatus::slip;
        if (trial_norm > 0)
          response.traction = (limit / trial_norm) * trial;
      }
    return response;
  }

  bool NodeToSurfaceContact::evaluate(const PETScWrappers::MPI::Vector &u, const double depth,
                                      const ActiveSet mode)
  {
    n_changes_ = 0;
    search_failed_ = false;
    depth_ = depth;
    before_last_.resize(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      {
        ContactNode &node = nodes_[i];
        before_last_[i] = {node.status, node.active, node.held};
        for (unsigned int k = 0; k < axes_.size(); ++k)
          node.x[axes_[k]] = node.X[axes_[k]] + u(node.dofs[k]);
        int normal_active = -1; // decided by the augmented pressure
        if ((mode == ActiveSet::predictor && node.lambda_converged > 0) ||
            (mode == ActiveSet::free && node.held))
          normal_active = 1;
        else if (mode == ActiveSet::frozen)
          normal_active = node.active;
        const ContactStatus  previous = node.status;
        const ContactStatus *fixed =
            (mode == ActiveSet::frozen && node.active) ? &previous : nullptr;
        NodeResponse response = respond(node, node.x, normal_active, fixed, depth_);
        // A node that carried no pressure in the last converged increment joins the
        // predictor's set only if the predicted state clearly penetrates: by more than the
        // activation depth (the contact tolerance), so that a node touching the indenter
        // within round-off is not active on one partition and open on another.
        if (mode == ActiveSet::predictor && normal_active == -1 &&
            response.status != ContactStatus::open &&
            !(response.projection.gap < -predictor_activation_depth_))
          response = respond(node, node.x, 0, fixed, depth_);
        if (!response.projection.converged || !std::isfinite(response.projection.gap))
          {
            search_failed_ = true;
            node.pressure = 0;
            node.active = false;
            node.status = ContactStatus::open;
            node.traction = 0;
            continue;
          }
        node.gap = response.projection.gap;
        node.normal = response.projection.normal;
        node.active = response.status != ContactStatus::open;
        node.held = node.held || (mode == ActiveSet::free && node.active);
        node.status = response.status;
        n_changes_ += (node.status != previous);
        node.pressure = response.pressure;
        node.traction = response.traction;
        node.slip = response.slip;
      }
    return !search_failed_;
  }

  void NodeToSurfaceContact::reject_last_evaluation()
  {
    for (std::size_t i = 0; i < std::min(nodes_.size(), before_last_.size()); ++i)
      {
        nodes_[i].status = before_last_[i].status;
        nodes_[i].active = before_last_[i].active;
        nodes_[i].held = before_last_[i].held;
      }
  }

  void NodeToSurfaceContact::start_pass()
  {
    for (ContactNode &node : nodes_)
      node.held = false;
  }

  void NodeToSurfaceContact::assemble(const AffineConstraints<double>  &constraints,
                                      PETScWrappers::MPI::Vector       &residual,
                                      PETScWrappers::MPI::SparseMatrix *matrix,
                                      DepthCoupling                    *coupling)
  {
    Assert(!coupling || matrix, ExcMessage("the depth coupling needs the tangent"));
    kept_.clear();
    kept_valid_ = matrix != nullptr && coupling == nullptr;
    // Component k of the node moves the 3D axis axes_[k]; the z axis is the last.
    const unsigned int                   n = axes_.size();
    FullMatrix<double>                   local_matrix(n, n);
    Vector<double>                       local_residual(n);
    std::vector<types::global_dof_index> dofs(n);
    for (const ContactNode &node : nodes_)
      {
        if (!node.active)
          continue;
        const double force = node.pressure * node.area; // [mN]
        for (unsigned int k = 0; k < n; ++k)
          {
            const unsigned int d = axes_[k];
            local_residual[k] = -force * node.normal[d] - node.area * node.traction[d];
            dofs[k] = node.dofs[k];
          }
        if (matrix)
          {
            const double h = 1e-7 * std::max(1.0, node.x.norm());
            if (mu_ == 0.0)
              {
                // d(-p A n)/dx = eps A n (x) n - p A dn/dx. The derivative of the normal (the
                // Hessian of the signed distance, i.e. the indenter's curvature) is taken by
                // central differences of the exact closest-point projection.
                for (unsigned int i = 0; i < n; ++i)
                  for (unsigned int j = 0; j < n; ++j)
                    local_matrix(i, j) =
                        node.penalty * node.area * node.normal[axes_[i]] * node.normal[axes_[j]];
                for (unsigned int j = 0; j < n; ++j)
                  {
                    Point<3> xp = node.x, xm = node.x;
                    xp[axes_[j]] += h;
                    xm[axes_[j]] -= h;
                    const auto pp = surface_.project(xp - offset_, depth_);
                    const auto pm = surface_.project(xm - offset_, depth_);
                    for (unsigned int i = 0; i < n; ++i)
                      local_matrix(i, j) -=
                          force * (pp.normal[axes_[i]] - pm.normal[axes_[i]]) / (2 * h);
                  }
              }
            else
              {
                // With friction: d(-f)/dx, f = A (p n + t), by central differences of the exact
                // nodal response at the frozen status (normal and Coulomb parts alike; the
                // slip tangent is not symmetric).
                for (unsigned int j = 0; j < n; ++j)
                  {
                    Point<3> xp = node.x, xm = node.x;
                    xp[axes_[j]] += h;
                    xm[axes_[j]] -= h;
                    const NodeResponse rp = respond(node, xp, 1, &node.status, depth_);
                    const NodeResponse rm = respond(node, xm, 1, &node.status, depth_);
                    for (unsigned int i = 0; i < n; ++i)
                      local_matrix(i, j) = -node.area *
                                           (nodal_force(rp, axes_[i]) - nodal_force(rm, axes_[i])) /
                                           (2 * h);
                  }
              }
            constraints.distribute_local_to_global(local_matrix, local_residual, dofs, *matrix,
                                                   residual);
            if (kept_valid_)
              {
                Contribution kept;
                for (unsigned int i = 0; i < n; ++i)
                  {
                    kept.dofs[i] = dofs[i];
                    kept.vector[i] = local_residual[i];
                    for (unsigned int j = 0; j < n; ++j)
                      kept.matrix[n * i + j] = local_matrix(i, j);
                  }
                kept_.push_back(kept);
              }
            if (coupling)
              {
                // d(-f)/dh by central differences of the nodal response at the frozen status;
                // F = sum(-f_z), so dF/du is the z row of d(-f)/dx.
                const double   dh = 1e-7 * std::max(1.0, std::abs(depth_));
                const auto     rp = respond(node, node.x, 1, &node.status, depth_ + dh);
                const auto     rm = respond(node, node.x, 1, &node.status, depth_ - dh);
                Vector<double> residual_derivative(n), force_gradient(n);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    residual_derivative[i] =
                        -node.area * (nodal_force(rp, axes_[i]) - nodal_force(rm, axes_[i])) /
                        (2 * dh);
                    force_gradient[i] = local_matrix(n - 1, i);
                  }
                coupling->force_derivative += residual_derivative[n - 1];
                constraints.distribute_local_to_global(residual_derivative, dofs,
                                                       *coupling->residual_derivative);
                constraints.distribute_local_to_global(force_gradient, dofs,
                                                       *coupling->force_gradient);
              }
          }
        else
          constraints.distribute_local_to_global(local_residual, dofs, residual);
      }
  }

  bool NodeToSurfaceContact::retract(const AffineConstraints<double>  &constraints,
                                     PETScWrappers::MPI::Vector       &residual,
                                     PETScWrappers::MPI::SparseMatrix &matrix)
  {
    // A kept node with a constrained dof whose constraint has entries or an inhomogeneity
    // would need the constraint's full treatment undone: then nothing is retracted (on any rank).
    bool possible = kept_valid_;
    for (const Contribution &kept : kept_)
      for (unsigned int k = 0; k < axes_.size(); ++k)
        if (const types::global_dof_index dof = kept.dofs[k];
            constraints.is_constrained(dof) && (constraints.is_inhomogeneously_constrained(dof) ||
                                                !constraints.get_constraint_entries(dof)->empty()))
          possible = false;
    if (Utilities::MPI::min(static_cast<unsigned int>(possible), communicator_) == 0)
      return false;
    const unsigned int                   n = axes_.size();
    FullMatrix<double>                   local_matrix(n, n);
    Vector<double>                       local_residual(n);
    std::vector<types::global_dof_index> dofs(n);
    for (const Contribution &kept : kept_)
      {
        for (unsigned int i = 0; i < n; ++i)
          {
            dofs[i] = kept.dofs[i];
            local_residual[i] = -kept.vector[i];
            for (unsigned int j = 0; j < n; ++j)
              local_matrix(i, j) = -kept.matrix[n * i + j];
          }
        constraints.distribute_local_to_global(local_matrix, local_residual, dofs, matrix,
                                               residual);
        // The diagonal entry a constrained (homogeneous) row received is |K_ii| of the local
        // matrix, or the mean |K_jj| if K_ii = 0 (AffineConstraints::distribute_local_to_global),
        // whatever the sign: the subtraction above added it once more, so take it off twice.
        double mean_diagonal = 0;
        for (unsigned int i = 0; i < n; ++i)
          mean_diagonal += std::abs(local_matrix(i, i));
        mean_diagonal /= n;
        if (mean_diagonal == 0)
          mean_diagonal = local_matrix.l1_norm() / n;
        if (mean_diagonal == 0)
          mean_diagonal = 1;
        for (unsigned int i = 0; i < n; ++i)
          if (constraints.is_constrained(dofs[i]))
            {
              const double diagonal =
                  local_matrix(i, i) != 0 ? std::abs(local_matrix(i, i)) : mean_diagonal;
              matrix.add(dofs[i], dofs[i], -2 * diagonal);
            }
      }
    kept_.clear();
    kept_valid_ = false;
    return true;
  }

  unsigned int NodeToSurfaceContact::n_status_changes() const
  {
    return Utilities::MPI::sum(n_changes_, communicator_);
  }

  double NodeToSurfaceContact::augment(const bool damp_oscillations, const double stiffen_above)
  {
    double largest_change = 0;
    for (ContactNode &node : nodes_)
      {
        largest_change =
            std::max({largest_change, std::abs(node.pressure - node.lambda) * node.area,
                      (node.traction - node.traction_multiplier).norm() * node.area});
        const bool oscillating = damp_oscillations && node.gap * node.gap_at_augmentation < 0;
        // Uzawa reduces a node's gap by the factor K / (K + eps_i A_i) per pass, K the stiffness
        // the node meets: a node far stiffer than its penalty (the apex node of a nearly sharp
        // tip under a pressure of tens of GPa, where the compressed material's tangent grows)
        // crawls toward the tolerance by a few per cent per pass. Where a pass has not reduced
        // the gap fourfold, eps_i is raised fourfold for the rest of the increment (at most
        // max_penalty_raise times): the multipliers, and so the converged answer, stay those of
        // the conditions.
        const bool held_to_surface = node.active || node.gap < 0; // its gap must vanish
        if (held_to_surface && std::abs(node.gap) > stiffen_above &&
            node.gap * node.gap_at_augmentation > 0 &&
            std::abs(node.gap) > 0.25 * std::abs(node.gap_at_augmentation) &&
            node.penalty < max_penalty_raise * node.penalty_initial)
          node.penalty *= 4;
        // The Uzawa update projected onto lambda >= 0: a node held in tension gets none.
        const double pressure = std::max(node.pressure, 0.0);
        node.lambda = oscillating ? 0.5 * (node.lambda + pressure) : pressure;
        node.traction_multiplier = node.traction;
        node.gap_at_augmentation = node.gap;
      }
    return Utilities::MPI::max(largest_change, communicator_);
  }

  double NodeToSurfaceContact::augmentation_jump() const
  {
    double sum_of_squares = 0;
    for (const ContactNode &node : nodes_)
      sum_of_squares +=
          ((node.pressure - node.lambda) * node.normal + node.traction - node.traction_multiplier)
              .norm_square() *
          node.area * node.area;
    return std::sqrt(Utilities::MPI::sum(sum_of_squares, communicator_));
  }

  void NodeToSurfaceContact::accept_increment()
  {
    // The converged pressures and tractions are the multipliers of the next increment (a last
    // Uzawa update): its predictor then starts from the active set that carries load now, not
    // from a node that has left the indenter since the last augmentation.
    for (ContactNode &node : nodes_)
      {
        node.lambda = std::max(node.pressure, 0.0);
        node.traction_multiplier = node.traction;
        node.lambda_previous = node.lambda_converged;
        node.lambda_converged = node.lambda;
        node.traction_multiplier_converged = node.traction_multiplier;
        node.x_converged = node.x;
        node.gap_at_augmentation = 0;
        node.penalty = node.penalty_initial;
      }
    depth_converged_ = depth_;
    offset_converged_ = offset_;
  }

  void NodeToSurfaceContact::extrapolate_multipliers(const double ratio)
  {
    for (ContactNode &node : nodes_)
      if (node.lambda_converged > 0 && node.lambda_previous > 0)
        node.lambda = std::max(0.0, node.lambda_converged +
                                        ratio * (node.lambda_converged - node.lambda_previous));
  }

  void NodeToSurfaceContact::reject_increment()
  {
    for (ContactNode &node : nodes_)
      {
        node.lambda = node.lambda_converged;
        node.traction_multiplier = node.traction_multiplier_converged;
        node.gap_at_augmentation = 0;
        node.penalty = node.penalty_initial;
      }
  }

  namespace
  {
    constexpr std::size_t n_values_per_node = 28, n_global_values = 10;
  } // namespace

  std::vector<double> NodeToSurfaceContact::persistent_state() const
  {
    std::vector<double> state;
    state.reserve(n_global_values + n_values_per_node * nodes_.size());
    const auto put = [&state](const Tensor<1, 3> &t) {
      for (unsigned int d = 0; d < 3; ++d)
        state.push_back(t[d]);
    };
    state.push_back(depth_);
    state.push_back(depth_converged_);
    put(offset_);
    put(offset_converged_);
    state.push_back(n_changes_);
    state.push_back(search_failed_ ? 1 : 0);
    for (const ContactNode &node : nodes_)
      {
        state.push_back(node.lambda);
        state.push_back(node.lambda_converged);
        state.push_back(node.lambda_previous);
        put(node.traction_multiplier);
        put(node.traction_multiplier_converged);
        put(node.x_converged);
        state.push_back(node.gap);
        state.push_back(node.pressure);
        state.push_back(node.active ? 1 : 0);
        state.push_back(static_cast<double>(node.status));
        put(node.normal);
        put(node.traction);
        put(node.slip);
        put(node.x);
      }
    return state;
  }

  void NodeToSurfaceContact::restore_state(const std::vector<double> &state)
  {
    if (state.size() != n_global_values + n_values_per_node * nodes_.size())
      throw std::runtime_error("the contact state of the checkpoint has " +
                               std::to_string(state.size()) + " values, this rank's " +
                               std::to_string(nodes_.size()) + " contact nodes need " +
                               std::to_string(n_global_values + n_values_per_node * nodes_.size()));
    std::size_t i = 0;
    const auto  get = [&state, &i]() { return state[i++]; };
    const auto  get_tensor = [&get](auto &t) {
      for (unsigned int d = 0; d < 3; ++d)
        t[d] = get();
    };
    depth_ = get();
    depth_converged_ = get();
    get_tensor(offset_);
    get_tensor(offset_converged_);
    n_changes_ = static_cast<unsigned int>(get());
    search_failed_ = get() != 0;
    for (ContactNode &node : nodes_)
      {
        node.lambda = get();
        node.lambda_converged = get();
        node.lambda_previous = get();
        get_tensor(node.traction_multiplier);
        get_tensor(node.traction_multiplier_converged);
        get_tensor(node.x_converged);
        node.gap = get();
        node.pressure = get();
        node.active = get() != 0;
        node.status = static_cast<ContactStatus>(static_cast<unsigned char>(get()));
        get_tensor(node.normal);
        get_tensor(node.traction);
        get_tensor(node.slip);
        get_tensor(node.x);
      }
  }

  ContactSummary NodeToSurfaceContact::summary() const
  {
    ContactSummary s;
    double         local_force = 0, local_area = 0, local_radius = 0, local_penetration = 0;
    double         local_stick_slip = 0, local_pressure = 0, local_active_gap = 0;
    Tensor<1, 3>   local_force_vector;
    unsigned int   local_active = 0, local_stick = 0, local_slip = 0;
    for (const ContactNode &node : nodes_)
      {
        local_penetration = std::max(local_penetration, -node.gap);
        // A node held active (free mode within a pass) or frozen may carry tension; it must
        // still lie on the indenter for the conditions to hold.
        if (node.active)
          local_active_gap = std::max(local_active_gap, std::abs(node.gap));
        if (node.pressure <= 0)
          continue;
        local_force += -node.pressure * node.area * node.normal[2] - node.area * node.traction[2];
        local_force_vector += node.area * (node.pressure * node.normal + node.traction);
        local_area += node.area;
        local_pressure = std::max(local_pressure, node.pressure);
        local_radius = std::max(local_radius, std::hypot(node.x[0], node.x[1]));
        ++local_active;
        if (node.status == ContactStatus::stick)
          {
            ++local_stick;
            local_stick_slip = std::max(local_stick_slip, node.slip.norm());
          }
        else
          ++local_slip;
      }
    s.force_z = Utilities::MPI::sum(local_force, communicator_);
    for (unsigned int d = 0; d < 3; ++d)
      s.force_on_specimen[d] = Utilities::MPI::sum(local_force_vector[d], communicator_);
    s.contact_area = Utilities::MPI::sum(local_area, communicator_);
    s.contact_radius = Utilities::MPI::max(local_radius, communicator_);
    s.max_penetration = Utilities::MPI::max(local_penetration, communicator_);
    s.max_stick_slip = Utilities::MPI::max(local_stick_slip, communicator_);
    s.max_pressure = Utilities::MPI::max(local_pressure, communicator_);
    s.max_active_gap = Utilities::MPI::max(local_active_gap, communicator_);
    s.n_active = Utilities::MPI::sum(local_active, communicator_);
    s.n_stick = Utilities::MPI::sum(local_stick, communicator_);
    s.n_slip = Utilities::MPI::sum(local_slip, communicator_);
    s.search_failed =
        Utilities::MPI::max(static_cast<unsigned int>(search_failed_), communicator_) > 0;
    return s;
  }

  double NodeToSurfaceContact::min_gap() const
  {
    double local = std::numeric_limits<double>::max();
    for (const ContactNode &node : nodes_)
      local = std::min(local, node.gap);
    return Utilities::MPI::min(local, communicator_);
  }

  double NodeToSurfaceContact::total_area() const
  {
    double local = 0;
    for (const ContactNode &node : nodes_)
      local += node.area;
    return Utilities::MPI::sum(local, communicator_);
  }
} // namespace indentsim::contact
