// How the indentsim executable starts MPI when no launcher started it.
//
// A process started without mpirun, srun or another process manager is an MPI singleton: one
// rank on this machine. OpenMPI still prepares its network transports then, and the Omni-Path
// (PSM) libraries it loads for that sleep while they look for their hardware; it also starts a
// helper daemon. That took 0.65 s of every start on the project's machines, against 0.25 s of
// computing for a small forward run of a calibration. A singleton needs no network: with the
// ob1 messaging layer (shared memory and self) and without the daemon it starts in 0.4 s.
#pragma once

#include <string>
#include <vector>

namespace indentsim::io
{
  // For a singleton, and unless the user chose OpenMPI's messaging layer or singleton mode
  // (OMPI_MCA_pml, OMPI_MCA_ess_singleton_isolated in the environment), sets OMPI_MCA_pml=ob1
  // and OMPI_MCA_ess_singleton_isolated=1 for MPI_Init. A launcher is recognised by the variables
  // it gives its ranks (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK, PMI_SIZE, SLURM_PROCID).
  // Returns the names it set; hand them to take_back_singleton_settings after MPI_Init.
  std::vector<std::string> choose_singleton_settings();

  // Removes the variables again, so that the processes this one starts (the forward runs of a
  // study or a calibration, perhaps through a launcher onto other nodes) choose for themselves.
  void take_back_singleton_settings(const std::vector<std::string> &names);
} // namespace indentsim::io
