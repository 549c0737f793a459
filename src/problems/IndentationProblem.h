// Indentation of a block by a rigid indenter: the finite-strain quasi-static boundary-value
// problem (setup, assembly, accepted-state update), its augmented-Lagrangian Newton solver
// (IndentationNewton.cc) and the run through the loading programme (IndentationRun.cc), with
// the problem's output (IndentationOutput.cc) and checkpoint (IndentationCheckpoint.cc).
// Units: um, mN, GPa.
//
// Constraints are layered as in deal.II's step-42: hanging-node constraints, then
// Dirichlet-and-hanging constraints (bottom face fixed, symmetry planes of the quarter model);
// all are homogeneous, so the Newton updates use the same object. The lateral faces are
// traction-free. Contact enters as nodal forces (see contact/NodeToSurfaceContact.h).
#pragma once

#include "analysis/PileUp.h"
#include "case/Case.h"
#include "contact/ContactArea.h"
#include "contact/NodeToSurfaceContact.h"
#include "fem/AxisymmetricCellWorkspace.h"
#include "fem/CellWorkspace.h"
#include "fem/FiniteStrainElement.h"
#include "fem/QuadraturePointHistory.h"
#include "fem/SolidDiscretisation.h"
#include "indenter/IndenterSurface.h"
#include "linalg/LinearSolver.h"
#include "linalg/MatrixScatter.h"
#include "materials/MaterialModel.h"
#include "mesh/IndentationMesh.h"
#include "nonlinear/CutBackStepper.h"
#include "nonlinear/IncrementStatus.h"
#include "nonlinear/LoadingProgramme.h"
#include "nonlinear/NewtonSteps.h"
#include "nonlinear/StepRecord.h"
#include "output/RunStatistics.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace indentsim::output
{
  class RunRecorder;
}

namespace indentsim::problems
{
  using nonlinear::StepRecord;

  // What `run --resume` finds in the case's output directory.
  enum class ResumeState
  {
    resumable, // a checkpoint of this case, written by as many ranks as this run has
    finished   // a finished run of this case: nothing to resume
  };
  // Collective. Checks, before anything is written, that `the_case` can be resumed from the
  // checkpoint in its output.directory: the directory exists, the checkpoint files are there,
  // of this format, rank count and case (the fingerprint; the keys that differ are named with
  // the old values from the directory's resolved_case.yaml) and of one step; or the run there is
  // finished with this case. Throws io::CaseFileError (the same on every rank) saying why not.
  // Reads only.
  ResumeState check_resume(const io::Case &the_case, MPI_Comm communicator);

  // dim = 3: the block (full or quarter model); dim = 2: the axisymmetric model, the (r, z)
  // section of the cylinder (mesh/IndentationMesh.h) with the axisymmetric element
  // (fem/AxisymmetricElement.h).
  template <int dim>
  class IndentationProblem
  {
  public:
    // `indenter`: the one the case's validation built (io::read_case_for_run); null: built here
    // from the_case.indenter.
    IndentationProblem(const io::Case &the_case, MPI_Comm communicator, bool verbose = true,
                       std::shared_ptr<const indenter::IndenterSurface> indenter = nullptr);
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
    // A file that cannot be written throws output::OutputError on every rank (the files written
    // before, and the last checkpoint, stay).
    RunOutcome run(const std::string &output_directory, bool resume = false);
    // Requests a stop after the converged step `step` (as a signal would); the environment
    // variable INDENTSIM_STOP_AFTER_STEP does the same for the command line.
    void stop_after_step(unsigned int step) { stop_after_step_ = step; }
    // The command that resumes a stopped run, printed with the stop message ("indentsim run
    // CASE --resume" if none is given).
    void set_resume_command(const std::string &command) { resume_command_ = command; }

    // Solves one increment to depth `depth` from the last converged state (no cut-back). With
    // `extrapolate`, Newton starts from the linear extrapolation of the last two converged
    // states (when the indenter keeps its direction), else from the last converged state.
    // Force control: with `target_force` [mN, whole indent], the depth is an unknown solved with
    // the displacements (bordered Newton system) and `depth` is its starting guess.
    nonlinear::IncrementStatus solve_increment(double depth, StepRecord &record,
                                               bool                  extrapolate = true,
                                               std::optional<double> target_force = std::nullopt);
    // Force control: the starting depth for the force `target_force` [mN], by the secant of the
    // last two converged states (else the last converged depth).
    double depth_guess_for_force(double target_force) const;
    // Accepts or rejects the increment just solved.
    void accept_increment();
    void reject_increment();

    const std::vector<StepRecord> &records() const { return records_; }
    // Counters and phase times of this problem so far (setup and runs).
    const output::RunStatistics &statistics() const { return statistics_; }
    // The contact nodes and their state at the last evaluation.
    const contact::NodeToSurfaceContact &contact() const { return *contact_; }
    const indenter::IndenterSurface     &indenter() const { return *indenter_; }
    // The pile-up analysis of the last run(): stages max_depth and (after unloading) unloaded.
    // Filled on rank 0 when run() was given an output directory, empty otherwise.
    const std::vector<analysis::pileup::PileUpResult> &pileup_results() const
    {
      return pileup_results_;
    }
    // The warnings of the physics guards in the last run() (IndentationGuards.cc), in order,
    // one per topic; each also went to run.log and, when verbose, to stderr.
    const std::vector<output::RunWarning> &warnings() const { return warnings_; }

    unsigned int          n_cells() const;
    unsigned int          n_dofs() const;
    unsigned int          n_constrained_dofs() const;
    unsigned int          n_hanging_node_constraints() const;
    const mesh::MeshInfo &mesh_info() const { return mesh_info_; }
    double                symmetry_factor() const { return mesh_info_.quarter ? 4.0 : 1.0; }
    // The round-off level of the residual (IndentationProblem.cc) [mN].
    double                                    residual_round_off() const;
    const dealii::DoFHandler<dim>            &dof_handler() const { return solid_.dof_handler; }
    const dealii::PETScWrappers::MPI::Vector &solution() const { return solution_; }

  private:
    using Workspace = typename fem::CellWorkspaceFor<dim>::type;
    // Test-only access to the fields and the assembly (tests/problem_test_access.h).
    friend struct ProblemTestAccess;

    struct AssemblyResult
    {
      materials::UpdateStatus status = materials::UpdateStatus::success;
      double                  bottom_reaction = 0; // z reaction on the bottom face [mN]
    };
    // The element and contact parts of residual_ (and with `with_matrix`, matrix_) at
    // solution_. Under force control `coupling` receives the depth derivatives of the contact
    // forces (the bordered system of IndentationNewton.cc).
    AssemblyResult assemble(bool                                          with_matrix,
                            contact::NodeToSurfaceContact::DepthCoupling *coupling = nullptr);
    // After an augmentation at an unchanged displacement (and depth): the element part of
    // residual_ and matrix_ (last assembled with the matrix) stands; only the contact part is
    // replaced. Returns false, changing nothing, if the contact kept nothing to replace.
    bool reassemble_contact();
    // With several MPI ranks: repartitions the mesh with the expected plastic zone's cells
    // weighted by the material's relative plastic cost.
    void balance_plastic_zone();
    // The material state of every Gauss point before the first increment.
    void initialise_material_states();
    void make_constraints();
    void collect_reaction_weights();

    // The augmented-Lagrangian Newton of one increment, in steps (IndentationNewton.cc).
    struct NewtonIncrement;
    struct NewtonPass;
    enum class IterateOutcome
    {
      next_iterate,      // a Newton update (or a line-search step) was taken
      converged,         // the pass converged
      augment_early,     // an inexact pass ends: augment now
      out_of_iterations, // max_newton_iterations reached
      failed             // NewtonIncrement::failure says why
    };
    void           apply_predictor(NewtonIncrement &increment);
    IterateOutcome newton_iteration(NewtonIncrement &increment, NewtonPass &pass, unsigned int it,
                                    StepRecord &record);
    bool           evaluate_iterate(NewtonIncrement &increment, NewtonPass &pass, unsigned int it);
    std::optional<IterateOutcome> check_convergence(NewtonIncrement &increment, NewtonPass &pass,
                                                    unsigned int it, double norm);
    nonlinear::IncrementStatus    newton_update(NewtonIncrement &increment, NewtonPass &pass,
                                                double norm);
    void                          fill_converged_record(double depth, StepRecord &record);

    // Projected contact area and radius of the model (not symmetry-multiplied) from the
    // interpolated contact indicator (contact/ContactArea.h).
    contact::ContactPatch contact_patch() const;

    // Evaluates every locally owned cell at the current displacement from the converged state
    // (no tangent) and passes the Cauchy stress and the updated state of its quadrature points.
    void for_each_cell_stress(
        const std::function<void(const typename dealii::DoFHandler<dim>::active_cell_iterator &,
                                 const std::vector<dealii::Tensor<2, 3>> &,
                                 std::span<const double>)> &visit);

    // Outputs of the run (IndentationOutput.cc). Collective: writes the VTU pieces, the PVTU
    // and the PVD of output step `index`; throws output::OutputError on every rank if a file
    // could not be written.
    void write_vtu(unsigned int index);
    void compute_cell_fields(dealii::Vector<float>              &von_mises,
                             dealii::Vector<float>              &plastic_strain,
                             std::vector<dealii::Vector<float>> &cauchy);
    // The top-face quads (corners with reference X, Y and displacement) of all ranks, gathered
    // on rank 0 (empty elsewhere) and mirrored into the full surface for the quarter model.
    // Collective.
    std::vector<analysis::pileup::SurfaceQuad> gather_top_surface() const;
    struct SurfaceSnapshot
    {
      std::string                                stage;     // "max_depth" | "unloaded"
      double                                     depth = 0; // [um]
      std::vector<analysis::pileup::SurfaceQuad> surface;
    };
    // Rank 0: analyses the snapshots (a_c: contact radius at maximum depth), writes pileup.json
    // and the pile-up CSV files, then plots them with python/plot_pileup.py (a failing plot is
    // a warning). Throws output::OutputError if a file could not be written (run() calls it
    // through output::write_collectively).
    void write_pileup(const std::vector<SurfaceSnapshot> &snapshots, double contact_radius);

    // Where run() is in the loading programme after a converged step: everything the next
    // step needs besides the fields, histories and contact state of the problem. A plain value:
    // checkpoints store it byte for byte.
    struct LoopState
    {
      unsigned int                segment = 0;          // index into the programme
      bool                        in_segment = false;   // false: `segment` starts afresh
      double                      value = 0, depth = 0; // control value (depth or force) and depth
      nonlinear::IncrementControl control;
      unsigned int                step = 0, total_newton = 0, vtu_index = 0;
      double                      max_force = 0, contact_radius_at_max = 0, value_at_max = 0;
      double partial_start_force = 0; // force where the current partial unload started [mN]
      double wall_time = 0;           // of the run so far, the parts before a resume included [s]
    };
    // The run through the loading programme, in steps (IndentationRun.cc).
    struct RunContext;
    void start_run(RunContext &context, bool resume);
    void add_record(RunContext &context, const nonlinear::Segment &segment, StepRecord &record);
    void first_contact_step(RunContext &context, const nonlinear::Segment &segment);
    void converged_step(RunContext &context, const nonlinear::Segment &segment);
    void complete_step(RunContext &context, const nonlinear::Segment &segment, StepRecord &record,
                       double nominal_before, double depth_before, double force_before);
    bool checkpoint_or_stop(RunContext &context);
    void note_plastic_zone_in_substrate(RunContext &context);
    // Collective: the plastic zone of the converged state into `record` (IndentationPlasticZone.cc).
    void measure_plastic_zone(StepRecord &record);
    void check_records(RunContext &context);
    // The physics guards after an accepted step (IndentationGuards.cc, mesh/MeshAdequacy.h):
    // throws mesh::MeshOutgrownError (after noting it in run.log) when the contact nears the
    // edge of the refined region; warns once per face when the plastic zone nears a face of
    // the specimen, at the maximum when too few elements lie across the contact radius, when
    // the contact force leaves a mirror plane of the indenter, material and mesh, and when every
    // face of a pyramid runs along the mesh lines.
    void check_guards(output::RunRecorder &recorder, const nonlinear::Segment &segment,
                      const StepRecord &record, bool at_max);
    void check_refined_region(output::RunRecorder &recorder, const nonlinear::Segment &segment,
                              const StepRecord &record);
    void check_plastic_zone(output::RunRecorder &recorder);
    void check_damage_profile_end(output::RunRecorder &recorder);
    void check_contact_resolution(output::RunRecorder &recorder, const StepRecord &record);
    // The planes x = 0 and y = 0 about which the indenter, the material and the model are all
    // mirror-symmetric, and the warning when the contact force leaves such a plane.
    std::array<bool, 2> shared_mirror_planes() const;
    void check_mirror_symmetry(output::RunRecorder &recorder, const StepRecord &record);
    // The warning for a pyramid whose faces all run along the mesh lines (stairs in the force).
    void check_faces_along_mesh_lines(output::RunRecorder &recorder);
    // A guard's warning: run.log, stderr (verbose runs) and warnings(); once per `topic`.
    void warn(output::RunRecorder &recorder, const std::string &topic, const std::string &text);
    void finish_run(RunContext &context);

    // Collective. Writes <output>/checkpoint/rank_<r>.bin: every rank its temporary file, and
    // only when all succeeded do they replace the previous checkpoint; otherwise throws
    // output::OutputError on every rank and the previous checkpoint stays.
    void write_checkpoint(const LoopState &loop, const std::vector<SurfaceSnapshot> &snapshots);
    // Collective. Reads the checkpoint into the problem; throws io::CaseFileError on every rank
    // if any rank's file is missing, of another case, rank count or format.
    void read_checkpoint(LoopState &loop, std::vector<SurfaceSnapshot> &snapshots);
    // The fingerprint of the case as far as it determines the results (io::case_fingerprint,
    // case/Fingerprint.h).
    std::uint64_t case_fingerprint() const;
    std::string   checkpoint_directory() const;

    const io::Case                   &case_;
    MPI_Comm                          communicator_;
    dealii::ConditionalOStream        pcout_;
    fem::SolidDiscretisation<dim>     solid_; // mesh, elements, DoFs, index sets
    mesh::MeshInfo                    mesh_info_;
    dealii::AffineConstraints<double> constraints_hanging_;
    dealii::AffineConstraints<double> constraints_all_; // Dirichlet and hanging nodes
    // The share of a DoF's internal force that lands on the bottom's z reactions: 1 for a
    // supported z DoF, the constraint weight of its bottom masters for a hanging z DoF.
    std::unordered_map<dealii::types::global_dof_index, double> reaction_weights_;

    std::unique_ptr<materials::MaterialModel>        material_;
    std::shared_ptr<const indenter::IndenterSurface> indenter_;
    std::unique_ptr<contact::NodeToSurfaceContact>   contact_;
    bool                                             use_f_bar_;

    dealii::PETScWrappers::MPI::SparseMatrix matrix_;
    dealii::PETScWrappers::MPI::Vector       solution_;           // ghosted
    fem::GhostedVector                       solution_readable_;  // its copy for the threads
    dealii::PETScWrappers::MPI::Vector       solution_converged_; // ghosted
    // The converged solution before it (owned) and the depths of both: the predictor of the
    // next increment extrapolates linearly from them.
    dealii::PETScWrappers::MPI::Vector solution_previous_;
    double                             depth_converged_ = 0, depth_previous_ = 0, depth_trial_ = 0;
    // Indenter force (whole indent) of the last two converged increments [mN].
    double force_converged_ = 0, force_previous_ = 0, force_trial_ = 0;
    // |indenter force| of the model [mN]: the largest of the converged states so far (the scale
    // of Newton's relative tolerance), and that of the trial state.
    double converged_force_scale_ = 0, trial_force_scale_ = 0;
    // The absolute residual tolerance of Newton's method: solver.absolute_tolerance, or the
    // round-off level of the residual if larger (residual_round_off) [mN].
    double                             absolute_tolerance_ = 0;
    bool                               has_previous_ = false;
    dealii::PETScWrappers::MPI::Vector residual_; // owned

    // Material states of the quadrature points, converged and current.
    fem::QuadraturePointHistory history_;

    linalg::LinearSolver  linear_solver_;
    linalg::MatrixScatter scatter_; // fast path of the matrix assembly
    // Residual reductions of the Newton iterations in the last increment that reached them:
    // steers which iterates assemble their residual first; no effect on results.
    nonlinear::ResidualReductions               newton_reduction_;
    output::RunStatistics                       statistics_;
    std::vector<StepRecord>                     records_;
    std::vector<analysis::pileup::PileUpResult> pileup_results_;
    std::vector<output::RunWarning>             warnings_;
    std::array<bool, 2> mirror_planes_{};                     // x = 0, y = 0 (shared_mirror_planes)
    std::vector<std::pair<double, std::string>> vtu_records_; // (output index, pvtu file)
    std::string                                 output_directory_;
    std::optional<unsigned int>                 stop_after_step_;
    std::string                                 resume_command_;
    dealii::Timer                               wall_timer_;
  };
} // namespace indentsim::problems
