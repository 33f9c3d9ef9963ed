#include <lme_mpm/base/input.h>
#include <lme_mpm/output/history_file.h>

#include <filesystem>

namespace lme_mpm
{
namespace
{
void require_open(const std::ofstream &out, const std::string &directory)
{
  AssertThrow(out,
              ExcBadInput("Output/Directory", "cannot write to '" + directory + "'"));
}
} // namespace

void HistoryFile::create(const std::string &directory, const std::string &header)
{
  name = directory + "/history.csv";
  out.open(name);
  require_open(out, directory);
  out << header << "\n";
}

void HistoryFile::resume(const std::string &directory, const std::uint64_t size)
{
  name = directory + "/history.csv";
  std::filesystem::resize_file(name, size);
  out.open(name, std::ios::app);
  require_open(out, directory);
}

void HistoryFile::write_row(const std::string &row)
{
  out << row << "\n" << std::flush;
}

std::uint64_t HistoryFile::size()
{
  out.flush();
  return std::filesystem::file_size(name);
}
} // namespace lme_mpm
