// GoogleTest entry point that initialises MPI (and deal.II's thread pool) once for all tests.
#include "io/MpiStartup.h"
#include "linalg/LinearSolver.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

int main(int argc, char **argv)
{
  // Started without mpirun (every test but the mpi tier), as the executable does: a singleton
  // without network transports (a quarter of a second less per test process) and with a
  // session directory of its own, since CTest starts test processes side by side
  // (io/MpiStartup.h).
  indentsim::io::SingletonStartup          singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  singleton.take_back();
  indentsim::linalg::LinearSolver::limit_library_threads();
  ::testing::InitGoogleTest(&argc, argv);
  // Only rank 0 prints, so the output of `mpirun -np 2` stays readable.
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    {
      auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
    }
  return RUN_ALL_TESTS();
}
