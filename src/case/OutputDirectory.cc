// Protection of an output directory (see OutputDirectory.h).
#include "case/OutputDirectory.h"
#include "case/CaseFile.h"
#include "output/OutputFile.h"

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <vector>

namespace indentsim::io
{
  namespace
  {
    namespace fs = std::filesystem;

    // The output-directory entries that belong to an earlier run.
    bool is_known_output_file(const fs::path &path)
    {
      const std::string name = path.filename().string();
      for (const char *known : output_files::known_names)
        if (name == known)
          return true;
      if (name.rfind(output_files::paraview_basename, 0) == 0)
        for (const char *extension : output_files::paraview_extensions)
          if (path.extension() == extension)
            return true;
      return false;
    }

    std::vector<fs::path> earlier_results(const fs::path &directory)
    {
      std::vector<fs::path> found;
      std::error_code       error;
      for (const auto &entry : fs::directory_iterator(directory, error))
        if ((entry.is_regular_file(error) && is_known_output_file(entry.path())) ||
            (entry.is_directory(error) &&
             entry.path().filename() == output_files::checkpoint_directory))
          found.push_back(entry.path());
      std::sort(found.begin(), found.end());
      return found;
    }
  } // namespace

  void prepare_output_directory(const std::string &directory, bool overwrite)
  {
    if (directory.empty())
      throw CaseFileError("output directory: the path is empty");
    const fs::path  dir(directory);
    std::error_code error;

    if (fs::exists(dir, error) && !fs::is_directory(dir, error))
      throw CaseFileError("output directory '" + directory +
                          "' exists but is not a directory; choose another one with --output DIR");
    fs::create_directories(dir, error);
    if (error || !fs::is_directory(dir))
      throw CaseFileError("output directory '" + directory + "' cannot be created" +
                          (error ? ": " + error.message() : std::string()));

    const std::vector<fs::path> earlier = earlier_results(dir);
    if (!earlier.empty())
      {
        if (!overwrite)
          throw CaseFileError(
              "output directory '" + directory + "' already contains results of an earlier run (" +
              earlier.front().filename().string() +
              (earlier.size() > 1 ? " and " + std::to_string(earlier.size() - 1) + " more"
                                  : std::string()) +
              "); pass --overwrite to replace them, or choose another directory "
              "(--output DIR or output.directory)");
        for (const auto &file : earlier)
          {
            if (fs::is_directory(file, error)) // only the checkpoint folder
              fs::remove_all(file, error);
            else
              fs::remove(file, error);
            if (error)
              throw CaseFileError("output directory '" + directory + "': cannot remove '" +
                                  file.string() + "': " + error.message());
          }
      }

    // Permission bits do not tell the whole story (read-only mounts, ACLs, root): try it.
    const fs::path probe = dir / ".indentsim_write_probe";
    try
      {
        output::write_file(probe.string(), "probe\n");
      }
    catch (const output::OutputError &e)
      {
        throw CaseFileError("output directory '" + directory + "' is not writable (" + e.reason() +
                            "); choose another one with --output DIR");
      }
    fs::remove(probe, error);
  }
} // namespace indentsim::io
