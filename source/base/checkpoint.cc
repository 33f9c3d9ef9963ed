#include <lme_mpm/base/checkpoint.h>
#include <lme_mpm/base/file_writing.h>
#include <lme_mpm/base/input.h>

#include <fstream>

namespace lme_mpm
{
namespace checkpoint
{
namespace
{
// Seven characters name the format, the eighth is its version.
const char magic[9] = "LMEMPMCG";
} // namespace

void write(const std::string &file, const std::function<void(Archive &)> &serialize)
{
  files::write_atomically(
      file,
      [&](std::ostream &out)
      {
        out.write(magic, 8);
        Archive archive(out);
        serialize(archive);
      },
      true);
}

void read(const std::string &file, const std::function<void(Archive &)> &serialize)
{
  std::ifstream in(file, std::ios::binary);
  AssertThrow(in, ExcBadInput("--resume", "no checkpoint '" + file + "'"));
  char head[8];
  in.read(head, 8);
  AssertThrow(in && std::string(head, 7) == std::string(magic, 7),
              ExcBadInput("--resume", "'" + file + "' is not an lme-mpm checkpoint"));
  AssertThrow(
      std::string(head, 8) == std::string(magic, 8),
      ExcBadInput("--resume", "'" + file + "' was written by another version of " +
                                  "lme-mpm (format " + std::string(head + 7, 1) +
                                  ", this one reads " + std::string(magic + 7, 1) + ")"));
  Archive archive(in);
  serialize(archive);
  AssertThrow(archive.good(), ExcBadInput("--resume", "'" + file + "' is truncated"));
}
} // namespace checkpoint
} // namespace lme_mpm
