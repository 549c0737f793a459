// The run of IndentationProblem through its loading programme (nonlinear/LoadingProgramme.h):
// one converged step at a time, with the cut-back stepper (nonlinear/CutBackStepper.h), the
// outputs of each step (output/RunRecorder.h, VTU, pile-up snapshots), checkpoints, stop and
// resume. Units: um, mN, GPa, s.
#include "case/CaseFile.h"
#include "case/DamageProfile.h"
#include "output/Checkpoint.h"
#include "output/OutputFile.h"
#include "output/RunRecorder.h"
#include "problems/IndentationProblem.h"

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace indentsim::problems
{
  using namespace dealii;
  using nonlinear::IncrementStatus;
  using nonlinear::Segment;
  using nonlinear::SegmentKind;

  // What run() carries from step to step besides the problem's own state.
  template <int dim>
  struct IndentationProblem<dim>::RunContext
  {
    RunContext(const io::Case &the_case, const Timer &timer)
      : programme(the_case.loading)
      , timer(timer)
    {
    }

    const nonlinear::LoadingProgramme programme;
    LoopState                         loop;
    // Top-surface snapshots for the pile-up analysis (rank 0), at the maximum of the last
    // cycle and at the end of unloading.
    std::vector<SurfaceSnapshot> snapshots;
    output::RunRecorder          recorder;
    std::optional<unsigned int>  stop_after;
    double                       last_checkpoint = 0; // [s] on this process's clock
    const Timer                 &timer;

    // Of the run so far, earlier parts before a resume included [s].
    double wall_time() const { return wall_offset + timer.wall_time(); }
    double wall_offset = 0;
  };

  template <int dim>
  typename IndentationProblem<dim>::RunOutcome
  IndentationProblem<dim>::run(const std::string &output_directory, const bool resume)
  {
    output_directory_ = output_directory;
    if (resume && output_directory_.empty())
      throw io::CaseFileError("--resume needs the output directory of the stopped run");
    RunContext context(case_, wall_timer_);
    start_run(context, resume);
    // Stop requests: signals, stop_after_step(), and INDENTSIM_STOP_AFTER_STEP.
    const output::checkpoint::StopRequest stop_request;
    context.stop_after = stop_after_step_;
    if (const char *text = std::getenv("INDENTSIM_STOP_AFTER_STEP"); text != nullptr && *text)
      context.stop_after = static_cast<unsigned int>(std::stoul(text));
    context.last_checkpoint = wall_timer_.wall_time();

    LoopState &loop = context.loop;
    while (loop.segment < context.programme.segments.size())
      {
        const Segment &segment = context.programme.segments[loop.segment];
        if (!loop.in_segment)
          {
            loop.in_segment = true;
            const bool partial = segment.kind == SegmentKind::partial_unload;
            loop.partial_start_force = partial ? records_.back().force : 0.0;
            loop.control.start_segment(context.programme.nominal_increment(segment, loop.value),
                                       context.programme.paced(segment),
                                       partial ? context.programme.partial_unload_probe(loop.depth)
                                               : 0.0);
          }
        // Force control from a state that carries no load has no contact stiffness to steer
        // the depth: the first contact is made under depth control.
        if (context.programme.force_control && segment.kind != SegmentKind::unload &&
            loop.step == 0 && force_converged_ <= 0)
          {
            first_contact_step(context, segment);
            continue;
          }
        converged_step(context, segment);
        if (checkpoint_or_stop(context))
          return RunOutcome::stopped;
      }
    finish_run(context);
    return RunOutcome::finished;
  }

  // Opens the records; from a checkpoint, the state and the curve so far, else the initial
  // state (record and VTU).
  template <int dim>
  void IndentationProblem<dim>::start_run(RunContext &context, const bool resume)
  {
    // Collective (an MPI sum): every rank counts, rank 0 writes it.
    const unsigned int n_constrained = n_constrained_dofs();
    pileup_results_.clear();
    warnings_.clear();
    if (resume)
      read_checkpoint(context.loop, context.snapshots);
    // Resumed: the curve so far, from the saved records, so that the files are consistent with
    // the state even if the stopped run went on beyond its last checkpoint.
    if (!resume)
      records_.push_back(StepRecord());
    output::write_collectively(communicator_, [&]() {
      if (Utilities::MPI::this_mpi_process(communicator_) == 0)
        context.recorder.open(
            output_directory_,
            {n_cells(), n_dofs(), n_constrained, Utilities::MPI::n_mpi_processes(communicator_)},
            resume ? records_ : std::vector<StepRecord>{records_.back()});
    });
    wall_timer_.restart();
    context.wall_offset = context.loop.wall_time;
    if (resume)
      {
        context.recorder.log_note("resumed at step " + std::to_string(context.loop.step));
        check_records(context);
        pcout_ << "Resumed at step " << context.loop.step << " (depth " << std::setprecision(6)
               << context.loop.depth << " um) from the checkpoint in " << checkpoint_directory()
               << std::endl;
        return;
      }
    if (!output_directory_.empty())
      {
        const output::RunStatistics::Scope timer(statistics_.output);
        write_vtu(context.loop.vtu_index++);
      }
  }

  // A converged step becomes the next recorded step of the run (numbered, stamped, kept).
  template <int dim>
  void IndentationProblem<dim>::add_record(RunContext &context, const Segment &segment,
                                           StepRecord &record)
  {
    LoopState &loop = context.loop;
    ++loop.step;
    record.step = loop.step;
    record.cycle = segment.cycle;
    record.segment = to_string(segment.kind);
    record.wall_time = context.wall_time();
    loop.total_newton += record.newton_iterations;
    records_.push_back(record);
  }

  // Force control's first step: the first touch under depth control, 0.1 % of a contact element
  // beyond the nearest node (a recorded step; its force lies below the first target in the
  // examples).
  template <int dim>
  void IndentationProblem<dim>::first_contact_step(RunContext &context, const Segment &segment)
  {
    LoopState &loop = context.loop;
    StepRecord record;
    contact_->evaluate(solution_, depth_converged_);
    const double touch = depth_converged_ + std::max(contact_->min_gap(), 0.0) +
                         1e-3 * mesh_info_.contact_element_size;
    const IncrementStatus status = solve_increment(touch, record, false);
    if (status != IncrementStatus::converged)
      throw std::runtime_error("force control: the first contact at depth " +
                               std::to_string(touch) + " um failed (" + to_string(status) + ")");
    loop.value = record.force;
    loop.depth = record.depth;
    add_record(context, segment, record);
    accept_increment();
    context.recorder.csv_row(record);
    check_records(context);
    pcout_ << "step " << std::setw(3) << loop.step << " touch   depth " << loop.depth
           << " um  force " << record.force << " mN (first contact, depth control)" << std::endl;
  }

  // One converged step of `segment`, with retries and cut-backs, then its outputs.
  template <int dim>
  void IndentationProblem<dim>::converged_step(RunContext &context, const Segment &segment)
  {
    LoopState                         &loop = context.loop;
    const nonlinear::LoadingProgramme &programme = context.programme;
    const double nominal_before = programme.nominal_increment(segment, loop.value);
    loop.control.increment = std::min(loop.control.increment, nominal_before);
    const double depth_before = loop.depth, force_before = records_.back().force;
    StepRecord   record;
    const auto   solve = [&](const double target, const bool extrapolate) {
      return programme.force_control
                   ? solve_increment(depth_guess_for_force(target), record, extrapolate, target)
                   : solve_increment(target, record, extrapolate);
    };
    const auto report = [&](const nonlinear::RetryEvent &event) {
      pcout_ << "    step " << event.step << " to " << event.value << programme.unit() << ": "
             << to_string(event.status);
      if (event.from_extrapolation)
        {
          ++statistics_.predictor_retries;
          pcout_ << " from the extrapolated start; retrying from the converged state\n";
          return;
        }
      pcout_ << "; cutting the increment back to " << event.next_increment << programme.unit()
             << "\n";
      std::ostringstream note;
      note << std::setprecision(4) << "step " << event.step << ": " << to_string(event.status)
           << ", increment cut back to " << event.next_increment << programme.unit();
      context.recorder.log_note(note.str());
    };
    unsigned int cutbacks = 0;
    loop.value = nonlinear::solve_with_cutbacks(
        programme, segment, loop.control, loop.value, loop.step, case_.loading.max_cutbacks, solve,
        [this]() { reject_increment(); }, report, cutbacks);
    loop.depth = record.depth;
    if (programme.force_control && loop.depth > case_.loading.max_depth)
      throw std::runtime_error(
          "force control: the indenter reached the depth " + std::to_string(loop.depth) +
          " um at the force " + std::to_string(record.force) +
          " mN, beyond loading.max_depth = " + std::to_string(case_.loading.max_depth) +
          " um, the depth the mesh is designed for; lower loading.max_force or raise "
          "loading.max_depth with specimen.refined_region");
    record.cutbacks = cutbacks;
    complete_step(context, segment, record, nominal_before, depth_before, force_before);
  }

  // Records a converged step, writes its outputs, accepts it and moves the programme on.
  template <int dim>
  void IndentationProblem<dim>::complete_step(RunContext &context, const Segment &segment,
                                              StepRecord &record, const double nominal_before,
                                              const double depth_before, const double force_before)
  {
    LoopState                         &loop = context.loop;
    const nonlinear::LoadingProgramme &programme = context.programme;
    ++loop.control.segment_steps;
    add_record(context, segment, record);
    loop.max_force = std::max(loop.max_force, record.force);

    const bool partial = segment.kind == SegmentKind::partial_unload;
    const bool reached =
        segment.kind == SegmentKind::hold ? loop.control.segment_steps >= segment.steps
        : partial ? programme.partial_unload_done(record.force, loop.partial_start_force)
                  : std::abs(loop.value - segment.target) <= 1e-12 * programme.maximum;
    // Depth-controlled unloading ends when contact is lost or the force has fallen below 0.1 %
    // of its maximum (the last node leaving the indenter makes the active set toggle; nothing
    // measurable happens below that force).
    const bool lost =
        segment.kind == SegmentKind::unload && !programme.force_control &&
        (record.n_active_nodes == 0 || loop.depth <= 0 || record.force <= 1e-3 * loop.max_force);
    const bool segment_done = reached || lost;
    // The loading's end (not the depth of a partial unload).
    const bool at_max = segment_done && segment.kind == SegmentKind::load &&
                        std::abs(segment.target - programme.maximum) <= 1e-12 * programme.maximum;
    const bool finished = segment_done && loop.segment + 1 == programme.segments.size();
    statistics_.steps = loop.step;
    statistics_.cutbacks += record.cutbacks;
    {
      const output::RunStatistics::Scope timer(statistics_.output);
      const bool                         writing = !output_directory_.empty();
      if (writing && (at_max || finished ||
                      (case_.output.vtu_every > 0 && loop.step % case_.output.vtu_every == 0)))
        write_vtu(loop.vtu_index++);
      if (writing && at_max)
        {
          std::erase_if(context.snapshots,
                        [](const SurfaceSnapshot &s) { return s.stage == "max_depth"; });
          context.snapshots.push_back({"max_depth", loop.depth, gather_top_surface()});
        }
      if (writing && finished && segment.kind == SegmentKind::unload)
        context.snapshots.push_back({"unloaded", loop.depth, gather_top_surface()});
      if (at_max)
        {
          loop.contact_radius_at_max = record.contact_radius;
          loop.value_at_max = programme.force_control ? loop.depth : record.force;
        }
    }
    accept_increment();
    measure_plastic_zone(record);
    records_.back() = record;

    // Progress: one line per step, with an ETA from the mean step time of this run and the
    // nominal steps left from where the run stands (cut-backs do not count as progress).
    const double eta = record.wall_time / loop.step *
                       programme.remaining_steps(loop.segment, loop.value, segment_done);
    pcout_ << output::ProgressLine{record, case_.loading.cycles > 1,
                                   programme.force_control ? &loop.value : nullptr,
                                   contact_->friction_coefficient() > 0, eta}
           << std::endl;
    context.recorder.csv_row(record);
    context.recorder.log_row(record);
    check_records(context);
    check_guards(context.recorder, segment, record, at_max);

    if (segment_done)
      {
        ++loop.segment;
        loop.in_segment = false;
        return;
      }
    loop.control.after_step(
        record.cutbacks == 0 && record.newton_iterations <= 6, programme.paced(segment),
        nominal_before, programme.nominal_increment(segment, loop.value), depth_before, loop.depth,
        force_before, record.force,
        programme.pacing_force(segment, loop.max_force, loop.partial_start_force),
        partial ? record.force - programme.partial_unload_target(loop.partial_start_force)
                : std::numeric_limits<double>::infinity());
  }

  // Collective: a failed write of load_penetration.csv or run.log on rank 0 (kept by the
  // recorder) stops every rank with its OutputError.
  template <int dim>
  void IndentationProblem<dim>::check_records(RunContext &context)
  {
    output::write_collectively(communicator_, [&]() { context.recorder.throw_if_failed(); });
  }

  // Checkpoint and stop, decided together by all ranks (each rank's signal flag and clock may
  // differ). Nothing is saved after the last step: the run is complete. Returns whether the run
  // stops here.
  template <int dim>
  bool IndentationProblem<dim>::checkpoint_or_stop(RunContext &context)
  {
    const LoopState &loop = context.loop;
    if (output_directory_.empty() || loop.segment == context.programme.segments.size())
      return false;
    const double interval = case_.output.checkpoint_interval_s;
    const bool   stop_local = output::checkpoint::StopRequest::requested() ||
                            (context.stop_after && loop.step >= *context.stop_after);
    const bool due_local =
        interval > 0 && wall_timer_.wall_time() - context.last_checkpoint >= interval;
    const unsigned int stop = Utilities::MPI::max(stop_local ? 1u : 0u, communicator_);
    const unsigned int due = Utilities::MPI::max(due_local ? 1u : 0u, communicator_);
    if (stop || due)
      {
        context.loop.wall_time = context.wall_time();
        const output::RunStatistics::Scope timer(statistics_.output);
        write_checkpoint(context.loop, context.snapshots);
        context.last_checkpoint = wall_timer_.wall_time();
      }
    if (!stop)
      return false;
    context.recorder.log_note("stopped at step " + std::to_string(loop.step) + "; checkpoint in " +
                              checkpoint_directory());
    check_records(context);
    const std::string command =
        !resume_command_.empty()
            ? resume_command_
            : "indentsim run " +
                  (case_.source_file.empty() ? std::string("CASE.yaml") : case_.source_file) +
                  " --resume";
    pcout_ << "stopped at step " << loop.step << " (depth " << std::setprecision(6) << loop.depth
           << " um); resume with: " << command << std::endl;
    return true;
  }

  // A depth-graded specimen: the indenter depth at which the plastic zone first reached below
  // the last layer or the damage profile's last depth (console and run.log).
  template <int dim>
  void IndentationProblem<dim>::note_plastic_zone_in_substrate(RunContext &context)
  {
    const double layered_depth = io::graded_depth(case_.material);
    if (!(layered_depth > 0))
      return;
    std::ostringstream note;
    note << std::setprecision(4) << "the plastic zone ";
    const auto reached = std::find_if(records_.begin(), records_.end(), [&](const StepRecord &r) {
      return r.plastic_zone_depth > layered_depth;
    });
    if (reached == records_.end())
      note << "stays above the substrate (the graded depth " << layered_depth << " um)";
    else
      note << "reaches the substrate below the graded depth " << layered_depth
           << " um at the indenter depth " << reached->depth << " um (step " << reached->step
           << ")";
    pcout_ << "Depth-graded specimen: " << note.str() << std::endl;
    context.recorder.log_note(note.str());
  }

  // The end of a finished run: pile-up analysis, statistics, run_summary.json; the checkpoint
  // is removed.
  template <int dim>
  void IndentationProblem<dim>::finish_run(RunContext &context)
  {
    const LoopState &loop = context.loop;
    const bool       root = Utilities::MPI::this_mpi_process(communicator_) == 0;
    pcout_ << "Finished: " << loop.step << " steps, " << loop.total_newton
           << " Newton iterations, wall time " << output::format_duration(context.wall_time())
           << '\n';
    {
      std::ostringstream note;
      note << std::setprecision(4) << "finished: " << loop.step << " steps, " << loop.total_newton
           << " Newton iterations, " << context.wall_time() << " s";
      context.recorder.log_note(note.str());
    }
    note_plastic_zone_in_substrate(context);
    check_records(context);
    if (!output_directory_.empty())
      {
        const output::RunStatistics::Scope timer(statistics_.output);
        output::write_collectively(communicator_, [&]() {
          if (root)
            write_pileup(context.snapshots, loop.contact_radius_at_max);
        });
      }
    statistics_.total = statistics_.setup + context.wall_time();
    const output::RunStatistics &s = statistics_;
    pcout_ << "Time [s]: setup " << s.setup << ", assembly " << s.assembly << ", contact "
           << s.contact << ", linear solve " << s.linear_solve << " (" << s.linear_solves
           << " solves, " << s.linear_iterations << " iterations, " << s.preconditioner_setups
           << " preconditioner setups in " << s.preconditioner_setup << "), output " << s.output
           << ", total " << s.total << "; peak memory " << output::peak_memory_mib()
           << " MiB (rank 0)" << std::endl;
    if (output_directory_.empty())
      return;
    output::RunDescription description;
    description.test = "indentation";
    description.material_model = io::to_string(case_.material.model);
    description.linear_solver = linear_solver_.description();
    description.cells = n_cells();
    description.dofs = n_dofs();
    description.mpi_ranks = Utilities::MPI::n_mpi_processes(communicator_);
    description.threads = MultithreadInfo::n_threads();
    description.final_value = loop.value_at_max;
    description.final_value_name =
        context.programme.force_control ? "depth_at_max_force_um" : "force_at_max_depth_mN";
    description.warnings = warnings_;
    output::write_run_summary(output_directory_ + "/" + io::output_files::run_summary, description,
                              statistics_, communicator_);
    // A finished run needs no checkpoint (an earlier one, if any, is removed).
    MPI_Barrier(communicator_);
    if (root)
      {
        std::error_code error;
        std::filesystem::remove_all(checkpoint_directory(), error);
      }
  }
  template class IndentationProblem<2>;
  template class IndentationProblem<3>;
} // namespace indentsim::problems
