// Scratch directories and file reading shared by the tests that run whole cases.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace indentsim::test_files
{
  namespace fs = std::filesystem;

  // A fresh, empty directory $INDENTSIM_TEST_TMP/<prefix>_<pid>/<name> (fallback root /tmp).
  inline fs::path scratch_directory(const std::string &prefix, const std::string &name)
  {
    const char    *root = std::getenv("INDENTSIM_TEST_TMP");
    const fs::path dir = fs::path(root != nullptr && *root != '\0' ? root : "/tmp") /
                         (prefix + "_" + std::to_string(::getpid())) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
  }

  inline std::string read_text(const fs::path &path)
  {
    std::ifstream      in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
} // namespace indentsim::test_files
