#include "io/MpiStartup.h"

#include <array>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace indentsim::io
{
  namespace
  {
    bool launched()
    {
      constexpr std::array launcher_variables = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK",
                                                 "PMI_SIZE", "SLURM_PROCID"};
      for (const char *name : launcher_variables)
        if (std::getenv(name) != nullptr)
          return true;
      return false;
    }

    // A new directory <TMPDIR or /tmp>/indentsim-mpi-XXXXXX, or "" if it cannot be made (then
    // OpenMPI uses its shared one, and says so if that fails too).
    std::string make_session_directory()
    {
      const char *tmp = std::getenv("TMPDIR");
      std::string path = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") +
                         "/indentsim-mpi-XXXXXX";
      return mkdtemp(path.data()) != nullptr ? path : std::string();
    }
  } // namespace

  SingletonStartup::SingletonStartup()
  {
    if (launched())
      return;
    struct Setting
    {
      const char *name, *value;
    };
    constexpr std::array<Setting, 2> transports = {
        {{"OMPI_MCA_pml", "ob1"}, {"OMPI_MCA_ess_singleton_isolated", "1"}}};
    bool user_chose = false;
    for (const Setting &setting : transports)
      user_chose = user_chose || std::getenv(setting.name) != nullptr;
    if (!user_chose)
      for (const Setting &setting : transports)
        if (setenv(setting.name, setting.value, /*overwrite=*/0) == 0)
          settings_.emplace_back(setting.name);

    constexpr const char *tmpdir_base = "OMPI_MCA_orte_tmpdir_base";
    if (std::getenv(tmpdir_base) == nullptr)
      {
        session_directory_ = make_session_directory();
        if (!session_directory_.empty() &&
            setenv(tmpdir_base, session_directory_.c_str(), /*overwrite=*/0) == 0)
          settings_.emplace_back(tmpdir_base);
      }
  }

  SingletonStartup::~SingletonStartup()
  {
    if (session_directory_.empty())
      return;
    std::error_code ignored; // a directory left in /tmp is no reason to fail a finished run
    std::filesystem::remove_all(session_directory_, ignored);
  }

  void SingletonStartup::take_back()
  {
    for (const std::string &name : settings_)
      unsetenv(name.c_str());
  }
} // namespace indentsim::io
