// ParaView files written without partial files (see ParaViewFiles.h).
#include "output/ParaViewFiles.h"

#include "output/OutputFile.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <exception>
#include <functional>
#include <memory>

namespace indentsim::output
{
  namespace
  {
    // Writes and closes `file` with `write`, a deal.II writer that checks its stream and throws
    // its own ExcIO (with no file name and no reason) when the stream fails: the stream's
    // system error is reported instead (OutputError from close()).
    void write_with_deal_ii(AtomicFile &file, const std::function<void(std::ostream &)> &write)
    {
      try
        {
          write(file.stream());
        }
      catch (const std::exception &)
        {
          if (file.stream())
            throw; // not a failure of the file
        }
      file.close();
    }
  } // namespace

  template <int dim>
  std::string write_vtu_with_pvtu_record(const dealii::DataOutInterface<dim, dim> &data_out,
                                         const std::string &directory, const std::string &basename,
                                         const unsigned int counter,
                                         const unsigned int n_digits_for_counter,
                                         const MPI_Comm     communicator)
  {
    using dealii::Utilities::int_to_string;
    const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(communicator);
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int rank_digits = dealii::Utilities::needed_digits(n_ranks - 1);
    const std::string  stem = basename + "_" + int_to_string(counter, n_digits_for_counter);
    const auto         piece = [&](const unsigned int r) {
      return stem + "." + int_to_string(r, rank_digits) + ".vtu";
    };

    // Every rank writes and closes its piece; only when all succeeded are they renamed.
    std::unique_ptr<AtomicFile> file;
    write_collectively(communicator, [&]() {
      file = std::make_unique<AtomicFile>(directory + "/" + piece(rank));
      write_with_deal_ii(*file, [&](std::ostream &out) { data_out.write_vtu(out); });
    });
    write_collectively(communicator, [&]() { file->commit(); });
    const std::string pvtu = stem + ".pvtu";
    write_collectively(communicator, [&]() {
      if (rank != 0)
        return;
      std::vector<std::string> pieces;
      for (unsigned int r = 0; r < n_ranks; ++r)
        pieces.push_back(piece(r));
      AtomicFile record(directory + "/" + pvtu);
      write_with_deal_ii(record,
                         [&](std::ostream &out) { data_out.write_pvtu_record(out, pieces); });
      record.commit();
    });
    return pvtu;
  }

  void write_pvd(const std::string                                 &path,
                 const std::vector<std::pair<double, std::string>> &records,
                 const MPI_Comm                                     communicator)
  {
    write_collectively(communicator, [&]() {
      if (dealii::Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      AtomicFile file(path);
      write_with_deal_ii(
          file, [&](std::ostream &out) { dealii::DataOutBase::write_pvd_record(out, records); });
      file.commit();
    });
  }

  template std::string write_vtu_with_pvtu_record(const dealii::DataOutInterface<2, 2> &,
                                                  const std::string &, const std::string &,
                                                  unsigned int, unsigned int, MPI_Comm);
  template std::string write_vtu_with_pvtu_record(const dealii::DataOutInterface<3, 3> &,
                                                  const std::string &, const std::string &,
                                                  unsigned int, unsigned int, MPI_Comm);
} // namespace indentsim::output
