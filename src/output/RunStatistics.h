// Where a run spends its time, and what it cost: counters and wall times per phase, peak
// memory, written to run_summary.json at the end of a run (read by bench/run_benchmarks.py).
// Times in s, memory in MiB.
#pragma once

#include <mpi.h>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace indentsim::output
{
  struct RunStatistics
  {
    // Wall time per phase [s] (rank 0's clock; the phases are collective).
    double setup = 0;        // mesh, DoFs, constraints, sparsity, history
    double assembly = 0;     // element loop: material updates, element kernels, scatter
    double cell_loop = 0;    // this rank's own cells, up to the exchange (part of assembly):
                             // its spread over ranks is the load imbalance
    double contact = 0;      // contact search, augmentation and its assembly
    double linear_solve = 0; // factorization or preconditioner setup and Krylov iterations
    double preconditioner_setup = 0; // of which AMG setups or LU factorizations
    double output = 0;               // VTU, pile-up snapshots and analysis, CSV
    double total = 0;                // whole run, setup included

    unsigned long steps = 0, cutbacks = 0, newton_iterations = 0, linear_iterations = 0,
                  linear_solves = 0, augmentations = 0, assemblies = 0,
                  predictor_retries = 0, // increments retried without the extrapolated start
        residual_only_assemblies = 0,    // residual without matrix (Newton's end predicted)
        residual_first_misses = 0,       // of those, iterates that needed the matrix after all
        contact_only_assemblies = 0,     // after an augmentation: element part kept
        preconditioner_setups = 0;       // AMG builds or LU factorizations

    // Counts one linear solve: its Krylov iterations, preconditioner setups and their time [s].
    void add_linear_solve(const unsigned int iterations, const unsigned int setups,
                          const double setup_seconds)
    {
      ++linear_solves;
      linear_iterations += iterations;
      preconditioner_setups += setups;
      preconditioner_setup += setup_seconds;
    }

    // Accumulates the wall time of its lifetime into `target`.
    class Scope
    {
    public:
      explicit Scope(double &target)
        : target_(target)
        , start_(std::chrono::steady_clock::now())
      {
      }
      ~Scope()
      {
        target_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      }
      Scope(const Scope &) = delete;
      Scope &operator=(const Scope &) = delete;

    private:
      double                               &target_;
      std::chrono::steady_clock::time_point start_;
    };
  };

  // Peak resident memory of this process [MiB] (getrusage).
  double peak_memory_mib();

  // A guard's warning: `topic` an identifier (run_summary.json's "topic", e.g.
  // contact_resolution), `text` what it says, with the numbers and the remedy.
  struct RunWarning
  {
    std::string topic, text;
  };

  // What run_summary.json records besides the statistics.
  struct RunDescription
  {
    std::string   test; // indentation | tensile
    std::string   material_model;
    std::string   linear_solver; // description of the solver used
    unsigned long cells = 0, dofs = 0;
    unsigned int  mpi_ranks = 1, threads = 1;
    double        final_value = 0; // force at maximum depth [mN] or final true stress [GPa]
    std::string   final_value_name;
    // The run's warnings, in the order they were given: a result the program cannot fully
    // vouch for says so in its summary, not only in run.log and on stderr.
    std::vector<RunWarning> warnings;
  };

  // Collective: gathers the peak memory of all ranks (largest and sum) and writes the JSON file
  // on rank 0 (through a temporary file); throws OutputError on every rank if it failed.
  void write_run_summary(const std::string &path, const RunDescription &description,
                         const RunStatistics &statistics, MPI_Comm communicator);
} // namespace indentsim::output
