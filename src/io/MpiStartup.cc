#include "io/MpiStartup.h"

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <sys/types.h>
#include <unistd.h>

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

    constexpr const char *session_prefix = "indentsim-mpi-";

    // Removes the session directories <prefix><pid>-XXXXXX in `tmp` whose process has ended
    // without removing its own (killed by a signal). A directory is listed before its process is
    // looked for, so a process started after the listing under a reused pid is never mistaken
    // for the dead one; a process that cannot be signalled (another user's) counts as alive.
    void remove_abandoned_session_directories(const std::filesystem::path &tmp)
    {
      std::error_code                    error;
      std::vector<std::filesystem::path> listed;
      for (const auto &entry : std::filesystem::directory_iterator(tmp, error))
        if (entry.path().filename().string().rfind(session_prefix, 0) == 0)
          listed.push_back(entry.path());
      for (const std::filesystem::path &path : listed)
        {
          const std::string name = path.filename().string().substr(std::strlen(session_prefix));
          char             *end = nullptr;
          const long        pid = std::strtol(name.c_str(), &end, 10);
          if (pid > 0 && *end == '-' && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH)
            std::filesystem::remove_all(path, error);
        }
    }

    // A new directory <TMPDIR or /tmp>/indentsim-mpi-<pid>-XXXXXX, or "" if it cannot be made
    // (then OpenMPI uses its shared one, and says so if that fails too).
    std::string make_session_directory()
    {
      const char       *tmpdir = std::getenv("TMPDIR");
      const std::string tmp = tmpdir != nullptr && *tmpdir != '\0' ? tmpdir : "/tmp";
      remove_abandoned_session_directories(tmp);
      std::string path = tmp + "/" + session_prefix + std::to_string(::getpid()) + "-XXXXXX";
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
