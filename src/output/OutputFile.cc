// Output files whose failures are never silent (see OutputFile.h).
#include "output/OutputFile.h"

#include <deal.II/base/mpi.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <streambuf>
#include <unistd.h>
#include <vector>

namespace indentsim::output
{
  OutputError::OutputError(const std::string &file, const std::string &reason)
    : std::runtime_error("cannot write '" + file + "': " + reason)
    , file_(file)
    , reason_(reason)
  {
  }

  std::string system_reason(const int error_number)
  {
    return std::strerror(error_number);
  }

  // A stream buffer on a POSIX file descriptor that keeps the errno of the first failed write
  // (std::ofstream only reports that something failed, not why).
  class DescriptorBuffer : public std::streambuf
  {
  public:
    explicit DescriptorBuffer(const int descriptor)
      : descriptor_(descriptor)
      , buffer_(1 << 16)
    {
      setp(buffer_.data(), buffer_.data() + buffer_.size());
    }

    // The errno of the first failure, 0 if none.
    int error() const { return error_; }

  protected:
    int_type overflow(const int_type c) override
    {
      if (!drain())
        return traits_type::eof();
      if (!traits_type::eq_int_type(c, traits_type::eof()))
        {
          *pptr() = traits_type::to_char_type(c);
          pbump(1);
        }
      return traits_type::not_eof(c);
    }

    int sync() override { return drain() ? 0 : -1; }

  private:
    bool drain()
    {
      const char *data = pbase();
      std::size_t n = static_cast<std::size_t>(pptr() - pbase());
      setp(buffer_.data(), buffer_.data() + buffer_.size());
      if (error_ != 0)
        return false;
      while (n > 0)
        {
          const ssize_t written = ::write(descriptor_, data, n);
          if (written < 0 && errno == EINTR)
            continue;
          if (written <= 0)
            {
              error_ = written < 0 ? errno : EIO;
              return false;
            }
          data += written;
          n -= static_cast<std::size_t>(written);
        }
      return true;
    }

    int               descriptor_;
    std::vector<char> buffer_;
    int               error_ = 0;
  };

  AtomicFile::AtomicFile(const std::string &path)
    : path_(path)
    , temporary_(path + ".tmp")
  {
    descriptor_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (descriptor_ < 0)
      throw OutputError(path_, system_reason(errno));
    buffer_ = std::make_unique<DescriptorBuffer>(descriptor_);
    stream_ = std::make_unique<std::ostream>(buffer_.get());
  }

  AtomicFile::~AtomicFile()
  {
    if (descriptor_ >= 0)
      ::close(descriptor_);
    if (!committed_)
      ::unlink(temporary_.c_str());
  }

  void AtomicFile::fail(const int error_number)
  {
    if (descriptor_ >= 0)
      ::close(descriptor_);
    descriptor_ = -1;
    ::unlink(temporary_.c_str());
    throw OutputError(path_, system_reason(error_number));
  }

  void AtomicFile::close()
  {
    if (descriptor_ < 0)
      return;
    stream_->flush();
    int error = buffer_->error();
    if (error == 0 && !*stream_)
      error = EIO; // a failure of the formatting itself, with no system error
    // fsync before the rename: after a crash the file at path_ is complete, old or new. A
    // special file (a device) cannot be synchronised (EINVAL, EROFS): nothing to keep then.
    if (error == 0 && ::fsync(descriptor_) != 0 && errno != EINVAL && errno != EROFS)
      error = errno;
    if (error != 0)
      fail(error);
    const int closed = ::close(descriptor_);
    descriptor_ = -1;
    if (closed != 0)
      fail(errno);
  }

  void AtomicFile::commit()
  {
    close();
    if (::rename(temporary_.c_str(), path_.c_str()) != 0)
      fail(errno);
    committed_ = true;
  }

  void write_file(const std::string &path, const std::function<void(std::ostream &)> &write)
  {
    AtomicFile file(path);
    write(file.stream());
    file.commit();
  }

  void write_file(const std::string &path, const std::string &text)
  {
    write_file(path, [&](std::ostream &out) { out << text; });
  }

  AppendFile::AppendFile() = default;

  AppendFile::~AppendFile()
  {
    if (descriptor_ >= 0)
      {
        stream_->flush();
        ::close(descriptor_);
      }
  }

  void AppendFile::open(const std::string &path)
  {
    path_ = path;
    descriptor_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0666);
    if (descriptor_ < 0)
      throw OutputError(path, system_reason(errno));
    buffer_ = std::make_unique<DescriptorBuffer>(descriptor_);
    stream_ = std::make_unique<std::ostream>(buffer_.get());
  }

  void AppendFile::flush()
  {
    if (descriptor_ < 0)
      return;
    stream_->flush();
    if (buffer_->error() != 0)
      throw OutputError(path_, system_reason(buffer_->error()));
    if (!*stream_)
      throw OutputError(path_, system_reason(EIO));
  }

  void write_collectively(const MPI_Comm communicator, const std::function<void()> &write)
  {
    // This rank's failure as "file\0reason", empty if it succeeded.
    std::string failure;
    try
      {
        write();
      }
    catch (const OutputError &e)
      {
        failure = e.file() + '\0' + (e.reason().empty() ? "unknown reason" : e.reason());
      }
    const std::vector<std::string> failures =
        dealii::Utilities::MPI::n_mpi_processes(communicator) == 1
            ? std::vector<std::string>{failure}
            : dealii::Utilities::MPI::all_gather(communicator, failure);
    for (const std::string &f : failures)
      if (!f.empty())
        {
          const std::size_t separator = f.find('\0');
          throw OutputError(f.substr(0, separator), f.substr(separator + 1));
        }
  }
} // namespace indentsim::output
