#include <lme_mpm/base/input.h>
#include <lme_mpm/output/peak_force.h>

namespace lme_mpm
{
template <int dim>
void PeakForce<dim>::parse(const std::string &entry,
                           const NodeConstraints<dim> &constraints)
{
  if (entry.empty())
    return;
  const auto colon       = entry.find(':');
  const std::string name = input::trim(entry.substr(0, colon));
  const std::string comp =
      colon == std::string::npos ? "" : input::trim(entry.substr(colon + 1));
  for (unsigned int c = 0; c < constraints.size(); ++c)
    if (constraints[c].name() == name)
      set = c;
  AssertThrow(set < constraints.size(),
              ExcBadInput("Output/Peak force set",
                          "no constrained node set is named '" + name + "'"));
  AssertThrow(comp.size() == 1 &&
                  std::string("xyz").substr(0, dim).find(comp) != std::string::npos,
              ExcBadInput("Output/Peak force set",
                          "give 'name:x', 'name:y'" +
                              std::string(dim == 3 ? " or 'name:z'" : "")));
  component = std::string("xyz").find(comp);
}

template <int dim>
void PeakForce<dim>::add_results(std::map<std::string, double> &results) const
{
  if (set == numbers::invalid_unsigned_int)
    return;
  results["peak_force"]           = peak;
  results["displacement_at_peak"] = displacement_at_peak;
}

template class PeakForce<2>;
template class PeakForce<3>;
} // namespace lme_mpm
