// Writing output files so that a failure is never silent and never leaves a truncated file in
// place of a good one.
//
// Every write goes through a POSIX file descriptor, so that the system's reason of a failure
// (errno: "No space left on device", "Read-only file system", ...) is known, and every failure
// raises OutputError naming the file and that reason (apps/indentsim.cc: exit code 4).
//   - A file written as a whole (VTU, PVTU, PVD, JSON, pile-up CSV, resolved_case.yaml, a
//     checkpoint) goes to `<file>.tmp` in the same directory, is flushed and fsynced, and only
//     then renamed over `<file>`: the file at its name is the previous complete one or the new
//     complete one, never a partial one. A failed temporary file is removed.
//   - A file that grows record by record (load_penetration.csv, run.log, stress_strain.csv) is
//     flushed after every record and its state checked.
// In an MPI run a failure on one rank must stop every rank at the same point: write_collectively()
// agrees on the outcome of a write over the ranks.
#pragma once

#include <mpi.h>

#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

namespace indentsim::output
{
  // An output file could not be written. what(): "cannot write 'FILE': REASON".
  class OutputError : public std::runtime_error
  {
  public:
    OutputError(const std::string &file, const std::string &reason);
    const std::string &file() const { return file_; }
    const std::string &reason() const { return reason_; }

  private:
    std::string file_, reason_;
  };

  // The system's text for an errno value ("No space left on device").
  std::string system_reason(int error_number);

  class DescriptorBuffer;

  // A file written as a whole, through `<path>.tmp`. stream() takes the content; close() flushes,
  // fsyncs and closes the temporary file, commit() (after close() if not yet done) renames it to
  // `path`. Both throw OutputError naming `path` and the system's reason, after removing the
  // temporary file. Destroyed without commit(), it removes the temporary file and leaves `path`
  // as it was.
  class AtomicFile
  {
  public:
    explicit AtomicFile(const std::string &path);
    ~AtomicFile();
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    std::ostream      &stream() { return *stream_; }
    const std::string &path() const { return path_; }
    void               close();
    void               commit();

  private:
    [[noreturn]] void fail(int error_number);

    std::string                       path_, temporary_;
    int                               descriptor_ = -1;
    bool                              committed_ = false;
    std::unique_ptr<DescriptorBuffer> buffer_;
    std::unique_ptr<std::ostream>     stream_;
  };

  // Writes the whole file `path` (through AtomicFile) with `write`, or `text`.
  void write_file(const std::string &path, const std::function<void(std::ostream &)> &write);
  void write_file(const std::string &path, const std::string &text);

  // A file that grows by records: opened for appending (created if missing, never truncated);
  // flush() after each record throws OutputError if anything since the last flush failed.
  class AppendFile
  {
  public:
    AppendFile();
    ~AppendFile();
    AppendFile(const AppendFile &) = delete;
    AppendFile &operator=(const AppendFile &) = delete;

    // Throws OutputError if `path` cannot be opened.
    void               open(const std::string &path);
    bool               is_open() const { return descriptor_ >= 0; }
    std::ostream      &stream() { return *stream_; }
    const std::string &path() const { return path_; }
    void               flush();

  private:
    std::string                       path_;
    int                               descriptor_ = -1;
    std::unique_ptr<DescriptorBuffer> buffer_;
    std::unique_ptr<std::ostream>     stream_;
  };

  // Collective over `communicator`: runs `write` on this rank (it may do nothing on some ranks)
  // and, if it threw OutputError on any rank, throws that of the lowest such rank on every rank.
  // No rank is left waiting in a later collective call for one that failed.
  void write_collectively(MPI_Comm communicator, const std::function<void()> &write);
} // namespace indentsim::output
