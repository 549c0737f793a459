// How the executable starts MPI without a launcher (io/MpiStartup.h): a singleton gets OpenMPI's
// ob1 messaging layer and no helper daemon for MPI_Init, unless its user chose either, and a
// private session directory, removed at the end; the settings are removed again after MPI_Init.
#include "io/MpiStartup.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace
{
  // Every variable the function reads or writes, saved and cleared for one test and restored
  // after it (the test binary itself may run under mpirun).
  class CleanEnvironment
  {
  public:
    CleanEnvironment()
    {
      for (const char *name : names)
        {
          const char *value = std::getenv(name);
          saved_[name] = value ? std::optional<std::string>(value) : std::nullopt;
          unsetenv(name);
        }
    }
    ~CleanEnvironment()
    {
      for (const auto &[name, value] : saved_)
        if (value)
          setenv(name.c_str(), value->c_str(), 1);
        else
          unsetenv(name.c_str());
    }

  private:
    static constexpr const char                      *names[] = {"OMPI_COMM_WORLD_SIZE",
                                                                 "PMIX_RANK",
                                                                 "PMI_RANK",
                                                                 "PMI_SIZE",
                                                                 "SLURM_PROCID",
                                                                 "OMPI_MCA_pml",
                                                                 "OMPI_MCA_ess_singleton_isolated",
                                                                 "OMPI_MCA_orte_tmpdir_base",
                                                                 "TMPDIR"};
    std::map<std::string, std::optional<std::string>> saved_;
  };

  std::string value_of(const char *name)
  {
    const char *value = std::getenv(name);
    return value ? value : "(unset)";
  }
} // namespace

TEST(MpiStartup, SingletonGetsSharedMemoryTransportsAndItsOwnSessionDirectory)
{
  const CleanEnvironment clean;
  const std::string      tmp = ::testing::TempDir() + "mpi_startup_" + std::to_string(getpid());
  std::filesystem::create_directories(tmp);
  setenv("TMPDIR", tmp.c_str(), 1);
  std::string directory;
  {
    indentsim::io::SingletonStartup singleton;
    EXPECT_EQ(singleton.settings(),
              (std::vector<std::string>{"OMPI_MCA_pml", "OMPI_MCA_ess_singleton_isolated",
                                        "OMPI_MCA_orte_tmpdir_base"}));
    EXPECT_EQ(value_of("OMPI_MCA_pml"), "ob1");
    EXPECT_EQ(value_of("OMPI_MCA_ess_singleton_isolated"), "1");
    directory = singleton.session_directory();
    EXPECT_EQ(value_of("OMPI_MCA_orte_tmpdir_base"), directory);
    EXPECT_EQ(std::filesystem::path(directory).parent_path(), std::filesystem::path(tmp));
    EXPECT_TRUE(std::filesystem::is_directory(directory));

    // A second process starting beside this one gets a directory of its own.
    unsetenv("OMPI_MCA_orte_tmpdir_base");
    {
      const indentsim::io::SingletonStartup other;
      EXPECT_FALSE(other.session_directory().empty());
      EXPECT_NE(other.session_directory(), directory);
    }
    setenv("OMPI_MCA_orte_tmpdir_base", directory.c_str(), 1);

    singleton.take_back();
    EXPECT_EQ(value_of("OMPI_MCA_pml"), "(unset)");
    EXPECT_EQ(value_of("OMPI_MCA_ess_singleton_isolated"), "(unset)");
    EXPECT_EQ(value_of("OMPI_MCA_orte_tmpdir_base"), "(unset)");
    // OpenMPI's session files, as MPI_Init leaves them there.
    std::filesystem::create_directories(directory + "/ompi.host.0/jf.0/1");
    EXPECT_EQ(std::filesystem::path(directory).filename().string().rfind(
                  "indentsim-mpi-" + std::to_string(getpid()) + "-", 0),
              0u);
    EXPECT_TRUE(std::filesystem::is_directory(directory));
  }
  EXPECT_FALSE(std::filesystem::exists(directory)); // removed with what OpenMPI left in it
  EXPECT_TRUE(std::filesystem::is_empty(tmp));
  std::filesystem::remove(tmp);
}

TEST(MpiStartup, LaunchedRanksAndUsersChoicesAreLeftAlone)
{
  for (const char *launcher : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    {
      const CleanEnvironment clean;
      setenv(launcher, "0", 1);
      const indentsim::io::SingletonStartup singleton;
      EXPECT_TRUE(singleton.settings().empty()) << launcher;
      EXPECT_TRUE(singleton.session_directory().empty()) << launcher;
      EXPECT_EQ(value_of("OMPI_MCA_pml"), "(unset)") << launcher;
      EXPECT_EQ(value_of("OMPI_MCA_orte_tmpdir_base"), "(unset)") << launcher;
    }
  {
    const CleanEnvironment clean;
    setenv("OMPI_MCA_pml", "ucx", 1);
    const indentsim::io::SingletonStartup singleton;
    EXPECT_EQ(singleton.settings(), (std::vector<std::string>{"OMPI_MCA_orte_tmpdir_base"}));
    EXPECT_EQ(value_of("OMPI_MCA_pml"), "ucx");
    EXPECT_EQ(value_of("OMPI_MCA_ess_singleton_isolated"), "(unset)");
  }
  const CleanEnvironment clean;
  setenv("OMPI_MCA_orte_tmpdir_base", "/var/tmp", 1);
  const indentsim::io::SingletonStartup singleton;
  EXPECT_EQ(singleton.settings(),
            (std::vector<std::string>{"OMPI_MCA_pml", "OMPI_MCA_ess_singleton_isolated"}));
  EXPECT_TRUE(singleton.session_directory().empty());
  EXPECT_EQ(value_of("OMPI_MCA_orte_tmpdir_base"), "/var/tmp");
}

// A process killed by a signal cannot remove its directory; the next singleton removes it, and
// only it: the directories of living processes (this one, init) and other files stay.
TEST(MpiStartup, TheDirectoryOfAKilledProcessIsRemovedByTheNextSingleton)
{
  const CleanEnvironment clean;
  const std::string      tmp =
      ::testing::TempDir() + "mpi_startup_abandoned_" + std::to_string(getpid());
  std::filesystem::remove_all(tmp);
  std::filesystem::create_directories(tmp);
  setenv("TMPDIR", tmp.c_str(), 1);
  const pid_t child = fork();
  if (child == 0)
    _exit(0);
  ASSERT_GT(child, 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child); // the child has ended: its pid is free
  const std::string dead = tmp + "/indentsim-mpi-" + std::to_string(child) + "-abcdef";
  const std::string alive = tmp + "/indentsim-mpi-" + std::to_string(getpid()) + "-abcdef";
  const std::string init = tmp + "/indentsim-mpi-1-abcdef";
  const std::string other = tmp + "/indentsim-mpi-notapid";
  for (const std::string &d : {dead, alive, init, other})
    std::filesystem::create_directories(d + "/ompi.host.0/jf.0/1");
  {
    const indentsim::io::SingletonStartup singleton;
    EXPECT_FALSE(std::filesystem::exists(dead));
    for (const std::string &d : {alive, init, other})
      EXPECT_TRUE(std::filesystem::exists(d)) << d;
  }
  std::filesystem::remove_all(tmp);
}
