#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/particles/damage_form.h>

#include <algorithm>

namespace lme_mpm
{
namespace
{
/// The entries of one "Output/Probe N", listed once for declaring and reading.
template <int dim>
struct ProbeEntries
{
  std::string name, point, quantities;
  double radius = 0.01;

  void entries(EntryList &list)
  {
    list.add("Name", name, "probe", Patterns::Anything(),
             "history.csv reports probe_<name>_sxx, ...: the volume-weighted mean "
             "effective stress (1 - damage) sigma of the particles within the "
             "radius, failed ones counting with zero.");
    list.add("Point", point, dim == 2 ? "0, 0" : "0, 0, 0", Patterns::Anything(),
             "Centre of the probe (m).");
    list.add("Radius", radius, "0.01", Patterns::Double(0),
             "Particles within this distance of the point (where they are now) are "
             "averaged (m), > 0.");
    list.add("Quantities", quantities, "stress",
             Patterns::MultipleSelection("stress|displacement|velocity|damage"),
             "What the probe reports, comma-separated: 'stress' (probe_<name>_sxx, "
             "...: the volume-weighted mean effective stress), 'displacement' "
             "(probe_<name>_ux, ...: the mass-weighted mean displacement, a "
             "displacement gauge), 'velocity' (probe_<name>_vx, ...: mass-weighted), "
             "'damage' (probe_<name>_damage: volume-weighted).");
  }
};

/// Runs the entries of @p n probes, each in its subsection of "Output".
template <int dim>
void probe_entries(EntryList &list, std::vector<ProbeEntries<dim>> &probes)
{
  list.enter("Output");
  for (unsigned int p = 0; p < probes.size(); ++p)
  {
    list.enter(input::subsection_name("Probe", p));
    probes[p].entries(list);
    list.leave();
  }
  list.leave();
}
} // namespace

template <int dim>
void Probes<dim>::declare_parameters(ParameterHandler &prm, const unsigned int n_probes)
{
  std::vector<ProbeEntries<dim>> in(n_probes);
  EntryList list(prm, EntryList::Mode::declare);
  probe_entries(list, in);
}

template <int dim>
void Probes<dim>::parse_parameters(ParameterHandler &prm, const unsigned int n_probes)
{
  std::vector<ProbeEntries<dim>> in(n_probes);
  EntryList list(prm, EntryList::Mode::parse);
  probe_entries(list, in);
  probes.clear();
  for (unsigned int p = 0; p < n_probes; ++p)
  {
    const std::string entry = "Output/" + input::subsection_name("Probe", p);
    Probe<dim> probe;
    probe.name   = input::trim(in[p].name);
    probe.point  = input::parse_point<dim>(in[p].point, entry + "/Point");
    probe.radius = in[p].radius;
    input::require_range(probe.radius, 0, 1e300, true, entry + "/Radius");
    const auto asked = input::split(in[p].quantities, ',');
    const auto has   = [&](const char *q)
    { return std::find(asked.begin(), asked.end(), std::string(q)) != asked.end(); };
    probe.stress       = has("stress");
    probe.displacement = has("displacement");
    probe.velocity     = has("velocity");
    probe.damage       = has("damage");
    AssertThrow(probe.stress || probe.displacement || probe.velocity || probe.damage,
                ExcBadInput(entry + "/Quantities",
                            "names nothing to report: give one or more of stress, "
                            "displacement, velocity, damage"));
    probes.push_back(probe);
  }
}

template <int dim>
void Probes<dim>::write_header(std::ostream &out) const
{
  for (const auto &probe : probes)
  {
    const std::string column = ",probe_" + probe.name + "_";
    if (probe.stress)
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          out << column << 's' << "xyz"[i] << "xyz"[j];
    if (probe.displacement)
      for (unsigned int d = 0; d < dim; ++d)
        out << column << 'u' << "xyz"[d];
    if (probe.velocity)
      for (unsigned int d = 0; d < dim; ++d)
        out << column << 'v' << "xyz"[d];
    if (probe.damage)
      out << column << "damage";
  }
}

template <int dim>
void Probes<dim>::write_row(std::ostream &out, const ParticleStore<dim> &store) const
{
  for (const auto &probe : probes)
  {
    SymmetricTensor<2, dim> s;
    Tensor<1, dim> u, v;
    double volume = 0, mass = 0, damage = 0;
    for (std::size_t p = 0; p < store.size(); ++p)
      if (store.position[p].distance(probe.point) <= probe.radius)
      {
        s += store.volume[p] * effective_stress(store, p);
        u += store.mass[p] * (store.position[p] - store.reference_position[p]);
        v += store.mass[p] * store.velocity[p];
        damage += store.volume[p] * store.damage[p];
        volume += store.volume[p], mass += store.mass[p];
      }
    if (volume > 0)
      s /= volume, damage /= volume;
    if (mass > 0)
      u /= mass, v /= mass;
    if (probe.stress)
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          out << "," << s[i][j];
    if (probe.displacement)
      for (unsigned int d = 0; d < dim; ++d)
        out << "," << u[d];
    if (probe.velocity)
      for (unsigned int d = 0; d < dim; ++d)
        out << "," << v[d];
    if (probe.damage)
      out << "," << damage;
  }
}

template class Probes<2>;
template class Probes<3>;
} // namespace lme_mpm
