// Checkpoint and resume of IndentationProblem::run (the format is described in
// output/Checkpoint.h). What a converged step leaves behind and the next one reads: the
// converged and previous displacements (the predictor extrapolates from both), their depths
// and forces, the material history, the contact multipliers and stick anchors, the loop state,
// the records so far and the pile-up snapshot at maximum depth. A rebuilt problem (same case,
// same number of ranks: the mesh, the partition and the DoF numbering are deterministic)
// continues from it as if it had never stopped.
#include "case/CaseFile.h"
#include "case/Fingerprint.h"
#include "output/Checkpoint.h"
#include "problems/IndentationProblem.h"

#include <deal.II/base/mpi.h>

#include <array>
#include <filesystem>
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
      visit(r.wall_time);
    }
  } // namespace

  std::string IndentationProblem::checkpoint_directory() const
  {
    return output_directory_ + "/" + io::output_files::checkpoint_directory;
  }

  std::uint64_t IndentationProblem::case_fingerprint() const
  {
    return io::case_fingerprint(case_);
  }

  void IndentationProblem::write_checkpoint(const LoopState                    &loop,
                                            const std::vector<SurfaceSnapshot> &snapshots)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator_);
    const std::string  directory = checkpoint_directory();
    std::string        error;
    if (rank == 0)
      {
        std::error_code code;
        std::filesystem::create_directories(directory, code);
        if (code)
          error = "checkpoint: cannot create '" + directory + "': " + code.message();
      }
    agree_on_errors(Utilities::MPI::broadcast(communicator_, error, 0), communicator_);
    try
      {
        checkpoint::Writer out(checkpoint::rank_file(directory, rank));
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
        out.commit();
      }
    catch (const std::exception &e)
      {
        error = e.what();
      }
    agree_on_errors(error, communicator_);
  }

  void IndentationProblem::read_checkpoint(LoopState &loop, std::vector<SurfaceSnapshot> &snapshots)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator_);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator_);
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
    try
      {
        if (!std::filesystem::exists(path))
          throw std::runtime_error("no checkpoint to resume from: '" + path +
                                   "' does not exist (was the run stopped? a finished run "
                                   "removes its checkpoint)");
        checkpoint::Reader in(path);
        const auto         magic = in.value<std::array<char, 8>>();
        if (std::string(magic.data(), 7) != std::string(checkpoint::magic, 7))
          throw std::runtime_error("'" + path + "' is not an indentsim checkpoint");
        if (const auto version = in.value<std::uint32_t>(); version != checkpoint::format_version)
          throw std::runtime_error("'" + path + "' has checkpoint format " +
                                   std::to_string(version) + ", this indentsim reads format " +
                                   std::to_string(checkpoint::format_version));
        if (const auto ranks = in.value<std::uint32_t>(); ranks != n_ranks)
          throw std::runtime_error(
              "the checkpoint in '" + directory + "' was written by " + std::to_string(ranks) +
              " MPI rank(s), this run has " + std::to_string(n_ranks) +
              "; resume with the same number (mpirun -np " + std::to_string(ranks) + ")");
        if (in.value<std::uint32_t>() != rank)
          throw std::runtime_error("'" + path + "' belongs to another rank");
        if (in.value<std::uint64_t>() != case_fingerprint())
          throw std::runtime_error(
              "the checkpoint in '" + directory +
              "' belongs to a different case: the resolved case "
              "(apart from output.directory and output.checkpoint_interval_s) differs from the one "
              "of the stopped run; resume with the unchanged case file, or start afresh with "
              "--overwrite");
        step = in.value<std::uint32_t>();
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
    const double setup = statistics_.setup;
    statistics_ = statistics;
    statistics_.setup = setup;
  }
} // namespace indentsim::problems
