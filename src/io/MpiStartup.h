// How indentsim's processes start MPI when no launcher started them.
//
// A process started without mpirun, srun or another process manager is an MPI singleton: one
// rank on this machine. Two things about OpenMPI's singletons matter here:
// - Speed. OpenMPI prepares its network transports, and the Omni-Path (PSM) libraries it loads
//   for that sleep while they look for their hardware; it also starts a helper daemon. That took
//   0.65 s of every start on the project's machines, against 0.25 s of computing for a small
//   forward run of a calibration. A singleton needs no network: with the ob1 messaging layer
//   (shared memory and self) and without the daemon it starts in 0.4 s.
// - Concurrency. All singletons of a user share one session directory,
//   <tmp>/ompi.<host>.<uid>/jf.0, which each creates at MPI_Init and the last one out removes at
//   MPI_Finalize. One singleton finishing while another starts can remove the directory between
//   the other's mkdir calls; the other then aborts in MPI_Init ("A call to mkdir was unable to
//   create the desired directory"). Calibrations and studies start many singletons side by side,
//   so each gets a private directory for OpenMPI's session files instead.
#pragma once

#include <string>
#include <vector>

namespace indentsim::io
{
  // Construct before MPI_Init, call take_back() after it, and let it go out of scope after
  // MPI_Finalize (declare it before deal.II's MPI_InitFinalize):
  //
  //   io::SingletonStartup singleton;
  //   dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, ...);
  //   singleton.take_back();
  //
  // A launched rank is recognised by the variables a launcher gives its ranks
  // (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK, PMI_SIZE, SLURM_PROCID) and left alone. For a
  // singleton the constructor sets, for MPI_Init:
  // - OMPI_MCA_pml=ob1 and OMPI_MCA_ess_singleton_isolated=1, unless the user chose either;
  // - OMPI_MCA_orte_tmpdir_base to a new directory <TMPDIR or /tmp>/indentsim-mpi-<pid>-XXXXXX,
  //   unless the user chose it. The destructor removes that directory; one left behind by a
  //   process killed by a signal is removed by the next singleton that starts.
  class SingletonStartup
  {
  public:
    SingletonStartup();
    ~SingletonStartup();
    SingletonStartup(const SingletonStartup &) = delete;
    SingletonStartup &operator=(const SingletonStartup &) = delete;

    // Removes the variables again, so that the processes this one starts (the forward runs of
    // a study or a calibration, perhaps through a launcher onto other nodes) choose for
    // themselves.
    void take_back();

    // The names of the variables the constructor set (empty for a launched rank).
    const std::vector<std::string> &settings() const { return settings_; }

    // The private session directory, or "" if none was made.
    const std::string &session_directory() const { return session_directory_; }

  private:
    std::vector<std::string> settings_;
    std::string              session_directory_;
  };
} // namespace indentsim::io
