#include <lme_mpm/base/file_writing.h>
#include <lme_mpm/output/run_summary.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace lme_mpm
{
void RunSummary::write(const std::string &file, const std::string &shape_function,
                       const std::uint64_t checksum, const unsigned int dim) const
{
  // Ordered as written; a value that is not finite becomes null and is named in the
  // message, as JSON has no inf or nan.
  nlohmann::ordered_json json;
  std::ostringstream hex;
  hex << std::hex << checksum;
  std::string non_finite;
  json["status"]  = status;
  json["message"] = message;
  if (!stop_reason.empty())
    json["stop_reason"] = stop_reason;
  json["shape_function"] = shape_function;
  json["state_checksum"] = hex.str();
  json["dimension"]      = dim;
  json["warnings"]       = warnings;
  for (const auto &[name, value] : values)
  {
    if (std::isfinite(value))
    {
      // 10 significant digits, as the history files have.
      std::ostringstream s;
      s << std::setprecision(10) << value;
      json[name] = nlohmann::ordered_json::parse(s.str());
    }
    else
    {
      json[name] = nullptr;
      non_finite += (non_finite.empty() ? "" : ", ") + name;
    }
  }
  if (!non_finite.empty())
    json["message"] = message + (message.empty() ? "" : " ") +
                      "(not finite, written as null: " + non_finite + ")";
  json["run"] = {{"version", version()},
                 {"git_revision", git_revision()},
                 {"command_line", record.command_line},
                 {"parameter_file", record.parameter_file},
                 {"overrides", record.overrides},
                 {"libraries", record.libraries},
                 {"resumed_from", record.resumed_from}};
  files::write_atomically(file, json.dump(2) + '\n');
}

namespace
{
/**
 * Particles as CSV rows 'id[,body],x0,x1,...,x0_0,x0_1,...,damage' (current, then
 * reference position), those for which @p keep holds, with @p damage as the last
 * column; @p with_body adds the body and, after the damage, each particle's
 * dissipated energy (J) and crack opening (m).
 */
template <int dim, class Keep, class Damage>
void write_particle_rows(std::ostream &out, const ParticleStore<dim> &store,
                         const bool with_body, const Keep &keep, const Damage &damage)
{
  out << (with_body ? "id,body" : "id");
  for (unsigned int d = 0; d < dim; ++d)
    out << ",x" << d;
  for (unsigned int d = 0; d < dim; ++d)
    out << ",x0_" << d;
  out << (with_body ? ",damage,dissipated,crack_opening\n" : ",damage\n")
      << std::setprecision(10);
  for (std::size_t p = 0; p < store.size(); ++p)
    if (keep(p))
    {
      out << store.id[p];
      if (with_body)
        out << ',' << store.body_id[p];
      for (unsigned int d = 0; d < dim; ++d)
        out << ',' << store.position[p][d];
      for (unsigned int d = 0; d < dim; ++d)
        out << ',' << store.reference_position[p][d];
      out << ',' << damage(p);
      if (with_body)
        out << ',' << store.value_at(store.dissipated, p) << ','
            << store.value_at(store.crack_opening, p);
      out << '\n';
    }
}

template <int dim, class Keep, class Damage>
void write_particle_points(const std::string &file, const ParticleStore<dim> &store,
                           const bool with_body, const Keep &keep, const Damage &damage)
{
  files::write_atomically(file, [&](std::ostream &out)
                          { write_particle_rows(out, store, with_body, keep, damage); });
}
} // namespace

template <int dim>
void write_failed_particles(const std::string &file, const ParticleStore<dim> &store)
{
  write_particle_points(
      file, store, false, [&](const std::size_t p) { return store.failed[p] != 0; },
      [&](const std::size_t p) { return store.damage[p]; });
}

template <int dim>
void write_damage_field(const std::string &file, const ParticleStore<dim> &store)
{
  write_particle_points(
      file, store, true, [](const std::size_t) { return true; },
      [&](const std::size_t p) { return store.failed[p] ? 1.0 : store.damage[p]; });
}

namespace
{
template <int dim>
void write_polyline_rows(std::ostream &lines,
                         const std::vector<std::vector<Point<dim>>> &polylines)
{
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
} // namespace

template <int dim>
void write_polylines(const std::string &file,
                     const std::vector<std::vector<Point<dim>>> &polylines)
{
  files::write_atomically(file, [&](std::ostream &lines)
                          { write_polyline_rows(lines, polylines); });
}

template void write_failed_particles(const std::string &, const ParticleStore<2> &);
template void write_damage_field(const std::string &, const ParticleStore<2> &);
template void write_damage_field(const std::string &, const ParticleStore<3> &);
template void write_failed_particles(const std::string &, const ParticleStore<3> &);
template void write_polylines(const std::string &,
                              const std::vector<std::vector<Point<2>>> &);
template void write_polylines(const std::string &,
                              const std::vector<std::vector<Point<3>>> &);
} // namespace lme_mpm
