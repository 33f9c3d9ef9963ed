#include <lme_mpm/output/run_files.h>

#include <filesystem>
#include <regex>
#include <system_error>

namespace lme_mpm
{
bool is_run_file(const std::string &name)
{
  // The series: <stem>.pvd, <stem>_NNNNN.vtu, <stem>_NNNNN.pvtu, <stem>_NNNNN.R.vtu
  // (and their temporaries); checkpoint.bin, checkpoint.R.bin, .prev and .tmp.
  static const std::regex pattern(
      "(history\\.csv|summary\\.json|parameters\\.prm|damage\\.csv|"
      "failed_particles\\.csv|cracks\\.csv|"
      "(particles|grid)(\\.pvd|_[0-9]+(\\.[0-9]+)?\\.p?vtu)|"
      "checkpoint(\\.[0-9]+)?\\.bin(\\.prev)?)(\\.tmp)?");
  return std::regex_match(name, pattern);
}

unsigned int remove_earlier_run(const std::string &directory)
{
  std::error_code ec;
  unsigned int removed = 0;
  if (!std::filesystem::is_directory(directory, ec))
    return 0;
  for (const auto &entry : std::filesystem::directory_iterator(directory, ec))
    if (entry.is_regular_file(ec) && is_run_file(entry.path().filename().string()) &&
        std::filesystem::remove(entry.path(), ec))
      ++removed;
  return removed;
}
} // namespace lme_mpm
