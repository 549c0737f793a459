// Checkpoint and resume of IndentationProblem::run (the format is described in
// output/Checkpoint.h). What a converged step leaves behind and the next one reads: the
// converged and previous displacements (the predictor extrapolates from both), their depths
// and forces, the material history, the contact multipliers and stick anchors, the loop state,
// the records so far and the pile-up snapshot at maximum depth. A rebuilt problem (same case,
// same number of ranks: the mesh, the partition and the DoF numbering are deterministic)
// continues from it as if it had never stopped.
#include "case/CaseFile.h"
#include "case/Fingerprint.h"
#include "case/OutputDirectory.h"
#include "output/Checkpoint.h"
#include "output/OutputFile.h"
#include "problems/IndentationProblem.h"

#include <deal.II/base/mpi.h>

#include <array>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace indentsim::problems
{
  using namespace dealii;
  using output::RunStatistics;
  namespace checkpoint = output::checkpoint;
  namespace pileup = analysis::pileup;

  namespace
  {
    std::vector<double> owned_values(const PETScWrappers::MPI::Vector &vector,
                                     const IndexSet                   &owned)
    {
      std::vector<double> values;
      values.reserve(owned.n_elements());
      for (const auto i : owned)
        values.push_back(vector(i));
      return values;
    }

    void set_owned_values(PETScWrappers::MPI::Vector &vector, const IndexSet &owned,
                          const std::vector<double> &values, const MPI_Comm communicator)
    {
      PETScWrappers::MPI::Vector owned_vector(owned, communicator);
      std::size_t                k = 0;
      for (const auto i : owned)
        owned_vector(i) = values[k++];
      owned_vector.compress(VectorOperation::insert);
      vector = owned_vector; // a ghosted target updates its ghosts
    }

    // Throws io::CaseFileError on every rank with the first rank's message if any rank failed.
    void agree_on_errors(const std::string &error, const MPI_Comm communicator)
    {
      for (const std::string &message : Utilities::MPI::all_gather(communicator, error))
        if (!message.empty())
          throw io::CaseFileError(message);
    }

    // The header of a checkpoint file (output/Checkpoint.h) after the magic and the format.
    struct CheckpointHeader
    {
      std::uint32_t n_ranks = 0, rank = 0;
      std::uint64_t fingerprint = 0;
      std::uint32_t step = 0;
    };

    // "no checkpoint to resume from" if `path` is missing; throws std::runtime_error.
    void require_checkpoint_file(const std::string &path)
    {
      if (!std::filesystem::exists(path))
        throw std::runtime_error("no checkpoint to resume from: '" + path +
                                 "' does not exist (was the run stopped? a finished run "
                                 "removes its checkpoint)");
    }

    CheckpointHeader read_header(checkpoint::Reader &in)
    {
      const std::string &path = in.path();
      const auto         magic = in.value<std::array<char, 8>>();
      if (std::string(magic.data(), 7) != std::string(checkpoint::magic, 7))
        throw std::runtime_error("'" + path + "' is not an indentsim checkpoint");
      if (const auto version = in.value<std::uint32_t>(); version != checkpoint::format_version)
        throw std::runtime_error("'" + path + "' has checkpoint format " + std::to_string(version) +
                                 ", this indentsim reads format " +
                                 std::to_string(checkpoint::format_version));
      CheckpointHeader header;
      header.n_ranks = in.value<std::uint32_t>();
      header.rank = in.value<std::uint32_t>();
      header.fingerprint = in.value<std::uint64_t>();
      header.step = in.value<std::uint32_t>();
      return header;
    }

    // The keys of `the_case` that differ from the case of the run in `output_directory`, as its
    // resolved_case.yaml states it: "key: old -> new" lines, or why they cannot be named.
    // The keys that do not determine the results never differ here (case/Fingerprint.h).
    std::string describe_case_differences(const io::Case    &the_case,
                                          const std::string &output_directory)
    {
      const std::string resolved = output_directory + "/" + io::output_files::resolved_case;
      const std::string unknown =
          " (a key other than output.directory, output.checkpoint_interval_s and solver.threads "
          "differs); which one cannot be told: '" +
          resolved + "' ";
      if (!std::filesystem::exists(resolved))
        return unknown + "is missing";
      try
        {
          const std::vector<io::KeyDifference> differences =
              io::case_differences(io::read_case_file(resolved), the_case);
          if (differences.empty())
            return unknown + "holds this case (was it edited?)";
          std::string text = "; the keys that differ (the stopped run's value, from " + resolved +
                             " -> this case's):";
          for (const io::KeyDifference &difference : differences)
            text += "\n  " + difference.path + ": " + difference.old_value + " -> " +
                    difference.new_value;
          return text;
        }
      catch (const std::exception &e)
        {
          return unknown + "cannot be read: " + e.what();
        }
    }

    // Reads the header of this rank's checkpoint file and checks it against the run: format,
    // rank count, rank and the case's fingerprint. Returns the step; throws std::runtime_error.
    std::uint32_t read_checked_header(checkpoint::Reader &in, const io::Case &the_case,
                                      const MPI_Comm communicator)
    {
      const unsigned int     rank = Utilities::MPI::this_mpi_process(communicator);
      const unsigned int     n_ranks = Utilities::MPI::n_mpi_processes(communicator);
      const std::string     &path = in.path();
      const std::string      directory = std::filesystem::path(path).parent_path().string();
      const CheckpointHeader header = read_header(in);
      if (header.n_ranks != n_ranks)
        throw std::runtime_error("the checkpoint in '" + directory + "' was written by " +
                                 std::to_string(header.n_ranks) + " MPI rank(s), this run has " +
                                 std::to_string(n_ranks) +
                                 "; resume with the same number (mpirun -np " +
                                 std::to_string(header.n_ranks) + ")");
      if (header.rank != rank)
        throw std::runtime_error("'" + path + "' belongs to another rank");
      if (header.fingerprint != io::case_fingerprint(the_case))
        throw std::runtime_error(
            "the checkpoint in '" + directory + "' belongs to a different case" +
            describe_case_differences(the_case,
                                      std::filesystem::path(directory).parent_path().string()) +
            "\nresume with the unchanged case file, or start afresh with --overwrite");
      return header.step;
    }

    // The fields of a step record in their checkpoint order, listed once for the writer and
    // the reader.
    template <typename Record, typename Visit>
    void visit_record_fields(Record &r, const Visit &visit)
    {
      visit(r.step);
      visit(r.cycle);
      visit(r.segment);
      visit(r.depth);
      visit(r.force);
      visit(r.contact_radius);
      visit(r.contact_area);
      visit(r.n_active_nodes);
      visit(r.n_stick_nodes);
      visit(r.n_slip_nodes);
      visit(r.max_pressure);
      visit(r.newton_iterations);
      visit(r.augmentations);
      visit(r.cutbacks);
      visit(r.max_penetration);
      visit(r.bottom_reaction);
      visit(r.plastic_zone_depth);
      visit(r.plastic_zone_radius);
      visit(r.plastic_zone_volume);
      visit(r.plastic_zone_layer_volume);
      visit(r.wall_time);
    }
  } // namespace

  template <int dim>
  std::string IndentationProblem<dim>::checkpoint_directory() const
  {
    return output_directory_ + "/" + io::output_files::checkpoint_directory;
  }

  template <int dim>
  std::uint64_t IndentationProblem<dim>::case_fingerprint() const
  {
    return io::case_fingerprint(case_);
  }

  template <int dim>
  void IndentationProblem<dim>::write_checkpoint(const LoopState                    &loop,
                                                 const std::vector<SurfaceSnapshot> &snapshots)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator_);
    const std::string  directory = checkpoint_directory();
    output::write_collectively(communicator_, [&]() {
      std::error_code code;
      if (rank == 0 && !std::filesystem::create_directories(directory, code) && code)
        throw output::OutputError(directory, code.message());
    });
    // Every rank writes and closes its file; only when all succeeded do they replace the
    // previous checkpoint, so that a failure (a full disk) on one rank keeps the previous
    // checkpoint of every rank.
    std::unique_ptr<checkpoint::Writer> writer;
    output::write_collectively(communicator_, [&]() {
      writer = std::make_unique<checkpoint::Writer>(checkpoint::rank_file(directory, rank));
      checkpoint::Writer &out = *writer;
      out.value(checkpoint::magic);
      out.value(checkpoint::format_version);
      out.value<std::uint32_t>(Utilities::MPI::n_mpi_processes(communicator_));
      out.value<std::uint32_t>(rank);
      out.value(case_fingerprint());
      out.value<std::uint32_t>(loop.step);
      out.value<std::uint64_t>(solid_.locally_owned.n_elements());
      out.value<std::uint64_t>(history_.converged_values().size());

      out.vector(owned_values(solution_converged_, solid_.locally_owned));
      out.vector(owned_values(solution_previous_, solid_.locally_owned));
      out.value(depth_converged_);
      out.value(depth_previous_);
      out.value(force_converged_);
      out.value(force_previous_);
      out.value(converged_force_scale_);
      out.value(has_previous_);
      out.vector(history_.converged_values());
      out.vector(contact_->persistent_state());

      out.value(loop);
      out.value<std::uint64_t>(records_.size());
      for (const StepRecord &r : records_)
        visit_record_fields(r, [&](const auto &field) {
          if constexpr (std::is_same_v<std::decay_t<decltype(field)>, std::string>)
            out.string(field);
          else
            out.value(field);
        });
      out.value<std::uint64_t>(vtu_records_.size());
      for (const auto &[index, file] : vtu_records_)
        {
          out.value(index);
          out.string(file);
        }
      out.value(statistics_);
      out.value<std::uint64_t>(snapshots.size());
      for (const SurfaceSnapshot &snapshot : snapshots)
        {
          out.string(snapshot.stage);
          out.value(snapshot.depth);
          out.vector(snapshot.surface);
        }
      // The warnings given so far: a resumed run's summary lists them too, although a guard
      // that looks only at the first step does not look again.
      out.value<std::uint64_t>(warnings_.size());
      for (const output::RunWarning &warning : warnings_)
        {
          out.string(warning.topic);
          out.string(warning.text);
        }
      out.close();
    });
    output::write_collectively(communicator_, [&]() { writer->commit(); });
  }

  template <int dim>
  void IndentationProblem<dim>::read_checkpoint(LoopState                    &loop,
                                                std::vector<SurfaceSnapshot> &snapshots)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator_);
    const std::string  directory = checkpoint_directory();
    const std::string  path = checkpoint::rank_file(directory, rank);

    std::string         error;
    std::uint32_t       step = 0;
    std::vector<double> converged, previous, state, contact_state;
    double depth_converged = 0, depth_previous = 0, force_converged = 0, force_previous = 0,
           force_scale = 0;
    bool                                        has_previous = false;
    std::vector<StepRecord>                     records;
    std::vector<std::pair<double, std::string>> vtu_records;
    RunStatistics                               statistics;
    std::vector<output::RunWarning>             warnings;
    try
      {
        require_checkpoint_file(path);
        checkpoint::Reader in(path);
        step = read_checked_header(in, case_, communicator_);
        if (const auto n_owned = in.value<std::uint64_t>();
            n_owned != solid_.locally_owned.n_elements())
          throw std::runtime_error("the checkpoint '" + path + "' holds " +
                                   std::to_string(n_owned) + " DoFs of this rank, the mesh has " +
                                   std::to_string(solid_.locally_owned.n_elements()));
        if (const auto n_state = in.value<std::uint64_t>();
            n_state != history_.converged_values().size())
          throw std::runtime_error("the checkpoint '" + path + "' holds " +
                                   std::to_string(n_state) +
                                   " material state values on this rank, the mesh needs " +
                                   std::to_string(history_.converged_values().size()));
        converged = in.vector<double>();
        previous = in.vector<double>();
        depth_converged = in.value<double>();
        depth_previous = in.value<double>();
        force_converged = in.value<double>();
        force_previous = in.value<double>();
        force_scale = in.value<double>();
        has_previous = in.value<bool>();
        state = in.vector<double>();
        contact_state = in.vector<double>();
        if (converged.size() != solid_.locally_owned.n_elements() ||
            previous.size() != solid_.locally_owned.n_elements() ||
            state.size() != history_.converged_values().size())
          throw std::runtime_error("'" + path + "' is inconsistent (vector sizes)");

        loop = in.value<LoopState>();
        records.resize(in.value<std::uint64_t>());
        for (StepRecord &r : records)
          visit_record_fields(r, [&](auto &field) {
            using Field = std::decay_t<decltype(field)>;
            if constexpr (std::is_same_v<Field, std::string>)
              field = in.string();
            else
              field = in.value<Field>();
          });
        vtu_records.resize(in.value<std::uint64_t>());
        for (auto &[index, file] : vtu_records)
          {
            index = in.value<double>();
            file = in.string();
          }
        statistics = in.value<RunStatistics>();
        snapshots.resize(in.value<std::uint64_t>());
        for (SurfaceSnapshot &snapshot : snapshots)
          {
            snapshot.stage = in.string();
            snapshot.depth = in.value<double>();
            snapshot.surface = in.vector<pileup::SurfaceQuad>();
          }
        warnings.resize(in.value<std::uint64_t>());
        for (output::RunWarning &warning : warnings)
          {
            warning.topic = in.string();
            warning.text = in.string();
          }
        contact_->restore_state(contact_state);
      }
    catch (const std::exception &e)
      {
        error = e.what();
      }
    agree_on_errors(error, communicator_);
    if (Utilities::MPI::min(step, communicator_) != Utilities::MPI::max(step, communicator_))
      throw io::CaseFileError("the checkpoint files in '" + directory +
                              "' are of different steps (the run was killed while writing "
                              "them); it cannot be resumed");

    set_owned_values(solution_converged_, solid_.locally_owned, converged, communicator_);
    set_owned_values(solution_, solid_.locally_owned, converged, communicator_);
    set_owned_values(solution_previous_, solid_.locally_owned, previous, communicator_);
    depth_converged_ = depth_trial_ = depth_converged;
    depth_previous_ = depth_previous;
    force_converged_ = force_trial_ = force_converged;
    force_previous_ = force_previous;
    converged_force_scale_ = trial_force_scale_ = force_scale;
    has_previous_ = has_previous;
    history_.converged_values() = std::move(state);
    history_.converged_changed();
    records_ = std::move(records);
    vtu_records_ = std::move(vtu_records);
    warnings_ = std::move(warnings);
    const double setup = statistics_.setup;
    statistics_ = statistics;
    statistics_.setup = setup;
  }

  ResumeState check_resume(const io::Case &the_case, const MPI_Comm communicator)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    const std::string &output_directory = the_case.output.directory;
    const std::string  directory = output_directory + "/" + io::output_files::checkpoint_directory;
    std::string        error;
    // On rank 0: the directory, and a finished run (its summary written, no checkpoint).
    bool finished = false;
    if (rank == 0)
      {
        if (!std::filesystem::is_directory(output_directory))
          error = "--resume: the output directory '" + output_directory + "' does not exist";
        else if (!std::filesystem::exists(directory) &&
                 std::filesystem::exists(output_directory + "/" + io::output_files::run_summary))
          {
            finished = true;
            const std::string resolved = output_directory + "/" + io::output_files::resolved_case;
            try
              {
                const std::vector<io::KeyDifference> differences =
                    io::case_differences(io::read_case_file(resolved), the_case);
                if (!differences.empty())
                  {
                    error = "--resume: the run in '" + output_directory +
                            "' is finished, and with another case; keys that differ (its value "
                            "in " +
                            resolved + " -> this case's):";
                    for (const io::KeyDifference &difference : differences)
                      error += "\n  " + difference.path + ": " + difference.old_value + " -> " +
                               difference.new_value;
                    error += "\nnothing was changed; to compute this case choose another "
                             "directory (--output DIR) or replace the results with --overwrite";
                  }
              }
            catch (const std::exception &e)
              {
                error = "--resume: the run in '" + output_directory +
                        "' is finished (it has no checkpoint), and its " + resolved +
                        " cannot be read: " + e.what();
              }
          }
      }
    agree_on_errors(Utilities::MPI::broadcast(communicator, error, 0), communicator);
    if (Utilities::MPI::broadcast(communicator, finished, 0))
      return ResumeState::finished;

    // Every rank: its checkpoint file's header.
    std::uint32_t step = 0;
    try
      {
        const std::string path = checkpoint::rank_file(directory, rank);
        require_checkpoint_file(path);
        checkpoint::Reader in(path);
        step = read_checked_header(in, the_case, communicator);
      }
    catch (const std::exception &e)
      {
        error = std::string("--resume: ") + e.what() + "\n(nothing in '" + output_directory +
                "' was changed)";
      }
    agree_on_errors(error, communicator);
    if (Utilities::MPI::min(step, communicator) != Utilities::MPI::max(step, communicator))
      throw io::CaseFileError("--resume: the checkpoint files in '" + directory +
                              "' are of different steps (the run was killed while writing "
                              "them); it cannot be resumed");
    return ResumeState::resumable;
  }
  template class IndentationProblem<2>;
  template class IndentationProblem<3>;
} // namespace indentsim::problems
