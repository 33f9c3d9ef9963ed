#ifndef LME_MPM_GEOMETRY_BODIES_H
#define LME_MPM_GEOMETRY_BODIES_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * The bodies of a run as the rest of the run refers to them: their names ("Body
 * N/Name", for history columns, scenes and messages) and the motion of the bodies
 * whose velocity is prescribed ("Body N/Prescribed velocity", a ParsedFunction of x
 * and t: rollers, platens, supports). ParticleGenerator fills the same subsections'
 * shapes with particles; contact reads the prescribed motion. Needed with or without
 * contact: a named body reports its displacement either way.
 */
template <int dim>
class Bodies
{
public:
  /// Declares "Name" and "Prescribed velocity" in each "Body N".
  static void declare_parameters(ParameterHandler &prm, unsigned int n_bodies);
  /**
   * Reads the entries; throws ExcBadInput naming the entry for a name that is not
   * letters, digits or '_', one used twice or one in @p reserved_names (the
   * constraint sets', whose history columns it would clash with), and when every
   * body is prescribed.
   */
  void parse_parameters(ParameterHandler &prm, unsigned int n_bodies,
                        const std::vector<std::string> &reserved_names);

  unsigned int size() const { return names_.size(); }
  const std::string &name(const unsigned int body) const { return names_[body]; }
  const std::vector<std::string> &names() const { return names_; }
  /// True if some body has a name (and so history columns).
  bool any_named() const;

  bool any_prescribed() const { return n_prescribed > 0; }
  bool prescribed(const unsigned int body) const { return flags[body] != 0; }
  /// True if @p body is a rigid exact surface (Surface = exact, no particles).
  bool exact(const unsigned int body) const { return exact_flags[body] != 0; }
  bool any_exact() const;
  /// True if some prescribed body is made of particles (it needs multi-field contact).
  bool any_prescribed_particles() const;
  /// Per body: 1 if it moves as prescribed.
  const std::vector<std::uint8_t> &prescribed_flags() const { return flags; }
  /// The "Body N/Prescribed velocity" of the first prescribed body (for messages).
  std::string first_prescribed_entry() const;

  /// The prescribed velocity of @p body at @p x and @p t, times its speed factor;
  /// throws ExcBadInput naming the entry where it is not finite.
  Tensor<1, dim> velocity(unsigned int body, const Point<dim> &x, double t) const
  {
    return factor[body] * entry_velocity(body, x, t);
  }
  /// The velocity its entry gives, without the speed factor.
  Tensor<1, dim> entry_velocity(unsigned int body, const Point<dim> &x, double t) const;
  /// Scales @p body's prescribed velocity from now on (a servo, LoadingControl; 1
  /// unless set).
  void set_speed_factor(const unsigned int body, const double f) { factor[body] = f; }
  double speed_factor(const unsigned int body) const { return factor[body]; }
  /// Its time derivative, by a central difference of half-width @p h (the speed
  /// factor held).
  Tensor<1, dim> acceleration(unsigned int body, const Point<dim> &x, double t,
                              double h) const;
  /// Gives the particles of prescribed bodies their prescribed velocity at @p t (their
  /// initial velocity entry is not used).
  void set_prescribed_velocities(ParticleStore<dim> &particles, double t) const;

  /**
   * history.csv: per named body force_<name>_x ... and force_<name>_mean_x ... (with
   * @p forces: the contact force it received, over the force window and over the
   * output interval) and displacement_<name>_x ... (its particles' mass-weighted mean
   * displacement; for a rigid exact surface, @p rigid_displacements).
   */
  void write_header(std::ostream &out, bool forces) const;
  void write_row(std::ostream &out, const ParticleStore<dim> &particles,
                 const std::vector<Tensor<1, dim>> *forces,
                 const std::vector<Tensor<1, dim>> *mean_forces,
                 const std::vector<Tensor<1, dim>> *rigid_displacements = nullptr) const;

private:
  std::vector<std::string> names_;
  std::vector<std::uint8_t> flags, exact_flags;
  std::vector<double> factor;
  unsigned int n_prescribed = 0;
  std::vector<std::unique_ptr<Functions::ParsedFunction<dim>>> functions;
  std::vector<std::string> entries;
  /// A velocity that depends on neither x nor t is evaluated once.
  std::vector<std::uint8_t> constant;
  std::vector<Tensor<1, dim>> constant_value;
};
} // namespace lme_mpm

#endif
