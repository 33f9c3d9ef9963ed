#include <deal.II/base/data_out_base.h>
#include <deal.II/base/exceptions.h>

#include <lme_mpm/base/file_writing.h>
#include <lme_mpm/output/vtu_series.h>

#include <iomanip>
#include <sstream>

namespace lme_mpm
{
using files::write_atomically;

VtuSeries::VtuSeries(const std::string &directory, const std::string &stem)
    : directory(directory), stem(stem)
{
}

void VtuSeries::add(const double time,
                    const std::function<void(std::ostream &)> &write_vtu)
{
  std::ostringstream file;
  file << stem << "_" << std::setw(5) << std::setfill('0') << written.size() << ".vtu";
  write_atomically(directory + "/" + file.str(), write_vtu);
  written.emplace_back(time, file.str());
  write_atomically(directory + "/" + stem + ".pvd", [&](std::ostream &out)
                   { dealii::DataOutBase::write_pvd_record(out, written); });
}
void VtuSeries::add_piece(
    const double time, const unsigned int rank, const unsigned int n_ranks,
    const std::function<void(std::ostream &)> &write_piece,
    const std::function<void(std::ostream &, const std::vector<std::string> &)>
        &write_pvtu)
{
  std::ostringstream base;
  base << stem << "_" << std::setw(5) << std::setfill('0') << written.size();
  std::vector<std::string> pieces;
  for (unsigned int r = 0; r < n_ranks; ++r)
    pieces.push_back(base.str() + "." + std::to_string(r) + ".vtu");
  write_atomically(directory + "/" + pieces[rank], write_piece);
  if (rank != 0)
  {
    written.emplace_back(time, base.str() + ".pvtu");
    return;
  }
  write_atomically(directory + "/" + base.str() + ".pvtu",
                   [&](std::ostream &out) { write_pvtu(out, pieces); });
  // Listed once it exists: the series never names a file that is not there.
  written.emplace_back(time, base.str() + ".pvtu");
  write_atomically(directory + "/" + stem + ".pvd", [&](std::ostream &out)
                   { dealii::DataOutBase::write_pvd_record(out, written); });
}
} // namespace lme_mpm
