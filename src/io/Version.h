#pragma once
// indentsim's version and the git commit it was built from, e.g. "0.1.0 (git 62529ce1a2b3)",
// "0.1.0 (git 62529ce1a2b3-dirty)" for uncommitted changes, "0.1.0 (no git checkout)".
// Written into run logs, run_summary.json, study indexes and reports so that a result names the
// code that produced it. Defined in the build directory's generated/Version.cc
// (cmake/write_version.cmake, refreshed before every build).

namespace indentsim
{
  const char *version();
} // namespace indentsim
