// The memory a run will need, estimated from the case's keys before anything is built or
// written, and the check against the memory the machine has available. `indentsim check` and
// `run` print the estimate; a case that would not fit is refused (exit code 1) with the
// estimate and the key to change. Units: MiB.
//
// The estimate: every rank's base (program, libraries, MPI, PETSc) plus a per-DOF amount for the
// model (matrix, vectors, quadrature-point histories, the iterative solver's AMG hierarchy and
// block copy), plus the direct solver's factors when MUMPS is used (solver.linear_solver:
// direct, or auto where linalg::LinearSolver::choose_kind predicts it cheaper), which grow faster than the DOFs. The coefficients are
// calibrated against the peak resident memory of real runs (docs/performance.md, "Memory
// estimate").
#pragma once

#include "case/Case.h"
#include "mesh/MeshEstimate.h"

#include <mpi.h>

#include <optional>
#include <ostream>
#include <string>

namespace indentsim::output
{
  struct MemoryEstimate
  {
    mesh::MeshSize mesh;
    unsigned int   ranks = 1;
    bool           direct_solver = false; // MUMPS factorisation
    double         per_rank_mib = 0;      // each rank's peak [MiB]
    double         total_mib = 0;         // summed over the ranks [MiB]
  };

  // The estimate for `the_case` on `n_ranks` MPI ranks.
  MemoryEstimate estimate_memory(const io::Case &the_case, unsigned int n_ranks);

  // The memory available to new processes on this machine [MiB]: MemAvailable of /proc/meminfo,
  // or the environment variable INDENTSIM_AVAILABLE_MEMORY_MB when set (to plan for another
  // machine, or in tests); nullopt if neither can be read.
  std::optional<double> available_memory_mib();

  // "1368 cells, 5643 DOFs, about 380 MiB (2 MPI ranks; 20 100 MiB available)".
  std::string describe(const MemoryEstimate &estimate, std::optional<double> available_mib);

  // Collective. Estimates the case's memory on the ranks of `communicator`, prints the
  // estimate on rank 0 (each line begins with `line_prefix`), and throws io::CaseFileError on
  // every rank if the ranks of any node together would need more than that node's available
  // memory, naming the estimate and the key to change.
  void check_memory(const io::Case &the_case, MPI_Comm communicator, std::ostream &out,
                    const std::string &line_prefix = "");
} // namespace indentsim::output
