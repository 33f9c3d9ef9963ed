#ifndef LME_MPM_OUTPUT_EXACT_SOLUTION_H
#define LME_MPM_OUTPUT_EXACT_SOLUTION_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>

#include <lme_mpm/particles/particle_store.h>

#include <map>
#include <memory>
#include <ostream>
#include <string>

namespace lme_mpm
{
/**
 * Verification against an exact solution ("Verification"): displacement, velocity
 * and optionally stress as functions of the reference position and t. At each
 * output time the relative L2 errors over the particles (weighted by their initial
 * volumes, normalised by the exact fields' largest norm over the run) go to
 * history.csv; their maxima over the history rows to summary.json.
 */
template <int dim>
class ExactSolution
{
public:
  static void declare_parameters(ParameterHandler &prm);
  void parse_parameters(ParameterHandler &prm);
  bool enabled() const { return displacement != nullptr; }

  /// The normalising norms: the exact fields' largest L2 norms over 1001 times
  /// spread evenly over the run.
  void compute_norms(const ParticleStore<dim> &particles, double end_time);

  void write_header(std::ostream &out) const;
  /// Appends the errors at time @p t and updates their maxima.
  void write_row(std::ostream &out, const ParticleStore<dim> &particles, double t);
  void add_results(std::map<std::string, double> &results) const;

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(max_error_displacement, max_error_velocity, max_error_stress);
  }

private:
  SymmetricTensor<2, dim> stress_at(const Point<dim> &X) const;

  std::unique_ptr<Functions::ParsedFunction<dim>> displacement, velocity, stress;
  double displacement_norm = 0, velocity_norm = 0, stress_norm = 0;
  double max_error_displacement = 0, max_error_velocity = 0, max_error_stress = 0;
};
} // namespace lme_mpm

#endif
