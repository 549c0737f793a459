#include "contact/NodeToSurfaceContact.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cmath>
#include <map>

namespace indentsim::contact
{
  using namespace dealii;

  NodeToSurfaceContact::NodeToSurfaceContact(const indenter::IndenterSurface &surface,
                                             const double                     penalty)
    : surface_(surface)
    , penalty_(penalty)
  {}

  void NodeToSurfaceContact::setup(const DoFHandler<3>             &dof_handler,
                                   const AffineConstraints<double> &hanging_node_constraints,
                                   const types::boundary_id         top_boundary,
                                   const double                     half_x,
                                   const double                     half_y,
                                   const MPI_Comm                   communicator)
  {
    communicator_ = communicator;
    nodes_.clear();
    const IndexSet &owned = dof_handler.locally_owned_dofs();

    // Tributary areas by nodal (Lobatto) quadrature of the top faces: each vertex of a
    // rectangular face receives a quarter of its area. Faces owned by other ranks contribute to
    // our nodes through the compress(add).
    PETScWrappers::MPI::Vector area(owned, communicator);
    std::map<types::global_dof_index, ContactNode> found;
    const double tol = 1e-8 * (half_x + half_y);
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
                if (!owned.is_element(dof_x) || hanging_node_constraints.is_constrained(dof_x))
                  continue;
                ContactNode node;
                for (unsigned int d = 0; d < 3; ++d)
                  node.dofs[d] = face->vertex_dof_index(v, d);
                node.X = face->vertex(v);
                found.emplace(dof_x, node);
              }
          }
      }
    area.compress(VectorOperation::add);
    for (auto &[dof_x, node] : found)
      {
        node.area = area(node.dofs[2]);
        nodes_.push_back(node);
      }
  }

  bool NodeToSurfaceContact::evaluate(const PETScWrappers::MPI::Vector &u,
                                      const double                      depth,
                                      const ActiveSet                   mode)
  {
    n_changes_ = 0;
    search_failed_ = false;
    depth_ = depth;
    for (ContactNode &node : nodes_)
      {
        for (unsigned int d = 0; d < 3; ++d)
          node.x[d] = node.X[d] + u(node.dofs[d]);
        const indenter::SurfaceProjection projection = surface_.project(node.x, depth);
        if (!projection.converged || !std::isfinite(projection.gap))
          {
            search_failed_ = true;
            node.pressure = 0;
            node.active = false;
            continue;
          }
        node.gap = projection.gap;
        node.normal = projection.normal;
        const double augmented = node.lambda - penalty_ * node.gap;
        const bool was_active = node.active;
        if (mode == ActiveSet::predictor)
          node.active = node.lambda_converged > 0;
        else if (mode == ActiveSet::free)
          node.active = augmented > 0;
        n_changes_ += (node.active != was_active);
        node.pressure = node.active ? augmented : 0.0;
      }
    return !search_failed_;
  }

  void NodeToSurfaceContact::assemble(const AffineConstraints<double>     &constraints,
                                      PETScWrappers::MPI::Vector          &residual,
                                      PETScWrappers::MPI::SparseMatrix    *matrix) const
  {
    FullMatrix<double>                   local_matrix(3, 3);
    Vector<double>                       local_residual(3);
    std::vector<types::global_dof_index> dofs(3);
    for (const ContactNode &node : nodes_)
      {
        if (!node.active)
          continue;
        const double force = node.pressure * node.area; // [mN]
        for (unsigned int d = 0; d < 3; ++d)
          {
            local_residual[d] = -force * node.normal[d];
            dofs[d] = node.dofs[d];
          }
        if (matrix)
          {
            // d(-p A n)/dx = eps A n (x) n - p A dn/dx. The derivative of the normal (the
            // Hessian of the signed distance, i.e. the indenter's curvature) is taken by central
            // differences of the exact closest-point projection.
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                local_matrix(i, j) = penalty_ * node.area * node.normal[i] * node.normal[j];
            const double h = 1e-7 * std::max(1.0, node.x.norm());
            for (unsigned int j = 0; j < 3; ++j)
              {
                Point<3> xp = node.x, xm = node.x;
                xp[j] += h;
                xm[j] -= h;
                const auto pp = surface_.project(xp, depth_);
                const auto pm = surface_.project(xm, depth_);
                for (unsigned int i = 0; i < 3; ++i)
                  local_matrix(i, j) -= force * (pp.normal[i] - pm.normal[i]) / (2 * h);
              }
            constraints.distribute_local_to_global(
              local_matrix, local_residual, dofs, *matrix, residual);
          }
        else
          constraints.distribute_local_to_global(local_residual, dofs, residual);
      }
  }

  unsigned int NodeToSurfaceContact::n_status_changes() const
  {
    return Utilities::MPI::sum(n_changes_, communicator_);
  }

  double NodeToSurfaceContact::augment()
  {
    double largest_change = 0;
    for (ContactNode &node : nodes_)
      {
        largest_change =
          std::max(largest_change, std::abs(node.pressure - node.lambda) * node.area);
        node.lambda = node.pressure;
      }
    return Utilities::MPI::max(largest_change, communicator_);
  }

  void NodeToSurfaceContact::accept_increment()
  {
    for (ContactNode &node : nodes_)
      node.lambda_converged = node.lambda;
  }

  void NodeToSurfaceContact::reject_increment()
  {
    for (ContactNode &node : nodes_)
      node.lambda = node.lambda_converged;
  }

  ContactSummary NodeToSurfaceContact::summary() const
  {
    ContactSummary s;
    double         local_force = 0, local_area = 0, local_radius = 0, local_penetration = 0;
    unsigned int   local_active = 0;
    for (const ContactNode &node : nodes_)
      {
        local_penetration = std::max(local_penetration, -node.gap);
        if (node.pressure <= 0)
          continue;
        local_force += -node.pressure * node.area * node.normal[2];
        local_area += node.area;
        local_radius = std::max(local_radius, std::hypot(node.x[0], node.x[1]));
        ++local_active;
      }
    s.force_z = Utilities::MPI::sum(local_force, communicator_);
    s.contact_area = Utilities::MPI::sum(local_area, communicator_);
    s.contact_radius = Utilities::MPI::max(local_radius, communicator_);
    s.max_penetration = Utilities::MPI::max(local_penetration, communicator_);
    s.n_active = Utilities::MPI::sum(local_active, communicator_);
    s.search_failed =
      Utilities::MPI::max(static_cast<unsigned int>(search_failed_), communicator_) > 0;
    return s;
  }

  double NodeToSurfaceContact::total_area() const
  {
    double local = 0;
    for (const ContactNode &node : nodes_)
      local += node.area;
    return Utilities::MPI::sum(local, communicator_);
  }
} // namespace indentsim::contact
