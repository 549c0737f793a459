// The ParaView series of a run: one VTU piece per MPI rank, the PVTU record of an output step
// and the PVD time series, each written through a temporary file (output/OutputFile.h), so that
// a failure (a full disk) names the file and the reason on every rank and leaves no partial
// file behind.
#pragma once

#include <deal.II/base/data_out_base.h>

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace indentsim::output
{
  // Writes DIR/BASE_CCCC.R.vtu on every rank R (CCCC: `counter` with `n_digits_for_counter`
  // digits; R with the digits of the largest rank) and DIR/BASE_CCCC.pvtu on rank 0; returns the
  // PVTU's name (without the directory). Collective; throws OutputError on every rank if any
  // rank's file could not be written.
  template <int dim>
  std::string write_vtu_with_pvtu_record(const dealii::DataOutInterface<dim, dim> &data_out,
                                         const std::string &directory, const std::string &basename,
                                         unsigned int counter, unsigned int n_digits_for_counter,
                                         MPI_Comm communicator);

  // Writes the PVD time series `path` (time, PVTU name) on rank 0. Collective; throws
  // OutputError on every rank if it could not be written.
  void write_pvd(const std::string                                 &path,
                 const std::vector<std::pair<double, std::string>> &records, MPI_Comm communicator);
} // namespace indentsim::output
