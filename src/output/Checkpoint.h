// Binary checkpoint files of a stopped run (IndentationProblem::run with --resume): a small
// writer and reader of plain values, strings and vectors, the case fingerprint, and the
// stop request set by SIGINT/SIGTERM.
//
// One file per MPI rank, <output>/checkpoint/rank_<r>.bin. Each starts with a header (magic,
// format version, rank count, this rank, the case fingerprint, the step) so that a checkpoint of
// another case, another rank count or another format is refused with a message instead of
// being read as garbage. The files hold the machine's native byte order: a checkpoint is
// resumed on the machine (or the cluster) that wrote it.
#pragma once

#include "output/OutputFile.h"

#include <csignal>
#include <cstdint>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

namespace indentsim::output::checkpoint
{
  inline constexpr char          magic[8] = {'I', 'N', 'D', 'C', 'K', 'P', 'T', '\0'};
  inline constexpr std::uint32_t format_version = 3;
  // The folder in the output directory (io::output_files::checkpoint_directory).
  std::string rank_file(const std::string &checkpoint_directory, unsigned int rank);

  // FNV-1a 64-bit hash of `text`: the fingerprint of the resolved case.
  std::uint64_t fingerprint(const std::string &text);

  class Writer
  {
  public:
    // Writes to `path`.tmp (output::AtomicFile); close() flushes and fsyncs it, commit() renames
    // it to `path`, so that the file at `path` is either the previous complete checkpoint or the
    // new complete one. An MPI run closes every rank's file, agrees that all succeeded, and only
    // then commits: the ranks' checkpoints stay of one step. Both throw OutputError naming the
    // file and the system's reason; a Writer destroyed before commit() removes its temporary
    // file.
    explicit Writer(const std::string &path);
    template <typename T>
    void value(const T &v)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      out_.write(reinterpret_cast<const char *>(&v), sizeof(T));
    }
    void string(const std::string &s);
    template <typename T>
    void vector(const std::vector<T> &v)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      value<std::uint64_t>(v.size());
      out_.write(reinterpret_cast<const char *>(v.data()), std::streamsize(v.size() * sizeof(T)));
    }
    void close() { file_.close(); }
    void commit() { file_.commit(); }

  private:
    AtomicFile    file_;
    std::ostream &out_;
  };

  class Reader
  {
  public:
    // Throws std::runtime_error if the file cannot be opened.
    explicit Reader(const std::string &path);
    template <typename T>
    T value()
    {
      static_assert(std::is_trivially_copyable_v<T>);
      T v;
      in_.read(reinterpret_cast<char *>(&v), sizeof(T));
      check();
      return v;
    }
    std::string string();
    template <typename T>
    std::vector<T> vector()
    {
      static_assert(std::is_trivially_copyable_v<T>);
      const auto n = value<std::uint64_t>();
      if (n > (std::uint64_t(1) << 40) / sizeof(T))
        fail();
      std::vector<T> v(n);
      in_.read(reinterpret_cast<char *>(v.data()), std::streamsize(n * sizeof(T)));
      check();
      return v;
    }
    const std::string &path() const { return path_; }

  private:
    void              check();
    [[noreturn]] void fail();
    std::string       path_;
    std::ifstream     in_;
  };

  // SIGINT and SIGTERM set a flag (and restore the default action, so that a second Ctrl-C
  // ends the process at once) while a StopRequest lives; its destructor restores the previous
  // handlers.
  class StopRequest
  {
  public:
    StopRequest();
    ~StopRequest();
    StopRequest(const StopRequest &) = delete;
    StopRequest &operator=(const StopRequest &) = delete;
    // Whether a signal arrived (this process only; reduce over the ranks before acting).
    static bool requested();
    static void clear();

  private:
    using Handler = void (*)(int);
    Handler previous_interrupt_, previous_terminate_;
  };
} // namespace indentsim::output::checkpoint
