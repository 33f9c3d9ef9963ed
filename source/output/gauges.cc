#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/output/gauges.h>

#include <algorithm>
#include <cctype>

namespace lme_mpm
{
namespace
{
const char *const list_entry   = "Output/Opening gauges";
const char *const radius_entry = "Output/Gauge radius";
} // namespace

template <int dim>
void OpeningGauges<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Output");
  prm.declare_entry(
      "Opening gauges", "", Patterns::Anything(),
      std::string("Clip gauges, separated by ';', each 'name: ") +
          (dim == 2 ? "xA, yA, xB, yB[, radius]"
                    : "xA, yA, zA, xB, yB, zB[, radius]' or 'name: xA, yA, xB, yB[, "
                      "radius]") +
          "' (m, positions at t = 0): history.csv reports opening_<name>, the "
          "change in distance between the mean displacements of the particles "
          "near A and near B (a crack mouth opening, a lateral expansion). " +
          (dim == 3 ? "Points given by x and y only stand for lines along z: the "
                      "gauge averages through the thickness. "
                    : "") +
          "A radius given with a gauge replaces 'Output/Gauge radius' for it. The "
          "built-in scenes add their own gauges to this list. 'Loading control/"
          "Gauge' may name one. Empty: none.");
  prm.declare_entry("Gauge radius", "0", Patterns::Double(0),
                    "Particles whose position at t = 0 lies within this distance of "
                    "a gauge point are averaged (m); 0: half the smallest cell.");
  prm.leave_subsection();
}

template <int dim>
void OpeningGauges<dim>::parse_parameters(ParameterHandler &prm, const double cell_size)
{
  prm.enter_subsection("Output");
  const std::string text = prm.get("Opening gauges");
  radius                 = prm.get_double("Gauge radius");
  prm.leave_subsection();
  if (radius == 0)
    radius = 0.5 * cell_size;
  gauges.clear();
  for (const std::string &item : input::split(text, ';'))
  {
    const auto colon = item.find(':');
    AssertThrow(colon != std::string::npos,
                ExcBadInput(list_entry,
                            "'" + item + "' is not 'name: " +
                                (dim == 2 ? "xA, yA, xB, yB" : "xA, yA, zA, xB, yB, zB") +
                                "'"));
    Gauge g;
    g.name = input::trim(item.substr(0, colon));
    AssertThrow(!g.name.empty() &&
                    std::all_of(g.name.begin(), g.name.end(),
                                [](const char c) {
                                  return std::isalnum(static_cast<unsigned char>(c)) ||
                                         c == '_';
                                }),
                ExcBadInput(list_entry, "the gauge name '" + g.name +
                                            "' must be letters, digits or '_'"));
    AssertThrow(find(g.name) == gauges.size(),
                ExcBadInput(list_entry, "two gauges are named '" + g.name + "'"));
    const std::vector<double> c =
        input::parse_doubles(item.substr(colon + 1), list_entry);
    // A and B with dim coordinates each, or (in 3D) lines along z with x and y; then
    // an optional radius.
    const unsigned int per_point = c.size() >= 2 * dim ? dim : 2;
    AssertThrow(
        c.size() == 2 * dim || c.size() == 2 * dim + 1 ||
            (dim == 3 && (c.size() == 4 || c.size() == 5)),
        ExcBadInput(list_entry, "gauge '" + g.name + "' has " + std::to_string(c.size()) +
                                    " numbers; it needs " + std::to_string(2 * dim) +
                                    " (A, then B) and optionally a radius" +
                                    (dim == 3 ? ", or 4 (x and y of A and B: lines along "
                                                "z) and optionally a radius"
                                              : "")));
    g.line = per_point < dim;
    for (unsigned int d = 0; d < per_point; ++d)
      g.a[d] = c[d], g.b[d] = c[per_point + d];
    g.radius = radius;
    if (c.size() == 2 * per_point + 1)
    {
      g.radius = c.back();
      AssertThrow(g.radius > 0,
                  ExcBadInput(list_entry, "the radius of gauge '" + g.name +
                                              "' must be positive (got " +
                                              format_double(g.radius) + " m)"));
    }
    AssertThrow(g.a.distance(g.b) > 2 * g.radius,
                ExcBadInput(list_entry,
                            "the points of gauge '" + g.name + "' are " +
                                format_double(g.a.distance(g.b)) +
                                " m apart; they must be more than twice its radius (" +
                                format_double(2 * g.radius) + " m; '" + radius_entry +
                                "' unless the gauge gives one) apart"));
    gauges.push_back(g);
  }
}

template <int dim>
unsigned int OpeningGauges<dim>::find(const std::string &n) const
{
  for (unsigned int g = 0; g < gauges.size(); ++g)
    if (gauges[g].name == n)
      return g;
  return gauges.size();
}

template <int dim>
std::string OpeningGauges<dim>::describe(const unsigned int g) const
{
  return "A " + point_to_string(gauges[g].a) + ", B " + point_to_string(gauges[g].b) +
         (gauges[g].line ? " (lines along z)" : "") + ", radius " +
         format_double(gauges[g].radius) + " m";
}

template <int dim>
std::string OpeningGauges<dim>::names() const
{
  std::string s;
  for (const auto &g : gauges)
    s += (s.empty() ? "" : ", ") + g.name;
  return s;
}

template <int dim>
std::vector<double> OpeningGauges<dim>::sums(const ParticleStore<dim> &p) const
{
  // Per gauge: mass at A, at B, then mass-weighted displacement along AB at A, at B.
  std::vector<double> s(4 * gauges.size(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    if (p.ghost[i] != 0 ||
        (p.body_id[i] < excluded.size() && excluded[p.body_id[i]] != 0))
      continue;
    const Point<dim> &X = p.reference_position[i];
    for (unsigned int g = 0; g < gauges.size(); ++g)
    {
      const Gauge &gauge = gauges[g];
      for (unsigned int k = 0; k < 2; ++k)
        if (gauge.near(X, k == 0 ? gauge.a : gauge.b))
        {
          const Tensor<1, dim> e = (gauge.b - gauge.a) / gauge.a.distance(gauge.b);
          s[4 * g + k] += p.mass[i];
          s[4 * g + 2 + k] += p.mass[i] * ((p.position[i] - X) * e);
        }
    }
  }
  return s;
}

template <int dim>
void OpeningGauges<dim>::check(const ParticleStore<dim> &p,
                               const RankReductions *ranks) const
{
  std::vector<double> s = sums(p);
  if (ranks != nullptr)
    ranks->sum(s);
  for (unsigned int g = 0; g < gauges.size(); ++g)
    for (unsigned int k = 0; k < 2; ++k)
      AssertThrow(s[4 * g + k] > 0,
                  ExcBadInput(list_entry,
                              "point " + std::string(k == 0 ? "A" : "B") + " of gauge '" +
                                  gauges[g].name + "' (" +
                                  point_to_string(k == 0 ? gauges[g].a : gauges[g].b) +
                                  ") has no particle of a free body within its "
                                  "radius (" +
                                  format_double(gauges[g].radius) +
                                  " m): put it inside a body"));
}

template <int dim>
std::vector<double> OpeningGauges<dim>::read(const ParticleStore<dim> &p,
                                             const RankReductions *ranks) const
{
  std::vector<double> s = sums(p);
  if (ranks != nullptr)
    ranks->sum(s);
  std::vector<double> w(gauges.size(), 0.0);
  const auto mean = [](const double m, const double u) { return m > 0 ? u / m : 0.0; };
  for (unsigned int g = 0; g < gauges.size(); ++g)
    w[g] = mean(s[4 * g + 1], s[4 * g + 3]) - mean(s[4 * g], s[4 * g + 2]);
  return w;
}

template <int dim>
void OpeningGauges<dim>::write_header(std::ostream &out) const
{
  for (const auto &g : gauges)
    out << ",opening_" << g.name;
}

template <int dim>
void OpeningGauges<dim>::write_row(std::ostream &out, const ParticleStore<dim> &p) const
{
  for (const double w : read(p, nullptr))
    out << "," << w;
}

template class OpeningGauges<2>;
template class OpeningGauges<3>;
} // namespace lme_mpm
