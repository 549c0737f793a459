// GoogleTest entry point that initialises MPI (and deal.II's thread pool) once for all tests.
#include "linalg/LinearSolver.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
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
