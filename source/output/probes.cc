#include <lme_mpm/base/input.h>
#include <lme_mpm/output/probes.h>

namespace lme_mpm
{
template <int dim>
void Probes<dim>::declare_parameters(ParameterHandler &prm, const unsigned int n_probes)
{
  prm.enter_subsection("Output");
  for (unsigned int p = 0; p < n_probes; ++p)
  {
    prm.enter_subsection(input::subsection_name("Probe", p));
    prm.declare_entry("Name", "probe", Patterns::Anything(),
                      "history.csv reports probe_<name>_sxx, ... .");
    prm.declare_entry("Point", dim == 2 ? "0, 0" : "0, 0, 0", Patterns::Anything(),
                      "Centre of the probe (m).");
    prm.declare_entry("Radius", "0.01", Patterns::Double(0),
                      "Particles within this distance are averaged (m), > 0.");
    prm.leave_subsection();
  }
  prm.leave_subsection();
}

template <int dim>
void Probes<dim>::parse_parameters(ParameterHandler &prm, const unsigned int n_probes)
{
  probes.clear();
  prm.enter_subsection("Output");
  for (unsigned int p = 0; p < n_probes; ++p)
  {
    const std::string section = input::subsection_name("Probe", p);
    prm.enter_subsection(section);
    Probe<dim> probe;
    probe.name = input::trim(prm.get("Name"));
    probe.point =
        input::parse_point<dim>(prm.get("Point"), "Output/" + section + "/Point");
    probe.radius = prm.get_double("Radius");
    input::require_range(probe.radius, 0, 1e300, true, "Output/" + section + "/Radius");
    probes.push_back(probe);
    prm.leave_subsection();
  }
  prm.leave_subsection();
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
        s += store.volume[p] * store.stress[p], w += store.volume[p];
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
