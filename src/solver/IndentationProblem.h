// Depth-controlled indentation of a block by a rigid indenter: the finite-strain quasi-static
// boundary-value problem, its Newton solver with augmented-Lagrangian contact, the load stepper
// with cut-back, and the outputs. Units: um, mN, GPa.
//
// Constraints are layered as in deal.II's step-42: hanging-node constraints, then
// Dirichlet-and-hanging constraints (bottom face fixed, symmetry planes of the quarter model);
// all are homogeneous, so the Newton updates use the same object. The lateral faces are
// traction-free. Contact enters as nodal forces (see contact/NodeToSurfaceContact.h).
#pragma once

#include "contact/ContactArea.h"
#include "contact/NodeToSurfaceContact.h"
#include "indenter/IndenterSurface.h"
#include "case/Case.h"
#include "materials/MaterialModel.h"
#include "mesh/IndentationMesh.h"
#include "solver/CellWorkspace.h"
#include "solver/FiniteStrainElement.h"
#include "solver/IncrementStatus.h"
#include "solver/LinearSolver.h"
#include "solver/MatrixScatter.h"
#include "solver/PileUp.h"
#include "solver/RunStatistics.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <span>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace indentsim::solver
{
  // One row of the load-penetration record. Forces and areas are those of the whole indent
  // (multiplied by 4 for the quarter model).
  struct StepRecord
  {
    unsigned int step = 0;
    unsigned int cycle = 0;           // load-unload cycle of the programme (0: initial state)
    std::string  segment = "start";   // start | load | hold | unload
    double       depth = 0;           // indenter apex depth [um]
    double       force = 0;           // indenter force [mN]
    double       contact_radius = 0;  // largest radius of the interpolated perimeter [um]
    double       contact_area = 0;    // projected area inside the interpolated perimeter [um^2]
    unsigned int n_active_nodes = 0;  // active nodes of the model (not symmetry-multiplied)
    unsigned int n_stick_nodes = 0;   // of them sticking (friction) ...
    unsigned int n_slip_nodes = 0;    // ... and slipping (all of them without friction)
    double       max_pressure = 0;    // largest nodal contact pressure (nominal) [GPa]
    unsigned int newton_iterations = 0;
    unsigned int augmentations = 0;
    unsigned int cutbacks = 0;
    double       max_penetration = 0; // [um]
    double       bottom_reaction = 0; // [mN], whole indent
    double       wall_time = 0;       // [s] since the start of the run
  };

  // The number of steps a loading programme is expected to take without cut-backs (for the
  // ETA): depth-controlled unloading is paced by force and takes about unload_points + 1.
  unsigned int expected_steps(const io::LoadingParameters &loading);

  class IndentationProblem
  {
  public:
    IndentationProblem(const io::Case &the_case, MPI_Comm communicator, bool verbose = true);
    ~IndentationProblem();

    // Builds mesh, dofs, constraints, history and contact nodes.
    void setup();

    enum class RunOutcome
    {
      finished, // the whole programme ran; the end-of-run outputs are written
      stopped   // a stop was requested (SIGINT/SIGTERM or stop_after_step): checkpoint written
    };
    // Runs the whole loading programme; writes outputs into `output_directory` (which must exist)
    // unless it is empty. With an output directory, a checkpoint of the converged state is
    // written into its folder `checkpoint` every output.checkpoint_interval_s seconds and when
    // SIGINT or SIGTERM arrives; then the run stops after the current step (RunOutcome::stopped,
    // no end-of-run outputs). With `resume`, the state is read from that checkpoint (setup()
    // must have built the same case on the same number of ranks; otherwise io::CaseFileError
    // explains why) and the programme continues from it. A finished run removes the checkpoint.
    RunOutcome run(const std::string &output_directory, bool resume = false);
    // Test hook: request a stop after the converged step `step` (as a signal would). The
    // environment variable INDENTSIM_STOP_AFTER_STEP does the same for the command line.
    void stop_after_step(unsigned int step) { stop_after_step_ = step; }

    // Solves one increment to depth `depth` from the last converged state (no cut-back). With
    // `extrapolate`, Newton starts from the linear extrapolation of the last two converged
    // states (when the indenter keeps its direction), else from the last converged state.
    // Force control: with `target_force` [mN, whole indent], the depth is an unknown solved with
    // the displacements (bordered Newton system) and `depth` is its starting guess.
    IncrementStatus solve_increment(double depth, StepRecord &record, bool extrapolate = true,
                                    std::optional<double> target_force = std::nullopt);
    // Force control: the starting depth for the force `target_force` [mN], by the secant of the
    // last two converged states (else the last converged depth).
    double depth_guess_for_force(double target_force) const;
    // Accepts or rejects the increment just solved.
    void accept_increment();
    void reject_increment();

    const std::vector<StepRecord> &records() const { return records_; }
    // Counters and phase times of this problem so far (setup and runs).
    const RunStatistics &statistics() const { return statistics_; }
    const LinearSolver  &linear_solver() const { return linear_solver_; }
    // The contact nodes and their state at the last evaluation.
    const contact::NodeToSurfaceContact &contact() const { return *contact_; }
    // The pile-up analysis of the last run(): stages max_depth and (after unloading) unloaded.
    // Filled on rank 0 when run() was given an output directory, empty otherwise.
    const std::vector<pileup::PileUpResult> &pileup_results() const { return pileup_results_; }

    unsigned int n_cells() const;
    unsigned int n_dofs() const;
    unsigned int n_constrained_dofs() const;
    unsigned int n_hanging_node_constraints() const;
    const mesh::MeshInfo &mesh_info() const { return mesh_info_; }
    double symmetry_factor() const { return mesh_info_.quarter ? 4.0 : 1.0; }
    const dealii::DoFHandler<3> &dof_handler() const { return dof_handler_; }
    const dealii::PETScWrappers::MPI::Vector &solution() const { return solution_; }

    // Sets the displacement to u(X) (for patch tests); hanging-node constraints are applied.
    void set_displacement(const std::function<dealii::Tensor<1, 3>(const dealii::Point<3> &)> &u);
    // Assembles the residual for the current displacement (no contact) and returns its l2 norm
    // over the dofs off the boundary [mN]; max_stress_error returns the largest deviation of the
    // Cauchy stress from `expected_cauchy` over all quadrature points [GPa].
    double interior_residual_norm();
    double max_stress_error(const dealii::Tensor<2, 3> &expected_cauchy);

  private:
    struct AssemblyResult
    {
      materials::UpdateStatus status = materials::UpdateStatus::success;
      double                  bottom_reaction = 0; // z reaction on the bottom face [mN]
    };
    AssemblyResult assemble(bool with_matrix);
    // After an augmentation at an unchanged displacement (and depth): the element part of
    // residual_ and matrix_ (last assembled with the matrix) stands; only the contact part is
    // replaced. Returns false, changing nothing, if the contact kept nothing to replace.
    bool reassemble_contact();
    // With several MPI ranks: repartitions the mesh with the expected plastic zone's cells
    // weighted by the material's relative plastic cost.
    void balance_plastic_zone();
    // Number of constrained dofs owned by this rank, summed over ranks.
    unsigned int count_owned_constraints(const dealii::AffineConstraints<double> &constraints) const;
    std::span<const double> cell_state(const std::vector<double>                        &states,
                                       const dealii::DoFHandler<3>::active_cell_iterator &cell) const;
    std::span<double>       cell_state(std::vector<double>                              &states,
                                       const dealii::DoFHandler<3>::active_cell_iterator &cell) const;

    // Evaluates every locally owned cell at the current displacement from the converged state
    // (no tangent) and passes the Cauchy stress and the updated state of its quadrature points.
    void for_each_cell_stress(
      const std::function<void(const dealii::DoFHandler<3>::active_cell_iterator &,
                               const std::vector<dealii::Tensor<2, 3>> &,
                               std::span<const double>)> &visit);
    void           write_vtu(unsigned int index);
    // The top-face quads (corners with reference X, Y and displacement) of all ranks, gathered
    // on rank 0 (empty elsewhere) and mirrored into the full surface for the quarter model.
    // Collective.
    std::vector<pileup::SurfaceQuad> gather_top_surface() const;
    // Projected contact area and radius of the model (not symmetry-multiplied) from the
    // interpolated contact indicator (contact/ContactArea.h).
    contact::ContactPatch contact_patch() const;
    struct SurfaceSnapshot
    {
      std::string                      stage; // "max_depth" | "unloaded"
      double                           depth = 0; // [um]
      std::vector<pileup::SurfaceQuad> surface;
    };
    // Rank 0: analyses the snapshots (a_c: contact radius at maximum depth), writes pileup.json
    // and the pile-up CSV files, then plots them with python/plot_pileup.py (a failing plot is
    // a warning).
    void write_pileup(const std::vector<SurfaceSnapshot> &snapshots, double contact_radius);

    // Where run() is in the loading programme after a converged step: everything the next
    // step needs besides the fields, histories and contact state of the problem.
    struct LoopState
    {
      unsigned int segment = 0;         // index into the programme
      bool         in_segment = false;  // false: `segment` starts afresh
      double       value = 0, depth = 0; // control value (depth or force) and depth
      double       increment = 0, paced_increment = 0;
      unsigned int easy_steps = 0, segment_steps = 0;
      unsigned int step = 0, total_newton = 0, vtu_index = 0;
      double       max_force = 0, contact_radius_at_max = 0, value_at_max = 0;
      double       wall_time = 0; // of the run so far, earlier sessions included [s]
    };
    // Collective. Writes <output>/checkpoint/rank_<r>.bin (atomically per rank).
    void write_checkpoint(const LoopState &loop, const std::vector<SurfaceSnapshot> &snapshots);
    // Collective. Reads the checkpoint into the problem; throws io::CaseFileError on every rank
    // if any rank's file is missing, of another case, rank count or format.
    void read_checkpoint(LoopState &loop, std::vector<SurfaceSnapshot> &snapshots);
    // The fingerprint of the case as far as it determines the results (io::case_fingerprint,
    // case/Fingerprint.h).
    std::uint64_t case_fingerprint() const;
    std::string   checkpoint_directory() const;
    void           compute_cell_fields(dealii::Vector<float> &von_mises,
                                       dealii::Vector<float> &plastic_strain,
                                       std::vector<dealii::Vector<float>> &cauchy);

    const io::Case                     &case_;
    MPI_Comm                            communicator_;
    dealii::ConditionalOStream          pcout_;
    dealii::parallel::distributed::Triangulation<3> triangulation_;
    mesh::MeshInfo                      mesh_info_;
    dealii::FESystem<3>                 fe_;
    dealii::DoFHandler<3>               dof_handler_;
    dealii::IndexSet                    locally_owned_, locally_relevant_;
    dealii::AffineConstraints<double>   constraints_hanging_;
    dealii::AffineConstraints<double>   constraints_all_; // Dirichlet and hanging nodes

    std::unique_ptr<materials::MaterialModel>     material_;
    std::unique_ptr<indenter::IndenterSurface>    indenter_;
    std::unique_ptr<contact::NodeToSurfaceContact> contact_;
    bool                                          use_f_bar_;

    dealii::PETScWrappers::MPI::SparseMatrix matrix_;
    dealii::PETScWrappers::MPI::Vector       solution_;           // ghosted
    GhostedVector                            solution_readable_;  // its copy for the threads
    dealii::PETScWrappers::MPI::Vector       solution_converged_; // ghosted
    // The converged solution before it (owned) and the depths of both: the predictor of the
    // next increment extrapolates linearly from them.
    dealii::PETScWrappers::MPI::Vector       solution_previous_;
    double depth_converged_ = 0, depth_previous_ = 0, depth_trial_ = 0;
    // Indenter force (whole indent) of the last two converged increments [mN].
    double force_converged_ = 0, force_previous_ = 0, force_trial_ = 0;
    // Set by solve_increment under force control: the assembly then adds the depth coupling.
    contact::NodeToSurfaceContact::DepthCoupling *depth_coupling_ = nullptr;
    // |indenter force| of the model [mN] at the last converged and at the trial state.
    double converged_force_scale_ = 0, trial_force_scale_ = 0;
    bool   has_previous_ = false;
    dealii::PETScWrappers::MPI::Vector       residual_;           // owned

    // Material states: [active_cell_index][q][variable], flattened.
    unsigned int        n_q_points_ = 8, n_state_ = 0;
    std::vector<double> state_old_, state_new_;

    LinearSolver                                     linear_solver_;
    MatrixScatter                                    scatter_; // fast path of the matrix assembly
    // |R_it| / |R_it-1| of Newton iteration it of augmentation pass `pass` in the last increment
    // that reached it ([pass][it], the last slots shared by the later ones; 0: unknown). Steers
    // which iterates assemble their residual first (solve_increment); no effect on results.
    std::array<std::array<double, 6>, 6>             newton_reduction_{};
    RunStatistics                                    statistics_;
    std::vector<StepRecord>                          records_;
    std::vector<pileup::PileUpResult>                pileup_results_;
    std::vector<std::pair<double, std::string>>      vtu_records_; // (output index, pvtu file)
    std::string                                      output_directory_;
    std::optional<unsigned int>                      stop_after_step_;
    dealii::Timer                                    wall_timer_;
  };
} // namespace indentsim::solver
