// How the executable starts MPI without a launcher (io/MpiStartup.h): a singleton gets OpenMPI's
// ob1 messaging layer and no helper daemon for MPI_Init, and only a singleton whose user chose
// neither; the settings are removed again afterwards.
#include "io/MpiStartup.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <vector>

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
                                                                 "OMPI_MCA_ess_singleton_isolated"};
    std::map<std::string, std::optional<std::string>> saved_;
  };

  std::string value_of(const char *name)
  {
    const char *value = std::getenv(name);
    return value ? value : "(unset)";
  }
} // namespace

TEST(MpiStartup, SingletonGetsSharedMemoryTransportsUntilMpiInit)
{
  const CleanEnvironment   clean;
  std::vector<std::string> set = indentsim::io::choose_singleton_settings();
  EXPECT_EQ(set, (std::vector<std::string>{"OMPI_MCA_pml", "OMPI_MCA_ess_singleton_isolated"}));
  EXPECT_EQ(value_of("OMPI_MCA_pml"), "ob1");
  EXPECT_EQ(value_of("OMPI_MCA_ess_singleton_isolated"), "1");
  indentsim::io::take_back_singleton_settings(set);
  EXPECT_EQ(value_of("OMPI_MCA_pml"), "(unset)");
  EXPECT_EQ(value_of("OMPI_MCA_ess_singleton_isolated"), "(unset)");
}

TEST(MpiStartup, LaunchedRanksAndUsersChoicesAreLeftAlone)
{
  for (const char *launcher : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    {
      const CleanEnvironment clean;
      setenv(launcher, "0", 1);
      EXPECT_TRUE(indentsim::io::choose_singleton_settings().empty()) << launcher;
      EXPECT_EQ(value_of("OMPI_MCA_pml"), "(unset)") << launcher;
    }
  const CleanEnvironment clean;
  setenv("OMPI_MCA_pml", "ucx", 1);
  EXPECT_TRUE(indentsim::io::choose_singleton_settings().empty());
  EXPECT_EQ(value_of("OMPI_MCA_pml"), "ucx");
  EXPECT_EQ(value_of("OMPI_MCA_ess_singleton_isolated"), "(unset)");
}
