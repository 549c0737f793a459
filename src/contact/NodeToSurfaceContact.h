// Frictionless node-to-surface contact between the specimen's top face and a rigid analytic
// indenter, enforced by the augmented Lagrangian. Units: um, mN, GPa.
//
// Each slave node i on the top face carries a tributary (Lobatto, nodal-quadrature) area A_i in
// the reference configuration and a Lagrange multiplier lambda_i >= 0 (nominal contact pressure,
// GPa). With the signed gap g_i from the closest-point projection onto the indenter and the
// penalty (augmentation) parameter eps, the Alart–Curnier augmented pressure is
//   p_i = < lambda_i - eps g_i >_+ ,
// and node i receives the force p_i A_i n_i (n_i the indenter's outward normal). The residual
// contribution is -p_i A_i n_i, its tangent eps A_i n_i (x) n_i - p_i A_i dn/dx for active nodes.
// For fixed multipliers, Newton converges to the penalty solution; the Uzawa update
// lambda_i <- p_i then drives the gaps of the active nodes to zero, so that the impenetrability
// conditions (paper eq. 17) g >= 0, p >= 0, p g = 0 hold to the requested tolerance.
//
// The class never knows which material lies underneath.
#pragma once

#include "indenter/IndenterSurface.h"

#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <array>
#include <vector>

namespace indentsim::contact
{
  using dealii::Point;
  using dealii::Tensor;

  struct ContactNode
  {
    std::array<dealii::types::global_dof_index, 3> dofs; // x, y, z displacement dofs
    Point<3>                                       X;    // reference position [um]
    double area = 0;          // tributary reference area [um^2]
    double lambda = 0;        // multiplier (nominal pressure) [GPa]
    double lambda_converged = 0; // multiplier of the last converged increment
    // State at the last evaluation.
    double       gap = 0;      // [um]
    double       pressure = 0; // augmented pressure p [GPa]
    bool         active = false;
    Tensor<1, 3> normal;
    Point<3>     x;            // current position [um]
  };

  struct ContactSummary
  {
    double       force_z = 0;         // total indenter force (z, positive pushing down) [mN]
    double       max_penetration = 0; // max(-g) over all nodes, >= 0 [um]
    double       contact_area = 0;    // sum of tributary areas of active nodes [um^2]
    double       contact_radius = 0;  // largest radial distance of an active node [um]
    unsigned int n_active = 0;
    bool         search_failed = false;
  };

  class NodeToSurfaceContact
  {
  public:
    NodeToSurfaceContact(const indenter::IndenterSurface &surface, double penalty);

    // Collects the locally owned top-face nodes inside the footprint |x| <= half_x,
    // |y| <= half_y and their tributary areas. Hanging nodes (constrained x dof) are excluded.
    void setup(const dealii::DoFHandler<3>            &dof_handler,
               const dealii::AffineConstraints<double> &hanging_node_constraints,
               dealii::types::boundary_id               top_boundary,
               double                                   half_x,
               double                                   half_y,
               MPI_Comm                                 communicator);

    // Evaluates gaps and augmented pressures for displacement `u` (ghosted) at indenter depth.
    // In `predictor` mode, the active set is that of the last converged increment and the pressure
    // of its nodes is not clipped at zero: the first Newton iteration of an increment then moves
    // the contact zone with the indenter (loading and unloading alike) instead of releasing it.
    // Returns false if a closest-point projection failed on this rank.
    // With `frozen`, the active set of the previous evaluation is kept (pressures unclipped):
    // the Newton driver freezes it when the semi-smooth iteration cycles between active sets.
    enum class ActiveSet
    {
      free,      // active where the augmented pressure is positive
      predictor, // active where the last converged increment was active
      frozen     // as in the previous evaluation
    };
    bool evaluate(const dealii::PETScWrappers::MPI::Vector &u, double depth,
                  ActiveSet mode = ActiveSet::free);

    // Number of nodes (global) whose status differs between the last two evaluations.
    unsigned int n_status_changes() const;

    // Adds residual -p A n and tangent for the active nodes through `constraints`.
    void assemble(const dealii::AffineConstraints<double>   &constraints,
                  dealii::PETScWrappers::MPI::Vector        &residual,
                  dealii::PETScWrappers::MPI::SparseMatrix  *matrix) const;

    // Uzawa update lambda <- p; returns the largest change of lambda*area [mN] (global).
    double augment();

    // Accept / reject the current increment's multipliers.
    void accept_increment();
    void reject_increment();

    ContactSummary summary() const; // global (MPI-summed) values
    const std::vector<ContactNode> &nodes() const { return nodes_; }
    double penalty() const { return penalty_; }
    double total_area() const;      // global tributary area of all contact nodes [um^2]

  private:
    const indenter::IndenterSurface &surface_;
    double                           penalty_;
    std::vector<ContactNode>         nodes_;
    MPI_Comm                         communicator_ = MPI_COMM_SELF;
    bool                             search_failed_ = false;
    double                           depth_ = 0; // indenter depth of the last evaluate() [um]
    unsigned int                     n_changes_ = 0; // local status changes of the last evaluate()
  };
} // namespace indentsim::contact
