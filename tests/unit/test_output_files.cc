// Output files whose failures are never silent (output/OutputFile.h, output/RunRecorder.h) and
// the keys named when a resumed case differs (case/Fingerprint.h). A full disk is simulated by
// /dev/full (every write fails with ENOSPC), reached through a symbolic link at the file's
// temporary name; a file-size limit (RLIMIT_FSIZE, EFBIG) makes appends fail after the files
// were opened.
#include "../test_cases.h"
#include "../test_files.h"
#include "case/CaseFile.h"
#include "case/Fingerprint.h"
#include "output/OutputFile.h"
#include "output/RunRecorder.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>

using namespace indentsim;
namespace fs = std::filesystem;

namespace
{
  const std::string no_space = std::strerror(ENOSPC); // "No space left on device"

  // The OutputError thrown by `action`, or a failed test.
  template <typename Action>
  output::OutputError output_error_of(const Action &action)
  {
    try
      {
        action();
      }
    catch (const output::OutputError &e)
      {
        return e;
      }
    ADD_FAILURE() << "no OutputError thrown";
    return output::OutputError("", "");
  }

  // The file's temporary name leads to /dev/full: the next write of the file fails with ENOSPC.
  void redirect_to_full_device(const fs::path &file)
  {
    ASSERT_TRUE(fs::exists("/dev/full")) << "/dev/full is needed to simulate a full disk";
    fs::create_symlink("/dev/full", file.string() + ".tmp");
  }
} // namespace

// Requirement: a whole-file write that fails names the file and the system's reason, leaves the
// previous file unchanged and no temporary file behind.
TEST(OutputFile, FailedWriteNamesFileAndReasonAndKeepsThePreviousFile)
{
  const fs::path dir = test_files::scratch_directory("output_files", "atomic");
  const fs::path file = dir / "pileup.json";
  output::write_file(file.string(), "good\n");
  EXPECT_EQ(test_files::read_text(file), "good\n");
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));

  redirect_to_full_device(file);
  const output::OutputError error =
      output_error_of([&]() { output::write_file(file.string(), std::string(200000, 'x')); });
  EXPECT_EQ(error.file(), file.string());
  EXPECT_EQ(error.reason(), no_space);
  EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  EXPECT_NE(std::string(error.what()).find(no_space), std::string::npos) << error.what();
  EXPECT_EQ(test_files::read_text(file), "good\n"); // not truncated, not replaced
  EXPECT_FALSE(fs::exists(fs::symlink_status(file.string() + ".tmp")));
}

// Requirement: a small write that fits the stream's buffer fails at the flush of close(), and
// an AtomicFile abandoned before commit() leaves the previous file as it was.
TEST(OutputFile, FailureInTheLastBufferAndAbandonedFilesLeaveThePreviousFile)
{
  const fs::path dir = test_files::scratch_directory("output_files", "small");
  const fs::path file = dir / "resolved_case.yaml";
  output::write_file(file.string(), "old\n");
  {
    output::AtomicFile abandoned(file.string());
    abandoned.stream() << "new\n";
  }
  EXPECT_EQ(test_files::read_text(file), "old\n");
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));

  redirect_to_full_device(file);
  const output::OutputError error =
      output_error_of([&]() { output::write_file(file.string(), "x\n"); });
  EXPECT_EQ(error.reason(), no_space);
  EXPECT_EQ(test_files::read_text(file), "old\n");
}

// Requirement: an append-style file checks every flush: a record that cannot be written raises
// OutputError naming the file and the reason.
TEST(OutputFile, AppendFileFailsLoudlyOnTheFlush)
{
  const fs::path dir = test_files::scratch_directory("output_files", "append");
  const fs::path file = dir / "run.log";
  fs::create_symlink("/dev/full", file);
  output::AppendFile log;
  log.open(file.string());
  log.stream() << "# a line\n";
  const output::OutputError error = output_error_of([&]() { log.flush(); });
  EXPECT_EQ(error.file(), file.string());
  EXPECT_EQ(error.reason(), no_space);
}

// Requirement: when load_penetration.csv or run.log cannot take a further row (here a file-size
// limit reached after the run started), the recorder does not cut the file silently: it keeps
// the failure, writes nothing after it, and throw_if_failed() names the file and the reason.
TEST(OutputFile, RunRecorderReportsACutLogInsteadOfGoingOn)
{
  const fs::path        dir = test_files::scratch_directory("output_files", "recorder");
  output::RunRecorder   recorder;
  nonlinear::StepRecord record;
  recorder.open(dir.string(), {});
  recorder.csv_row(record);
  recorder.log_note("before the limit");
  EXPECT_NO_THROW(recorder.throw_if_failed());

  // No file may grow beyond the CSV's present size (the process ignores SIGXFSZ: writes fail
  // with EFBIG instead of ending it), so the next CSV row fails.
  rlimit previous{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &previous), 0);
  const auto   previous_handler = std::signal(SIGXFSZ, SIG_IGN);
  const rlimit limit{static_cast<rlim_t>(fs::file_size(dir / "load_penetration.csv")),
                     previous.rlim_max};
  const auto   log_size = fs::file_size(dir / "run.log");
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
  for (unsigned int step = 1; step <= 3; ++step)
    {
      record.step = step;
      recorder.csv_row(record);
      recorder.log_row(record);
    }
  ::setrlimit(RLIMIT_FSIZE, &previous);
  std::signal(SIGXFSZ, previous_handler);

  const output::OutputError error = output_error_of([&]() { recorder.throw_if_failed(); });
  EXPECT_EQ(error.file(), (dir / "load_penetration.csv").string());
  EXPECT_EQ(error.reason(), std::strerror(EFBIG));
  // Nothing is written after the first failure, not even to the other file.
  recorder.log_note("after the failure");
  EXPECT_EQ(fs::file_size(dir / "run.log"), log_size);
}

// Requirement: the keys named when a resumed case differs are exactly the keys of the
// fingerprint that differ, with the old and the new value; keys that do not determine the
// results (output.directory, output.checkpoint_interval_s, solver.threads) are not named.
TEST(CaseDifferences, NameTheResultKeysThatDifferWithOldAndNewValues)
{
  const io::Case base = test_cases::small_j2_case();
  io::Case       changed = base;
  EXPECT_TRUE(io::case_differences(base, changed).empty());
  changed.output.directory = "elsewhere";
  changed.output.checkpoint_interval_s = 17;
  changed.solver.threads = 3;
  EXPECT_TRUE(io::case_differences(base, changed).empty());
  EXPECT_EQ(io::case_fingerprint(base), io::case_fingerprint(changed));

  changed.material.yield_stress = 0.5;
  changed.loading.steps = base.loading.steps + 2;
  const std::vector<io::KeyDifference> differences = io::case_differences(base, changed);
  ASSERT_EQ(differences.size(), 2u);
  EXPECT_NE(io::case_fingerprint(base), io::case_fingerprint(changed));
  const auto find = [&](const std::string &path) {
    for (const io::KeyDifference &d : differences)
      if (d.path == path)
        return d;
    ADD_FAILURE() << path << " not named";
    return io::KeyDifference{};
  };
  const io::KeyDifference yield = find("material.yield_stress");
  EXPECT_EQ(yield.new_value, "0.5");
  EXPECT_NE(yield.old_value, yield.new_value);
  const io::KeyDifference steps = find("loading.steps");
  EXPECT_EQ(steps.old_value, std::to_string(base.loading.steps));
  EXPECT_EQ(steps.new_value, std::to_string(base.loading.steps + 2));
}
