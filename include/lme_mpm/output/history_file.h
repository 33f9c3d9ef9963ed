#ifndef LME_MPM_OUTPUT_HISTORY_FILE_H
#define LME_MPM_OUTPUT_HISTORY_FILE_H

#include <lme_mpm/base/file_writing.h>

#include <cstdint>
#include <string>

namespace lme_mpm
{
/**
 * history.csv: a header line, then one row per output time, on disk as it is
 * written so that a run that stops early keeps every row. A row that cannot be
 * written (a full disk) is cut off again and stops the run naming the file. A
 * resumed run cuts the rows written after its checkpoint and appends.
 */
class HistoryFile
{
public:
  /// Creates @p directory/history.csv with the columns in @p header
  /// (comma-separated, no newline).
  void create(const std::string &directory, const std::string &header);
  /// Opens @p directory/history.csv for appending after cutting it to @p size bytes.
  void resume(const std::string &directory, std::uint64_t size);
  void write_row(const std::string &row);
  /// The file's size in bytes now (what a checkpoint records).
  std::uint64_t size() const { return file.size(); }

private:
  files::AppendFile file;
};
} // namespace lme_mpm

#endif
