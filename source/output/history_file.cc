#include <lme_mpm/output/history_file.h>

namespace lme_mpm
{
void HistoryFile::create(const std::string &directory, const std::string &header)
{
  file.create(directory + "/history.csv");
  file.append(header + "\n");
}

void HistoryFile::resume(const std::string &directory, const std::uint64_t size)
{
  file.open_at(directory + "/history.csv", size);
}

void HistoryFile::write_row(const std::string &row)
{
  file.append(row + "\n");
}
} // namespace lme_mpm
