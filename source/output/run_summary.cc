#include <lme_mpm/output/run_summary.h>

#include <fstream>
#include <iomanip>

namespace lme_mpm
{
void RunSummary::write(const std::string &file, const std::string &shape_function,
                       const std::uint64_t checksum, const unsigned int dim) const
{
  std::ofstream json(file);
  std::string quoted;
  for (const char c : message)
    quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  json << std::setprecision(10) << "{\n  \"status\": \"" << status << "\",\n"
       << "  \"message\": \"" << quoted << "\",\n"
       << "  \"shape_function\": \"" << shape_function << "\",\n"
       << "  \"state_checksum\": \"" << std::hex << checksum << std::dec << "\",\n"
       << "  \"dimension\": " << dim;
  for (const auto &r : values)
    json << ",\n  \"" << r.first << "\": " << r.second;
  json << "\n}\n";
}

template <int dim>
void write_failed_particles(const std::string &file, const ParticleStore<dim> &store)
{
  std::ofstream crack(file);
  crack << "id";
  for (unsigned int d = 0; d < dim; ++d)
    crack << ",x" << d;
  for (unsigned int d = 0; d < dim; ++d)
    crack << ",x0_" << d;
  crack << ",damage\n" << std::setprecision(10);
  for (std::size_t p = 0; p < store.size(); ++p)
    if (store.failed[p])
    {
      crack << store.id[p];
      for (unsigned int d = 0; d < dim; ++d)
        crack << ',' << store.position[p][d];
      for (unsigned int d = 0; d < dim; ++d)
        crack << ',' << store.reference_position[p][d];
      crack << ',' << store.damage[p] << '\n';
    }
}

template <int dim>
void write_polylines(const std::string &file,
                     const std::vector<std::vector<Point<dim>>> &polylines)
{
  std::ofstream lines(file);
  lines << "crack,point";
  for (unsigned int d = 0; d < dim; ++d)
    lines << ",x" << d;
  lines << '\n' << std::setprecision(17);
  for (unsigned int l = 0; l < polylines.size(); ++l)
    for (unsigned int i = 0; i < polylines[l].size(); ++i)
    {
      lines << l << ',' << i;
      for (unsigned int d = 0; d < dim; ++d)
        lines << ',' << polylines[l][i][d];
      lines << '\n';
    }
}

template void write_failed_particles(const std::string &, const ParticleStore<2> &);
template void write_failed_particles(const std::string &, const ParticleStore<3> &);
template void write_polylines(const std::string &,
                              const std::vector<std::vector<Point<2>>> &);
template void write_polylines(const std::string &,
                              const std::vector<std::vector<Point<3>>> &);
} // namespace lme_mpm
