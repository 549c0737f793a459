#include "output/Checkpoint.h"

#include <stdexcept>

namespace indentsim::output::checkpoint
{
  namespace
  {
    volatile std::sig_atomic_t stop_flag = 0;

    void on_stop_signal(const int signal_number)
    {
      stop_flag = 1;
      // A second signal takes the default action (ends the process).
      std::signal(signal_number, SIG_DFL);
    }
  } // namespace

  std::string rank_file(const std::string &checkpoint_directory, const unsigned int rank)
  {
    return checkpoint_directory + "/rank_" + std::to_string(rank) + ".bin";
  }

  std::uint64_t fingerprint(const std::string &text)
  {
    std::uint64_t hash = 14695981039346656037ull;
    for (const unsigned char c : text)
      {
        hash ^= c;
        hash *= 1099511628211ull;
      }
    return hash;
  }

  Writer::Writer(const std::string &path)
    : file_(path)
    , out_(file_.stream())
  {
  }

  void Writer::string(const std::string &s)
  {
    value<std::uint64_t>(s.size());
    out_.write(s.data(), std::streamsize(s.size()));
  }

  Reader::Reader(const std::string &path)
    : path_(path)
    , in_(path, std::ios::binary)
  {
    if (!in_)
      throw std::runtime_error("checkpoint: cannot read '" + path + "'");
  }

  std::string Reader::string()
  {
    const auto n = value<std::uint64_t>();
    if (n > (std::uint64_t(1) << 32))
      fail();
    std::string s(n, '\0');
    in_.read(s.data(), std::streamsize(n));
    check();
    return s;
  }

  void Reader::check()
  {
    if (!in_)
      fail();
  }

  void Reader::fail()
  {
    throw std::runtime_error("checkpoint: '" + path_ + "' is truncated or corrupt");
  }

  StopRequest::StopRequest()
  {
    stop_flag = 0;
    previous_interrupt_ = std::signal(SIGINT, on_stop_signal);
    previous_terminate_ = std::signal(SIGTERM, on_stop_signal);
    // A process started to ignore SIGINT (nohup, a background job of a script) keeps ignoring it.
    if (previous_interrupt_ == SIG_IGN)
      std::signal(SIGINT, SIG_IGN);
  }

  StopRequest::~StopRequest()
  {
    std::signal(SIGINT, previous_interrupt_ == SIG_ERR ? SIG_DFL : previous_interrupt_);
    std::signal(SIGTERM, previous_terminate_ == SIG_ERR ? SIG_DFL : previous_terminate_);
  }

  bool StopRequest::requested()
  {
    return stop_flag != 0;
  }

  void StopRequest::clear()
  {
    stop_flag = 0;
  }
} // namespace indentsim::output::checkpoint
