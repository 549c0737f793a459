#include "output/MemoryEstimate.h"

#include "case/CaseFile.h"
#include "case/Schema.h"
#include "linalg/LinearSolver.h"
#include "mesh/IndentationMesh.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace indentsim::output
{
  namespace
  {
    // Calibration (docs/performance.md, "Memory estimate"): peak resident memory of real runs
    // against their DOFs.
    constexpr double base_per_rank_mib = 180; // program, libraries, MPI, PETSc
    constexpr double j2_kib_per_dof = 8.0;    // neo-Hookean and J2
    constexpr double crystal_kib_per_dof = 8.7;
    // MUMPS factors: coefficient * DOFs^exponent [KiB], summed over the ranks.
    constexpr double direct_coefficient_kib = 0.038;
    constexpr double direct_exponent = 1.5;

    std::string mib_text(const double mib)
    {
      std::ostringstream text;
      if (mib >= 10240)
        text << std::fixed << std::setprecision(1) << mib / 1024 << " GiB";
      else
        text << std::fixed << std::setprecision(0) << mib << " MiB";
      return text.str();
    }

    bool uses_direct_solver(const io::Case &the_case, const std::uint64_t dofs)
    {
      const unsigned int dim = the_case.specimen.symmetry == io::Symmetry::axisymmetric ? 2 : 3;
      return linalg::LinearSolver::choose_kind(the_case.solver.linear_solver, dim, dofs) ==
             linalg::LinearSolver::Kind::direct;
    }

    // The key that sizes the mesh and the largest value of it whose estimate fits in
    // `per_rank_limit_mib` on `n_ranks` ranks ("" if none does).
    std::string advice(const io::Case &the_case, const unsigned int n_ranks,
                       const double per_rank_limit_mib)
    {
      io::Case smaller = the_case;
      if (the_case.test == io::TestKind::tensile)
        {
          unsigned int &n = smaller.specimen.elements_per_side;
          while (n > 1 && estimate_memory(smaller, n_ranks).per_rank_mib > per_rank_limit_mib)
            --n;
          return "lower specimen.elements_per_side" +
                 (n > 1 ? " (" + std::to_string(n) + " fits)" : std::string());
        }
      if (the_case.specimen.automatic_mesh())
        return "give specimen.size (the automatic mesh's specimen is large but costs few "
               "cells), use specimen.symmetry: quarter or axisymmetric where the case allows it, "
               "or give contact_elements a number with a smaller refined_region";
      unsigned int &n = smaller.specimen.contact_elements;
      while (n > 4 && estimate_memory(smaller, n_ranks).per_rank_mib > per_rank_limit_mib)
        n -= 4;
      std::string text = "lower specimen.contact_elements";
      if (estimate_memory(smaller, n_ranks).per_rank_mib <= per_rank_limit_mib)
        text += " (" + std::to_string(n) + " fits)";
      text += ", or make specimen.refined_region (now " +
              io::format_triple(the_case.specimen.refined_region) +
              ") smaller for the same element size";
      if (the_case.specimen.symmetry != io::Symmetry::quarter)
        text += ", or use specimen.symmetry: quarter where the case allows it";
      return text;
    }
  } // namespace

  MemoryEstimate estimate_memory(const io::Case &the_case, const unsigned int n_ranks)
  {
    MemoryEstimate estimate;
    estimate.mesh = mesh::estimate_mesh(the_case);
    estimate.ranks = std::max(1u, n_ranks);
    const double dofs = static_cast<double>(estimate.mesh.dofs);
    estimate.direct_solver = uses_direct_solver(the_case, estimate.mesh.dofs);
    const double per_dof_kib =
        the_case.material.model == io::ModelKind::crystal ? crystal_kib_per_dof : j2_kib_per_dof;
    double shared_kib = per_dof_kib * dofs;
    if (estimate.direct_solver)
      shared_kib += direct_coefficient_kib * std::pow(dofs, direct_exponent);
    estimate.total_mib = estimate.ranks * base_per_rank_mib + shared_kib / 1024;
    estimate.per_rank_mib = estimate.total_mib / estimate.ranks;
    return estimate;
  }

  std::optional<double> available_memory_mib()
  {
    if (const char *text = std::getenv("INDENTSIM_AVAILABLE_MEMORY_MB"); text != nullptr && *text)
      {
        char        *end = nullptr;
        const double value = std::strtod(text, &end);
        if (end != text && *end == '\0' && value > 0 && std::isfinite(value))
          return value;
        throw io::CaseFileError("the environment variable INDENTSIM_AVAILABLE_MEMORY_MB = '" +
                                std::string(text) +
                                "' must be a positive number of MiB (the memory to plan for)");
      }
    std::ifstream meminfo("/proc/meminfo");
    std::string   name;
    double        kib = 0;
    std::string   unit;
    while (meminfo >> name >> kib >> unit)
      if (name == "MemAvailable:")
        return kib / 1024;
    return std::nullopt;
  }

  std::string describe(const MemoryEstimate &estimate, const std::optional<double> available_mib)
  {
    std::ostringstream text;
    text << estimate.mesh.cells << " cells, " << estimate.mesh.dofs << " DOFs, about "
         << mib_text(estimate.total_mib) << " of memory ("
         << (estimate.direct_solver ? "direct" : "iterative") << " solver, " << estimate.ranks
         << " MPI rank" << (estimate.ranks > 1 ? "s" : "");
    if (available_mib)
      text << "; " << mib_text(*available_mib) << " available";
    text << ")";
    return text.str();
  }

  void check_memory(const io::Case &the_case, const MPI_Comm communicator, std::ostream &out,
                    const std::string &line_prefix)
  {
    const unsigned int   n_ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);
    const bool           root = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
    const MemoryEstimate estimate = estimate_memory(the_case, n_ranks);

    // The ranks on this node share its available memory.
    MPI_Comm node;
    MPI_Comm_split_type(communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    const unsigned int node_ranks = dealii::Utilities::MPI::n_mpi_processes(node);
    MPI_Comm_free(&node);
    std::string           error;
    std::optional<double> available;
    try
      {
        available = available_memory_mib();
      }
    catch (const io::CaseFileError &e)
      {
        error = e.what();
      }
    // Per rank, on the tightest node (a negative value: unknown).
    const double per_rank_available =
        dealii::Utilities::MPI::min(available ? *available / node_ranks : 1e300, communicator);
    error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
    if (!error.empty())
      throw io::CaseFileError(error);
    const std::optional<double> shown = per_rank_available < 1e300
                                            ? std::optional<double>(per_rank_available * node_ranks)
                                            : std::nullopt;
    if (root)
      out << line_prefix << "Estimated size: " << describe(estimate, shown) << std::endl;
    if (!shown || estimate.per_rank_mib <= per_rank_available)
      return;

    const bool         tensile = the_case.test == io::TestKind::tensile;
    std::ostringstream message;
    message << (the_case.source_file.empty() ? std::string("case") : the_case.source_file) << ": "
            << (tensile ? "specimen.elements_per_side = " +
                              std::to_string(the_case.specimen.elements_per_side)
                        : "specimen.contact_elements = " +
                              (the_case.specimen.automatic_mesh()
                                   ? std::string("auto")
                                   : std::to_string(the_case.specimen.contact_elements)))
            << ": the case needs about " << mib_text(estimate.total_mib) << " of memory ("
            << estimate.mesh.cells << " cells, " << estimate.mesh.dofs << " DOFs on " << n_ranks
            << " MPI rank" << (n_ranks > 1 ? "s" : "") << ", " << mib_text(estimate.per_rank_mib)
            << " per rank; estimate of docs/performance.md), "
            << "more than the " << mib_text(per_rank_available * node_ranks) << " available"
            << (node_ranks > 1 ? " to its " + std::to_string(node_ranks) + " ranks on a node"
                               : std::string(" on this machine"))
            << " (MemAvailable of /proc/meminfo, or INDENTSIM_AVAILABLE_MEMORY_MB); "
            << advice(the_case, n_ranks, per_rank_available) << ", or run on more nodes";
    throw io::CaseFileError(message.str());
  }
} // namespace indentsim::output
