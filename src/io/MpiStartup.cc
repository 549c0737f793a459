#include "io/MpiStartup.h"

#include <array>
#include <cstdlib>

namespace indentsim::io
{
  std::vector<std::string> choose_singleton_settings()
  {
    constexpr std::array launcher_variables = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK",
                                               "PMI_SIZE", "SLURM_PROCID"};
    for (const char *name : launcher_variables)
      if (std::getenv(name) != nullptr)
        return {};
    struct Setting
    {
      const char *name, *value;
    };
    constexpr std::array<Setting, 2> settings = {
        {{"OMPI_MCA_pml", "ob1"}, {"OMPI_MCA_ess_singleton_isolated", "1"}}};
    for (const Setting &setting : settings)
      if (std::getenv(setting.name) != nullptr)
        return {};
    std::vector<std::string> set;
    for (const Setting &setting : settings)
      if (setenv(setting.name, setting.value, /*overwrite=*/0) == 0)
        set.emplace_back(setting.name);
    return set;
  }

  void take_back_singleton_settings(const std::vector<std::string> &names)
  {
    for (const std::string &name : names)
      unsetenv(name.c_str());
  }
} // namespace indentsim::io
