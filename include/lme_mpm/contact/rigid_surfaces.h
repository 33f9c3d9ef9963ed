#ifndef LME_MPM_CONTACT_RIGID_SURFACES_H
#define LME_MPM_CONTACT_RIGID_SURFACES_H

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/geometry/bodies.h>
#include <lme_mpm/geometry/geometry.h>
#include <lme_mpm/solver/grid_transfer.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Prescribed bodies with `Surface = exact`: rigid shapes (rectangle, disc, cylinder)
 * that move as prescribed and have no particles. Each step every particle of the
 * other bodies is tested against each surface at the end of the step: its domain
 * (a disc or ball of radius r_p, the depth below a cell face of a body's outermost
 * particles) overlaps the surface by p = r_p - phi(x_p), phi the surface's signed
 * distance, and the surface pushes it
 * along the surface normal with f_n = alpha m_p p / dt_w^2 (alpha the `Contact/Surface
 * penalty factor`, dt_w the wave speed's time step) and, with friction, against its
 * tangential slip with at most mu f_n and at most what stops the slip in one step. This
 * is the particle-level penalty of the open-source MPM code Karamelo (its "minimize
 * penetration" indenter and plane contacts, src/fix/fix_indent_minimize_penetration.cpp),
 * where Stomakhin et al. (2013, ACM Trans. Graph. 32(4):102) act on grid nodes; at the
 * particles the contact patch, and the force it carries, grow particle by particle inside
 * a cell. The forces enter the nodal forces through the particles' shape functions, so
 * momentum goes to the body and its opposite is booked on the surface (its contact
 * force, as for a prescribed body of particles); their work on the particles is the
 * surface's work on the run.
 */
template <int dim>
class RigidSurfaces
{
public:
  /// Declares "Contact/Surface penalty factor".
  static void declare_parameters(ParameterHandler &prm);
  /**
   * Reads the rigid surfaces from the bodies with `Surface = exact` (their Shape) and
   * the factor; throws ExcBadInput naming the entry for a shape without an exact
   * surface. @p depth gives per body how deep below a face of its cells its
   * outermost particles sit (m: the particles' radius r_p, so that a face of the body
   * along a cell face touches a surface at that face), @p h_min the smallest cell.
   */
  void parse_parameters(ParameterHandler &prm, const Bodies<dim> &bodies,
                        const std::vector<double> &depth, double h_min);
  void set_ranks(const RankReductions &r) { ranks = &r; }
  /**
   * The step the penalty is scaled by (the wave speed's step, Time/CFL): a fixed
   * stiffness, so that a step shortened by the travel limit or at the end of the run
   * neither stiffens the contact nor pumps energy into it.
   */
  void set_reference_step(const double dt) { reference_step = dt; }

  /// True if some body is a rigid exact surface.
  bool active() const { return !surfaces.empty(); }

  /**
   * Adds the surfaces' push at the end of the step [t, t + dt] to the nodal forces of
   * @p transfer (its rates are the step's displacement rates, which carry each
   * particle to its end-of-step position); books the force on each surface and
   * returns the work on the particles over the step (J, summed over the ranks).
   */
  double apply(GridTransfer<dim> &transfer, const ParticleStore<dim> &particles, double t,
               double dt);
  /**
   * Seating, before the first step: a surface that moves (its prescribed velocity at
   * @p end_time is not zero) is carried along that velocity's direction until it
   * touches the nearest particle domain in its path, if one lies within a cell of
   * it. A body's discrete surface lies up to a particle spacing inside its shape
   * where the shape is curved (the top of the semicircular-bending arc), and a
   * testing machine is seated on the specimen before the test; without seating the
   * roller would first travel through that gap. The shift is `seating_<body>` in
   * summary.json; displacements count from the seated position. Every rank calls it.
   */
  void seat(const ParticleStore<dim> &particles, double end_time, double h_min);
  /// After the step: the surfaces stand where apply() put them.
  void finish_step() { displacement = next_displacement; }

  /// Per body: the force the surface received in the last step (N; zero for others).
  const std::vector<Tensor<1, dim>> &step_forces() const { return force; }
  /// Per body: how far the surface has moved (m; zero for others).
  const std::vector<Tensor<1, dim>> &displacements() const { return displacement; }
  /// The deepest overlap so far, as a share of the particle spacing.
  void add_results(std::map<std::string, double> &results) const;

  void serialize(Archive &ar) { ar(displacement, max_overlap, seating); }

private:
  struct Surface
  {
    unsigned int body = 0;
    std::unique_ptr<Geometry<dim>> shape;
    /// The body's Holes (a strip's seat cut to the specimen's curve).
    std::vector<std::unique_ptr<Geometry<dim>>> holes;
    BoundingBox<dim> box;
    /// Where the prescribed velocity is evaluated (the shape's centre at t = 0).
    Point<dim> reference;

    /// The shape minus its holes: max(phi_shape, -phi_hole) and its normal (exact
    /// in sign, the distance bounded by the true one near the surface).
    void distance(const Point<dim> &x, double &phi, Tensor<1, dim> &normal) const
    {
      shape->signed_distance(x, phi, normal);
      double phi_h;
      Tensor<1, dim> n_h;
      for (const auto &h : holes)
      {
        h->signed_distance(x, phi_h, n_h);
        if (-phi_h > phi)
          phi = -phi_h, normal = -n_h;
      }
    }
  };

  const Bodies<dim> *bodies   = nullptr;
  const RankReductions *ranks = nullptr;
  double penalty = 0.5, damping_ratio = 0.5, friction = 0, max_overlap = 0;
  double reference_step = 0;
  std::vector<double> radius;
  /// Two cells: a particle moves less than half a cell in a step (the run guard's
  /// limit), so this far around the moved surface holds every particle it can touch.
  double margin = 0;
  std::vector<Surface> surfaces;
  std::vector<Tensor<1, dim>> displacement, next_displacement, force;
  /// Per body: the seating shift (seat()), part of the surface's position.
  std::vector<Tensor<1, dim>> seating;
  bool seat_surfaces = false;
  /// Per surface at the end of the step: velocity and the box particles may touch.
  std::vector<Tensor<1, dim>> velocity, shift;
  std::vector<BoundingBox<dim>> reach;
  std::vector<double> sums;
};
} // namespace lme_mpm

#endif
