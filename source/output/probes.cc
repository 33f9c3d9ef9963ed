#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/particles/damage_form.h>

namespace lme_mpm
{
namespace
{
/// The entries of one "Output/Probe N", listed once for declaring and reading.
template <int dim>
struct ProbeEntries
{
  std::string name, point;
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
             "Particles within this distance are averaged (m), > 0.");
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
    probes.push_back(probe);
  }
}

template <int dim>
void Probes<dim>::write_header(std::ostream &out) const
{
  for (const auto &probe : probes)
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        out << ",probe_" << probe.name << "_s"
            << "xyz"[i] << "xyz"[j];
}

template <int dim>
void Probes<dim>::write_row(std::ostream &out, const ParticleStore<dim> &store) const
{
  for (const auto &probe : probes)
  {
    SymmetricTensor<2, dim> s;
    double w = 0;
    for (std::size_t p = 0; p < store.size(); ++p)
      if (store.position[p].distance(probe.point) <= probe.radius)
        s += store.volume[p] * effective_stress(store, p), w += store.volume[p];
    if (w > 0)
      s /= w;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        out << "," << s[i][j];
  }
}

template class Probes<2>;
template class Probes<3>;
} // namespace lme_mpm
