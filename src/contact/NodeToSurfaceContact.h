// Node-to-surface contact between the specimen's top face and a rigid analytic indenter,
// frictionless or with Coulomb friction (paper eqs. 17-18), enforced by the augmented Lagrangian.
// Units: um, mN, GPa.
//
// Each slave node i on the top face carries a tributary (Lobatto, nodal-quadrature) area A_i in
// the reference configuration, a normal multiplier lambda_i >= 0 (nominal contact pressure, GPa)
// and, with friction, a tangential multiplier t_i (nominal traction in the tangent plane, GPa).
//
// Normal part (Alart–Curnier). With the signed gap g_i from the closest-point projection onto
// the indenter and the penalty (augmentation) parameter eps,
//   p_i = < lambda_i - eps g_i >_+ .
// Tangential part (Coulomb, backward Euler over the increment). With the relative slip of the
// node against the rigid indenter over the increment, s = (x - x_n) - (w - w_n) (w the indenter
// position), its tangential part s_T = (I - n (x) n) s and the trial traction
//   t_trial = (I - n (x) n) t_i - eps s_T ,
// the node sticks if |t_trial| <= mu p_i (t = t_trial) and slips otherwise
// (t = mu p_i t_trial / |t_trial|): the return onto the Coulomb cone.
// Node i receives the force f_i = A_i (p_i n_i + t_i); the residual contribution is -f_i.
//
// For fixed multipliers, Newton converges to the penalty solution; the Uzawa update
// lambda_i <- p_i, t_i <- t then drives the gaps of the active nodes and the slips of the
// sticking nodes to zero, so that the conditions of eqs. 17-18 (g >= 0, p >= 0, p g = 0;
// |t| <= mu p, stick without slip, slip opposite to t) hold to the requested tolerance. The
// penalty only sets the convergence rate of these passes, not the converged answer: the user
// tunes nothing.
//
// Axisymmetric model: the nodes of the (r, z) section's top edge, placed in the 3D frame at
// (r, 0, z) (the meridian plane y = 0), where the axisymmetric indenter's projection, normal and
// tangent plane restricted to the meridian are those of the 3D formulation; friction slips
// along the meridian. A node's area is then the whole ring's, A_i = integral of N_i 2 pi r ds
// over its top edges, so that f_i is the ring's force and the forces sum to the whole indent's.
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
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace indentsim::contact
{
  using dealii::Point;
  using dealii::Tensor;

  // Contact status of a node: open (no contact), stick or slip. Frictionless contact nodes slip.
  enum class ContactStatus : unsigned char
  {
    open = 0,
    stick = 1,
    slip = 2
  };

  struct ContactNode
  {
    // Displacement dofs of the model's components: x, y, z (3D) or r, z (axisymmetric, the
    // third unused); component k moves the 3D coordinate axis(k) (NodeToSurfaceContact::axes).
    std::array<dealii::types::global_dof_index, 3> dofs;
    Point<3>                                       X; // reference position [um]
    bool   on_axis = false; // held on the indenter's axis (NodeToSurfaceContact::axis_projection)
    double area = 0;        // tributary reference area [um^2] (axisymmetric: of the whole ring)
    double penalty = 0;     // augmentation parameter eps_i [GPa/um] (raised by augment())
    double penalty_initial = 0;                 // eps_i at the start of every increment [GPa/um]
    double lambda = 0;                          // normal multiplier (nominal pressure) [GPa]
    double lambda_converged = 0;                // normal multiplier of the last converged increment
    double lambda_previous = 0;                 // ... and of the one before
    Tensor<1, 3> traction_multiplier;           // tangential multiplier t_i [GPa]
    Tensor<1, 3> traction_multiplier_converged; // t_i of the last converged increment
    Point<3>     x_converged;                   // position at the last converged increment [um]
    // State at the last evaluation.
    double gap = 0;      // [um]
    double pressure = 0; // augmented pressure p [GPa]
    bool   active = false;
    bool   held = false; // active in an earlier free evaluation of this Newton pass (kept active)
    ContactStatus status = ContactStatus::open;
    Tensor<1, 3>  normal;
    Tensor<1, 3>  traction;                // tangential traction t on the node [GPa]
    Tensor<1, 3>  slip;                    // tangential slip s_T over the increment [um]
    double        gap_at_augmentation = 0; // gap at the last Uzawa update of the increment [um]
    Point<3>      x;                       // current position [um]
  };

  struct ContactSummary
  {
    double       force_z = 0;         // total indenter force (z, positive pushing down) [mN]
    Tensor<1, 3> force_on_specimen;   // total contact force the indenter exerts [mN]
    double       max_penetration = 0; // max(-g) over all nodes, >= 0 [um]
    double       max_active_gap = 0;  // max |g| over the active nodes (0 at convergence) [um]
    double       max_stick_slip = 0;  // max |s_T| over sticking nodes (0 at convergence) [um]
    double       max_pressure = 0;    // largest nodal pressure p [GPa]
    double       contact_area = 0;    // sum of tributary areas of active nodes [um^2]
    double       contact_radius = 0;  // largest radial distance of an active node [um]
    unsigned int n_active = 0;
    unsigned int n_stick = 0;
    unsigned int n_slip = 0;
    bool         search_failed = false;

    // Eqs. 17-18 to `tolerance` [um]: no node penetrates, no node carrying pressure stands off
    // the indenter, no sticking node slips.
    bool conditions_met(const double tolerance) const
    {
      return max_penetration <= tolerance && max_active_gap <= tolerance &&
             max_stick_slip <= tolerance;
    }
  };

  class NodeToSurfaceContact
  {
  public:
    // friction_coefficient: Coulomb mu >= 0 (0: frictionless).
    NodeToSurfaceContact(const indenter::IndenterSurface &surface, double penalty,
                         double friction_coefficient = 0.0);

    // eps_i = stiffness / L_i, L_i the mean edge of the top faces at node i, instead of the
    // constructor's uniform penalty (call before setup). On a graded mesh a uniform eps is stiff
    // against the large elements and soft against the small ones, where the augmentation passes
    // then converge slowly; stiffness = c E keeps eps_i L_i / E = c on every node.
    void set_local_penalty(double stiffness);

    // Collects the locally owned top-face nodes inside the footprint |x| <= half_x,
    // |y| <= half_y and their tributary areas. Hanging nodes (constrained x dof) are excluded.
    // `axis_held`: the model holds the node on the axis x = y = 0 there (the quarter model's
    // two symmetry planes), which then moves along the axis only (axis_projection).
    void setup(const dealii::DoFHandler<3>             &dof_handler,
               const dealii::AffineConstraints<double> &hanging_node_constraints,
               dealii::types::boundary_id top_boundary, double half_x, double half_y,
               MPI_Comm communicator, bool axis_held = false);
    // The same for the axisymmetric (r, z) section: the top-edge nodes with r <= half_x, their
    // ring areas integral of N_i 2 pi r ds (exact for the linear edge).
    void setup(const dealii::DoFHandler<2>             &dof_handler,
               const dealii::AffineConstraints<double> &hanging_node_constraints,
               dealii::types::boundary_id top_boundary, double half_x, MPI_Comm communicator);
    // The 3D coordinate axes the model's displacement components move: {0, 1, 2} or {0, 2}.
    const std::vector<unsigned int> &axes() const { return axes_; }

    // Penetration [um] beyond which a node outside the last converged active set is active in
    // `predictor` mode (see evaluate); 0 until set. IndentationProblem sets the contact
    // tolerance.
    void set_predictor_activation_depth(const double depth) { predictor_activation_depth_ = depth; }

    // Lateral (x, y) position of the indenter axis [um]; 0 unless a test slides the indenter.
    void set_lateral_offset(const Tensor<1, 3> &offset);

    // Evaluates gaps, pressures and tractions for displacement `u` (ghosted) at indenter depth.
    // In `predictor` mode, the normal active set is that of the last converged increment, and
    // the pressure of its nodes is not clipped at zero: the first Newton iteration of an
    // increment then moves the contact zone with the indenter (loading and unloading alike)
    // instead of releasing it. A node outside that set joins it where the predicted state
    // penetrates by more than the predictor activation depth: the ring of nodes the indenter
    // reaches in this increment then enters with the first Newton iteration, instead of
    // penetrating freely in it and being pushed back in the next. In `free` mode a node that was
    // active in an earlier free evaluation of the same Newton pass stays active (held; its
    // pressure unclipped) until start_pass: within a pass the active set only grows, so the
    // semi-smooth iteration cannot cycle by releasing a node and capturing it again. A held node
    // that would separate ends the pass with an active gap; the augmentation then clears its
    // multiplier, and the next pass releases it. With `frozen`, the statuses of the previous
    // evaluation are kept (pressures unclipped): the Newton driver freezes them when the
    // iteration still cycles.
    // Returns false if a closest-point projection failed on this rank.
    enum class ActiveSet
    {
      free,      // active where the augmented pressure is positive or the node is held,
                 // stick/slip by the cone
      predictor, // active where the last converged increment was active
      frozen     // as in the previous evaluation
    };
    bool evaluate(const dealii::PETScWrappers::MPI::Vector &u, double depth,
                  ActiveSet mode = ActiveSet::free);

    // Releases the nodes held active by the last Newton pass: call when a pass begins.
    void start_pass();

    // Restores the active set, the statuses and the holds from before the last evaluate(): the
    // Newton driver calls it when its line search rejects an iterate. The nodes a rejected full
    // step pushed into the indenter then neither stay held for the rest of the pass nor join a
    // frozen set, where away from the indenter their unclipped pressure would pull on them.
    void reject_last_evaluation();

    // Number of nodes (global) whose status differs between the last two evaluations.
    unsigned int n_status_changes() const;

    // Force control couples the indenter depth h into the Newton system: the derivative of the
    // contact residual with respect to h, the gradient of the indenter force F (force_z) with
    // respect to the nodal displacements, and dF/dh (this rank's nodes; the caller sums).
    struct DepthCoupling
    {
      dealii::PETScWrappers::MPI::Vector *residual_derivative = nullptr; // dR/dh [mN/um]
      dealii::PETScWrappers::MPI::Vector *force_gradient = nullptr;      // dF/du [mN/um]
      double                              force_derivative = 0;          // dF/dh [mN/um]
    };

    // Adds residual -f and tangent for the active nodes through `constraints`; with `coupling`
    // (and a matrix), also the depth coupling of force control.
    // Without coupling, the contributions added to the matrix are also kept, for retract().
    void assemble(const dealii::AffineConstraints<double>  &constraints,
                  dealii::PETScWrappers::MPI::Vector       &residual,
                  dealii::PETScWrappers::MPI::SparseMatrix *matrix,
                  DepthCoupling                            *coupling = nullptr);

    // Subtracts what the last assemble() with a matrix and without coupling added to `residual`
    // and `matrix` (both compressed since): after an augmentation at an unchanged displacement,
    // the element part of the system stands and only the contact part is replaced. Returns
    // false (and changes nothing, on every rank) if there is nothing kept to subtract, or if a
    // kept dof has a constraint with entries or an inhomogeneity (only homogeneous ones such as
    // the symmetry planes' are undone exactly). Collective.
    bool retract(const dealii::AffineConstraints<double>  &constraints,
                 dealii::PETScWrappers::MPI::Vector       &residual,
                 dealii::PETScWrappers::MPI::SparseMatrix &matrix);

    // Smallest gap over the nodes at the last evaluation (global) [um].
    double min_gap() const;

    // Uzawa update lambda <- p, t_i <- t; returns the largest change of the nodal force [mN]
    // (global). With `damp_oscillations`, a node whose gap changed sign since the last update
    // (penetrating, then standing off under its multiplier, or the reverse) takes the mean
    // lambda <- (lambda + p)/2: a node at the edge of the contact can otherwise alternate between
    // the two states forever (the fixed point, and so the converged answer, is the same).
    // A node whose gap beyond `stiffen_above` [um] the last pass did not reduce fourfold gets a
    // fourfold penalty until the increment ends (at most max_penalty_raise times its own).
    double                  augment(bool   damp_oscillations = false,
                                    double stiffen_above = std::numeric_limits<double>::infinity());
    static constexpr double max_penalty_raise = 1024;

    // The residual change the next augment() would make: the l2 norm over the nodes of the
    // nodal force change A_i |(p_i - lambda_i) n_i + t_i - t^lambda_i| (global) [mN].
    double augmentation_jump() const;

    // Predictor of the normal multipliers: lambda = lambda_n + ratio (lambda_n - lambda_{n-1})
    // on the nodes that carried pressure in both of the last two increments, so that the first
    // augmentation pass starts from the pressure the increment is heading for.
    void extrapolate_multipliers(double ratio);

    // Accept / reject the current increment's multipliers and positions.
    void accept_increment();
    void reject_increment();

    // Everything that persists between increments (multipliers, stick anchors, active status,
    // the last evaluation), flattened for a checkpoint of a stopped run, and its restoration
    // into a contact set up on the same mesh and partition. restore_state throws
    // std::runtime_error if the size does not match this rank's nodes.
    std::vector<double> persistent_state() const;
    void                restore_state(const std::vector<double> &state);

    ContactSummary                  summary() const; // global (MPI-summed) values
    const std::vector<ContactNode> &nodes() const { return nodes_; }
    // The smallest and largest eps_i over all nodes [GPa/um].
    std::pair<double, double> penalty_range() const;
    double                    friction_coefficient() const { return mu_; }
    // The contact tangent is symmetric only without friction (the Coulomb return is not).
    bool   symmetric_tangent() const { return mu_ == 0.0; }
    double total_area() const; // global tributary area of all contact nodes [um^2]

  private:
    // Pressure, traction and status of `node` placed at `x`. normal_active: -1 decides by the
    // augmented pressure, 0/1 imposes it (pressure then unclipped); with `fixed_status`, stick or
    // slip is imposed (frozen set, tangent by differences) instead of decided.
    struct NodeResponse
    {
      indenter::SurfaceProjection projection;
      double                      pressure = 0;
      Tensor<1, 3>                traction, slip;
      ContactStatus               status = ContactStatus::open;
    };
    NodeResponse respond(const ContactNode &node, const Point<3> &x, int normal_active,
                         const ContactStatus *fixed_status, double depth) const;
    // The gap, closest point and normal of a node held on the indenter's axis (the axisymmetric
    // model's axis, u_r = 0, or the quarter model's edge x = y = 0) at `x`, the indenter at
    // `depth`: the node moves along the axis only; its gap is the vertical distance to the
    // indenter's profile there, its normal the axis (-z). At a smooth tip this is the
    // closest-point projection; at a sharp apex (a cone or pyramid with tip_radius 0) that
    // projection jumps from the apex (normal along the axis, the node just outside) to a flank
    // (normal tilted by the half-angle, the node just inside), so that the node's force jumps
    // where the contact holds it, on the apex, and Newton's method cycles between the two
    // sides. Both gaps vanish at the same position: the contact condition is the same.
    indenter::SurfaceProjection axis_projection(const Point<3> &x, double depth) const;

    // Keeps the found nodes, in the order of their first dof, with their areas from `area` and
    // their penalties from the sums of their faces' edges and the number of faces.
    void store_nodes(std::map<dealii::types::global_dof_index, ContactNode> &found,
                     dealii::PETScWrappers::MPI::Vector                     &area,
                     dealii::PETScWrappers::MPI::Vector                     &edge_sum,
                     dealii::PETScWrappers::MPI::Vector                     &faces);

    const indenter::IndenterSurface &surface_;
    std::vector<unsigned int>        axes_ = {0, 1, 2};
    double                           penalty_;
    double                           local_penalty_stiffness_ = 0; // 0: the uniform penalty_
    double                           mu_;
    double                           predictor_activation_depth_ = 0; // [um]
    std::vector<ContactNode>         nodes_;
    MPI_Comm                         communicator_ = MPI_COMM_SELF;
    bool                             search_failed_ = false;
    double                           depth_ = 0; // indenter depth of the last evaluate() [um]
    double                           depth_converged_ = 0;
    Tensor<1, 3>                     offset_, offset_converged_; // lateral indenter position
    unsigned int                     n_changes_ = 0; // local status changes of the last evaluate()
    // Per node, the status, activity and hold before the last evaluate() (reject_last_evaluation).
    struct StatusBefore
    {
      ContactStatus status;
      bool          active, held;
    };
    std::vector<StatusBefore> before_last_;
    // What the last assemble() with a matrix and without coupling added, node by node (retract).
    struct Contribution
    {
      std::array<dealii::types::global_dof_index, 3> dofs;
      std::array<double, 9>                          matrix; // row-major n x n (n components)
      std::array<double, 3>                          vector;
    };
    std::vector<Contribution> kept_;
    bool                      kept_valid_ = false;
  };
} // namespace indentsim::contact
