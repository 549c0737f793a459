// Locating the Python helpers from the executable's own path (see PythonScripts.h).
#include "output/PythonScripts.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace indentsim::output
{
  namespace
  {
    namespace fs = std::filesystem;

    const char *const environment_override = "INDENTSIM_PYTHON_DIR";
    const char *const share_folder = "share/indentsim/python";

    fs::path executable_folder()
    {
      std::error_code error;
      const fs::path  executable = fs::read_symlink("/proc/self/exe", error);
      return error ? fs::current_path(error) : executable.parent_path();
    }
  } // namespace

  std::vector<std::string> python_script_folders()
  {
    std::vector<std::string> folders;
    if (const char *override_folder = std::getenv(environment_override);
        override_folder != nullptr && *override_folder != '\0')
      folders.emplace_back(override_folder);
    const fs::path executable = executable_folder();
    folders.push_back((executable.parent_path() / share_folder).lexically_normal().string());
    folders.push_back((executable / share_folder).lexically_normal().string());
    return folders;
  }

  std::string python_script(const std::string &name)
  {
    const std::vector<std::string> folders = python_script_folders();
    std::error_code                error;
    for (const auto &folder : folders)
      if (fs::is_regular_file(fs::path(folder) / name, error))
        return (fs::path(folder) / name).string();

    std::cerr << "warning: the Python helper " << name << " was not found; looked in";
    for (const auto &folder : folders)
      std::cerr << ' ' << folder;
    std::cerr << " (set " << environment_override << " to the folder that holds it)\n";
    return (fs::path(folders.front()) / name).string();
  }

  namespace
  {
    bool plots_switched_on = true;
  }

  void set_plots_enabled(const bool enabled)
  {
    plots_switched_on = enabled;
  }

  bool plots_enabled()
  {
    return plots_switched_on;
  }

  bool draw_plot(const std::string &script_name, const std::vector<std::string> &arguments,
                 const std::string &what, std::ostream &warnings)
  {
    if (!plots_switched_on)
      return false;
    std::string command = "python3 \"" + python_script(script_name) + "\"";
    for (const std::string &argument : arguments)
      command += " \"" + argument + "\"";
    if (std::system(command.c_str()) == 0)
      return true;
    warnings << "warning: the plot " << what << " could not be written (command: " << command
             << ")\n";
    return false;
  }
} // namespace indentsim::output
