#ifndef LME_MPM_SCENES_SCENE_TOOLS_H
#define LME_MPM_SCENES_SCENE_TOOLS_H

#include <lme_mpm/scenes/scene.h>

#include <string>

namespace lme_mpm
{
namespace scenes
{
/// A number written with enough digits that shapes built from it meet exactly.
std::string number(double x);

/// "rectangle(...)" of the box [x0, x1] x [y0, y1] (and [0, length] in z in 3D).
template <int dim>
std::string box_shape(double x0, double y0, double x1, double y1, double length);

/// "cylinder(...)" of axis (cx, cy) and radius r (along z over [0, length] in 3D).
template <int dim>
std::string cylinder_shape(double cx, double cy, double r, double length);

/**
 * A velocity expression for "Prescribed velocity": @p vx, @p vy (times the ramp) with
 * a cosine ramp from zero over @p ramp seconds (none if 0), and 0 in z in 3D.
 */
template <int dim>
std::string ramped_velocity(double vx, double vy, double ramp);

/// The same for a velocity with every component given (@p v, times the ramp).
template <int dim>
std::string ramped_velocity(const Tensor<1, dim> &v, double ramp);

/**
 * Throws naming scene entries @p owner (the ones that size and place @p what) unless
 * the x-y box [x0, x1] x [y0, y1] lies within the grid's 'Grid/Lower corner' and
 * 'Grid/Upper corner', so that a scene grown past its grid is blamed on the entry
 * the user changed, with both extents.
 */
void require_inside_grid(const EntryWriter &writer, double x0, double y0, double x1,
                         double y1, const std::string &owner, const std::string &what);

/**
 * Writes the entries of an explicit, non-growing crack along @p polyline ("x0, y0, x1,
 * y1, ...") that cuts only the body named @p body: Cracks/Polylines, Cracks/Grow with
 * erosion = false and Cracks/Body, on behalf of scene entry @p owner (under the rule
 * of set_entry()). A notch narrower than the shape functions' support needs one, or
 * the grid ties its faces together.
 */
void set_notch_crack(EntryWriter &writer, const std::string &body,
                     const std::string &polyline, const std::string &owner);
/**
 * A load test's stop: once the contact force on body @p body (its mean over the force
 * window, after a step) has fallen below @p fraction of the largest it has reached and
 * some particle has begun to soften, the reason to end the run (empty before, with a
 * fraction of 0, or without contact), as a testing machine stops after the specimen
 * fails.
 */
template <int dim>
std::string load_fell_below(const SceneState<dim> &state, unsigned int body,
                            double fraction);
/// The particles of a body at or above a damage threshold, in clusters of particles
/// linked where they lie within a link factor times the larger of their own sizes of
/// each other (reference x-y plane; a particle's size is the side of its initial area,
/// volume over thickness in 2D, or the cube root of its volume in 3D).
struct CrackClusters
{
  /// The particles' spacing: the square root of their mean initial area (volume
  /// over thickness in 2D; the cube root of the mean volume in 3D); 0 if none.
  double spacing = 0;
  std::vector<std::vector<std::size_t>> clusters;
};
template <int dim>
CrackClusters crack_clusters(const ParticleStore<dim> &particles, unsigned int body,
                             double thickness, double threshold = 0.99,
                             double link_factor = 1.5);
/**
 * How far a crack that starts at @p origin has run along the unit @p direction (m, in
 * the reference configuration): the largest projection onto @p direction, from
 * @p origin, of the particles of the crack_clusters() that hold a particle within 1.5
 * spacings of @p origin; 0 while none does. Used for a crack tip on a ligament. The
 * clusters link particles within 1.75 of their sizes: on cells up to twice as long
 * as wide, two particles per direction sit up to 1.63 sizes apart along the longer
 * side, and a crack across them must stay one cluster; 2 sizes would bridge an intact
 * particle in square cells.
 */
template <int dim>
double crack_tip_distance(const ParticleStore<dim> &particles, unsigned int body,
                          double thickness, const Point<2> &origin,
                          const Tensor<1, 2> &direction, double threshold = 0.99);
/// The Rayleigh surface-wave speed (m/s) of an isotropic elastic medium (Young's
/// modulus @p E, Poisson's ratio @p nu, density @p rho): the root of the Rayleigh
/// equation, with a thin plate's longitudinal speed in plane stress.
double rayleigh_wave_speed(double E, double nu, double rho, bool plane_stress);
/**
 * The crack the damage field of @p body shows, in the x-y plane of the reference
 * configuration: of the largest of its crack_clusters(), the
 * particles are sorted along its main axis (the principal direction of their
 * positions), cut into slices one spacing wide, and the centroids of successive
 * slices joined. Returns that polyline's length plus one spacing (the crack's extent
 * within its end slices), in m; 0 without damaged particles. The particle spacing is
 * the square root of a particle's initial area (volume over @p thickness in 2D).
 */
template <int dim>
double crack_path_length(const ParticleStore<dim> &particles, unsigned int body,
                         double thickness, double threshold = 0.99);
/**
 * The crack a damage field shows, in the x-y plane of the reference configuration:
 * the particles of one cluster of crack_clusters(), cut into slices one particle
 * spacing wide along the cluster's main axis; each slice gives a point of the path
 * (its particles' centroid) and the band's width there (the extent of its particles
 * across the axis plus one spacing).
 */
struct CrackPath
{
  double spacing = 0;
  std::vector<Point<2>> points;
  std::vector<double> widths;
  /// The path's length: its polyline's plus one spacing (the crack's extent within
  /// its end slices); 0 without damaged particles.
  double length() const;
};
/// The crack_path() of the largest cluster of @p body's particles with damage of at
/// least @p threshold, or with an @p origin (a notch tip) of the cluster that comes
/// nearest to it.
template <int dim>
CrackPath crack_path(const ParticleStore<dim> &particles, unsigned int body,
                     double thickness, double threshold,
                     const Point<2> *origin = nullptr);
/// Where a crack's energy went (doc/outputs.md).
struct CrackBand
{
  /// The median of the path's widths over its central 80 % (m).
  double width = 0;
  /// Fracture energy dissipated by the body's particles, all of them and those within
  /// one width of the crack's line (J).
  double dissipated = 0, on_crack = 0;
  /// The share of it dissipated farther than one width from the line.
  double off_crack_share = 0;
};
/// The band of @p path, the energy dissipated by @p body's particles, and its share
/// farther than one band width from the polyline @p line (reference positions).
template <int dim>
CrackBand crack_band(const ParticleStore<dim> &particles, unsigned int body,
                     const CrackPath &path, const std::vector<Point<2>> &line);
/// Adds crack_band_width and dissipation_off_crack_share of @p band to @p results.
void add_crack_band(const CrackBand &band, std::map<std::string, double> &results);
/// The distance from @p x to the polyline @p line (to its point if it has one).
double distance_to_polyline(const Point<2> &x, const std::vector<Point<2>> &line);
/**
 * Adds crack_area (crack_path_length() times @p thickness, m^2) and, with a fracture
 * energy @p G_F > 0, fracture_energy_ratio = dissipated_energy / (G_F crack_area) to
 * @p results.
 */
template <int dim>
void add_crack_energy(const ParticleStore<dim> &particles, unsigned int body,
                      double thickness, double G_F,
                      std::map<std::string, double> &results);
/**
 * How far the fully damaged particles of @p body (damage of at least @p threshold) lie
 * from one plane (a line in 2D): the root mean square distance of their reference
 * positions from the plane that fits them best in least squares, the plane through
 * their centroid normal to the least principal direction of their spread, divided by
 * @p cell. 0 with fewer than dim + 1 such particles. A crack one band wide and straight
 * reads about the band's width over sqrt(12) cells; a branch or a second crack reads
 * more.
 */
template <int dim>
double crack_plane_deviation(const ParticleStore<dim> &particles, unsigned int body,
                             double cell, double threshold = 0.99);
/// The fracture energy of the material body @p body is made of (0 without fracture).
double fracture_energy_of(const EntryWriter &writer, unsigned int body);
/// The damaged volume of @p body: sum of damage times volume over its particles (m^3
/// in 3D, m^2 in 2D).
template <int dim>
double damaged_volume(const ParticleStore<dim> &particles, unsigned int body);
/// The index of the body named @p name; throws ExcBadInput naming @p entry if none.
template <int dim>
unsigned int body_index(const SceneState<dim> &state, const std::string &name,
                        const std::string &entry);
/// The constrained node set named @p name; throws ExcBadInput naming @p entry if none.
template <int dim>
const NodeConstraint<dim> &constraint_named(const SceneState<dim> &state,
                                            const std::string &name,
                                            const std::string &entry);

/**
 * Adds the opening gauge @p name to Output/Opening gauges: points @p a and @p b in the
 * x-y plane (lines along z in 3D, so that it averages through the thickness), each
 * averaging the particles within @p radius. Its reading is history.csv's
 * opening_<name>, and a servo (Loading control/Gauge) may drive on it.
 */
void add_opening_gauge(EntryWriter &writer, const std::string &name, const Point<2> &a,
                       const Point<2> &b, double radius);
/// The reading of opening gauge @p name in a history row (all particles, rank 0).
template <int dim>
double gauge_reading(const SceneState<dim> &state, const std::string &name);
/**
 * Throws ExcBadInput naming scene entry @p owner unless both points of opening gauge
 * @p name hold particles (before the run; every rank holds all particles then).
 */
template <int dim>
void require_gauge_particles(const SceneState<dim> &state, const std::string &name,
                             const std::string &owner, const std::string &what);
} // namespace scenes
} // namespace lme_mpm

#endif
