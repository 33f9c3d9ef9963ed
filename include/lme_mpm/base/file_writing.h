#ifndef LME_MPM_BASE_FILE_WRITING_H
#define LME_MPM_BASE_FILE_WRITING_H

#include <deal.II/base/exceptions.h>

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

namespace lme_mpm
{
/// A file that could not be written, with the system's reason ("No space left on
/// device", "File too large", "Permission denied").
DeclException2(ExcCannotWrite, std::string, std::string,
               << "cannot write '" << arg1 << "': " << arg2);

namespace files
{
/**
 * Writes @p path through @p write so that a reader sees the old file or the complete
 * new one, never a part: the bytes go to path.tmp, which replaces @p path only when
 * every byte is written and the file is closed (no fsync: a crash of the machine
 * itself is not covered). With @p keep_previous the file it replaces is kept as
 * path.prev (a hard link, so that @p path never goes missing). A failure removes
 * path.tmp, leaves @p path as it was and throws ExcCannotWrite naming the file and
 * the system's reason.
 */
void write_atomically(const std::string &path,
                      const std::function<void(std::ostream &)> &write,
                      bool keep_previous = false);

/// The same for a text held in memory.
void write_atomically(const std::string &path, const std::string &text);

/**
 * A file that grows by whole records (history.csv): each append is written to the
 * file (not buffered) before it returns, and one that fails is cut off again, so the
 * file holds whole records only; it throws ExcCannotWrite naming the file and the
 * reason.
 */
class AppendFile
{
public:
  AppendFile()                              = default;
  AppendFile(const AppendFile &)            = delete;
  AppendFile &operator=(const AppendFile &) = delete;
  ~AppendFile();

  /// Creates (or empties) @p path.
  void create(const std::string &path);
  /// Opens @p path after cutting it to its first @p size bytes.
  void open_at(const std::string &path, std::uint64_t size);
  void append(const std::string &record);
  /// The bytes written so far.
  std::uint64_t size() const { return bytes; }
  const std::string &path() const { return name; }

private:
  void close();

  std::string name;
  int fd              = -1;
  std::uint64_t bytes = 0;
};
} // namespace files
} // namespace lme_mpm

#endif
