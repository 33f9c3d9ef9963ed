#include <lme_mpm/base/file_writing.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <streambuf>
#include <string>
#include <vector>

namespace lme_mpm
{
namespace files
{
namespace
{
/// The system's words for errno @p e.
std::string reason(const int e)
{
  return std::strerror(e);
}

/// Writes all of [data, data + n) to @p fd (at @p offset if not negative); returns 0
/// or the errno of the failure.
int write_all(const int fd, const char *data, std::size_t n, off_t offset = -1)
{
  while (n > 0)
  {
    const ssize_t w = offset < 0 ? ::write(fd, data, n) : ::pwrite(fd, data, n, offset);
    if (w < 0 && errno == EINTR)
      continue;
    if (w <= 0)
      return w < 0 ? errno : ENOSPC;
    data += w, n -= static_cast<std::size_t>(w);
    if (offset >= 0)
      offset += w;
  }
  return 0;
}

/// Keeps @p path as @p previous while @p path itself stays in place (a hard link),
/// so that a reader always finds @p path; a file system without hard links renames.
/// Returns 0 or the errno of the failure.
int keep_as_previous(const std::string &path, const std::string &previous)
{
  if (::access(path.c_str(), F_OK) != 0)
    return 0;
  if (::unlink(previous.c_str()) != 0 && errno != ENOENT)
    return errno;
  if (::link(path.c_str(), previous.c_str()) == 0)
    return 0;
  return std::rename(path.c_str(), previous.c_str()) == 0 ? 0 : errno;
}

/**
 * A stream buffer on a file descriptor that keeps the errno of its first failed
 * write: std::ofstream reports a failure but not its cause.
 */
class DescriptorBuffer : public std::streambuf
{
public:
  explicit DescriptorBuffer(const int fd) : fd(fd), buffer(1 << 16)
  {
    setp(buffer.data(), buffer.data() + buffer.size());
  }
  /// 0, or the errno of the first failed write.
  int error() const { return failure; }

protected:
  int_type overflow(const int_type c) override
  {
    if (sync() != 0)
      return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof()))
    {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override
  {
    if (failure == 0)
      failure = write_all(fd, pbase(), static_cast<std::size_t>(pptr() - pbase()));
    setp(buffer.data(), buffer.data() + buffer.size());
    return failure == 0 ? 0 : -1;
  }

private:
  int fd;
  std::vector<char> buffer;
  int failure = 0;
};
} // namespace

void write_atomically(const std::string &path,
                      const std::function<void(std::ostream &)> &write,
                      const bool keep_previous)
{
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  AssertThrow(fd >= 0, ExcCannotWrite(path, reason(errno)));
  int failure        = 0;
  const auto give_up = [&](const int e)
  {
    ::close(fd);
    std::remove(tmp.c_str());
    AssertThrow(false, ExcCannotWrite(path, reason(e)));
  };
  {
    DescriptorBuffer buffer(fd);
    std::ostream out(&buffer);
    try
    {
      write(out);
      out.flush();
    }
    catch (...)
    {
      // A writer that stops on the failed stream (deal.II's ExcIO) is reported with
      // the cause; any other error passes unchanged.
      if (buffer.error() != 0)
        give_up(buffer.error());
      ::close(fd);
      std::remove(tmp.c_str());
      throw;
    }
    failure = buffer.error();
  }
  if (failure != 0)
    give_up(failure);
  if (::close(fd) != 0)
  {
    const int e = errno;
    std::remove(tmp.c_str());
    AssertThrow(false, ExcCannotWrite(path, reason(e)));
  }
  if (keep_previous)
    if (const int e = keep_as_previous(path, path + ".prev"); e != 0)
    {
      std::remove(tmp.c_str());
      AssertThrow(false, ExcCannotWrite(path + ".prev", reason(e)));
    }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
  {
    const int e = errno;
    std::remove(tmp.c_str());
    AssertThrow(false, ExcCannotWrite(path, reason(e)));
  }
}

void write_atomically(const std::string &path, const std::string &text)
{
  write_atomically(path, [&](std::ostream &out) { out << text; });
}

AppendFile::~AppendFile()
{
  close();
}

void AppendFile::close()
{
  if (fd >= 0)
    ::close(fd);
  fd = -1;
}

void AppendFile::create(const std::string &path)
{
  open_at(path, 0);
}

void AppendFile::open_at(const std::string &path, const std::uint64_t size)
{
  close();
  name = path;
  fd   = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  AssertThrow(fd >= 0, ExcCannotWrite(path, reason(errno)));
  // Cutting may shorten the file, never lengthen it with zeros.
  const off_t held = ::lseek(fd, 0, SEEK_END);
  if (held < static_cast<off_t>(size))
  {
    close();
    AssertThrow(false, ExcCannotWrite(path, "it holds " + std::to_string(held) +
                                                " bytes, fewer than the " +
                                                std::to_string(size) + " to keep"));
  }
  if (::ftruncate(fd, static_cast<off_t>(size)) != 0 ||
      ::lseek(fd, static_cast<off_t>(size), SEEK_SET) < 0)
  {
    const int e = errno;
    close();
    AssertThrow(false, ExcCannotWrite(path, reason(e)));
  }
  bytes = size;
}

void AppendFile::append(const std::string &record)
{
  Assert(fd >= 0, dealii::ExcMessage("append() before create() or open_at()"));
  // At the end of the whole records: a fragment a failed append left (should cutting
  // it off fail too) is overwritten by the next.
  const int e = write_all(fd, record.data(), record.size(), static_cast<off_t>(bytes));
  if (e != 0)
  {
    // The part that was written goes: a reader finds whole records only.
    [[maybe_unused]] const int cut = ::ftruncate(fd, static_cast<off_t>(bytes));
    AssertThrow(false, ExcCannotWrite(name, reason(e)));
  }
  bytes += record.size();
}
} // namespace files
} // namespace lme_mpm
