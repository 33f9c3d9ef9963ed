#include <deal.II/base/symmetric_tensor.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parallel.h>
#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/particles/damage_form.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace lme_mpm
{
template <int dim>
void FractureCoupling<dim>::declare_parameters(ParameterHandler &prm,
                                               const unsigned int n_materials)
{
  for (unsigned int m = 0; m < n_materials; ++m)
  {
    prm.enter_subsection(input::subsection_name("Material", m));
    prm.enter_subsection("Fracture");
    declare_fracture_parameters<dim>(prm);
    StrengthField<dim>::declare_parameters(prm);
    prm.leave_subsection();
    prm.leave_subsection();
  }
}

namespace
{
/**
 * lambda / M of @p material: the stress it gives across a uniaxial strain increment
 * over the stress along it, asked of the material itself on one particle (so the
 * plane assumption is the material's); 0 for a material without a stress along it.
 */
template <int dim>
double lame_coupling(const Material<dim> &material, const unsigned int id)
{
  ParticleStore<dim> probe;
  probe.add(Point<dim>(), 1.0, 1.0, id, 0);
  probe.strain_increment[0][0][0] = 1e-6;
  probe.strain[0][0][0]           = 1e-6;
  material.update_stress(probe, 0, 1, id);
  const double along = probe.stress[0][0][0];
  return along > 0 ? probe.stress[0][1][1] / along : 0.0;
}
} // namespace

template <int dim>
void FractureCoupling<dim>::parse_parameters(ParameterHandler &prm,
                                             const MaterialSet<dim> &materials,
                                             const BackgroundGrid<dim> &grid_,
                                             const double thickness)
{
  grid               = &grid_;
  specimen_thickness = thickness;
  placements.clear();
  uniform_grid = true;
  for (unsigned int d = 0; d < dim; ++d)
    uniform_grid = uniform_grid && grid->is_uniform(d);
  models.clear();
  strength_fields.assign(materials.size(), StrengthField<dim>());
  strength_floor.assign(materials.size(), 1.0);
  strengths_assigned = false;
  any_model          = false;
  for (unsigned int m = 0; m < materials.size(); ++m)
  {
    const std::string section = input::subsection_name("Material", m);
    prm.enter_subsection(section);
    prm.enter_subsection("Fracture");
    const std::string model = prm.get("Model");
    if (model != "none")
    {
      FractureContext fc;
      fc.grid_spacing   = grid->min_spacing();
      fc.thickness      = thickness;
      fc.dim            = dim;
      fc.p_wave_modulus = materials[m].density() * std::pow(materials[m].wave_speed(), 2);
      fc.lame_coupling  = lame_coupling(materials[m], m);
      fc.section        = section + "/Fracture";
      models.push_back(FractureModelRegistry<dim>::instance().create(model, prm, fc));
      any_model = true;
    }
    else
      models.emplace_back();
    strength_fields[m].parse_parameters(prm, section + "/Fracture", m);
    AssertThrow(!strength_fields[m].active() ||
                    (models.back() && models.back()->reads_strength_factors()),
                ExcBadInput(section + "/Fracture/Strength variability/Distribution",
                            "varies the tensile strength of a model that has one "
                            "(eigensoftening); Model = " +
                                model + " has none"));
    prm.leave_subsection();
    prm.leave_subsection();
  }
}

template <int dim>
void FractureCoupling<dim>::add_body(const BodyPlacement &body)
{
  placements.emplace_back(body.offsets, body.weights);
  // Only the cells the body starts in bound its neighbourhoods.
  check_neighbourhood(body.material, body.particles_per_cell, body.section, &body.cells);
  for (const unsigned int m : body.zone_materials)
    check_neighbourhood(m, body.particles_per_cell, body.section, &body.cells);
}

template <int dim>
void FractureCoupling<dim>::set_crack_band(const ShapeFunction<dim> &functions)
{
  if (!any_model)
    return;
  // A band width tied to the grid spans the band these functions spread a crack
  // over, which depends on where the body's particles sit in their cells.
  fields.band_cells.clear(), fields.band_reach.clear();
  for (const auto &band : crack_bands(functions, *grid, placements, specimen_thickness))
    fields.band_cells.push_back(band.width_cells),
        fields.band_reach.push_back(band.reach_cells);
  shares_openings = std::any_of(fields.band_reach.begin(), fields.band_reach.end(),
                                [](const double r) { return r > 0; });
  // The rows' reaches depend on the bands: the next prepare() finds them anew.
  prepared_size = unprepared;
}

template <int dim>
void FractureCoupling<dim>::check_neighbourhood(
    const unsigned int material, const unsigned int particles_per_cell,
    const std::string &body_section, const std::vector<std::uint8_t> *occupied) const
{
  if (!models[material])
    return;
  // The particle's h is its cell's shortest side; the particles are spaced by up to the
  // longest side / particles_per_cell. The worst cell the body occupies decides (on a
  // uniform grid every particle uses the grid's smallest spacing).
  double worst_margin = std::numeric_limits<double>::max(), h = 0, H = 0;
  std::array<unsigned int, dim> ijk{};
  for (unsigned int c = 0; c < grid->n_cells(); ++c)
  {
    double lo = std::numeric_limits<double>::max(), hi = 0;
    for (unsigned int d = 0; d < dim; ++d)
      lo = std::min(lo, grid->spacing(d, ijk[d])),
      hi = std::max(hi, grid->spacing(d, ijk[d]));
    if (uniform_grid)
      lo = grid->min_spacing();
    const double margin = models[material]->epsilon(lo) * particles_per_cell / hi;
    if (margin < worst_margin && (occupied == nullptr || (*occupied)[c]))
      worst_margin = margin, h = lo, H = hi;
    for (unsigned int d = 0; d < dim && ++ijk[d] == grid->n_cells_in(d); ++d)
      ijk[d] = 0;
  }
  {
    const double eps = models[material]->epsilon(h), spacing = H / particles_per_cell;
    AssertThrow(eps >= spacing,
                ExcBadInput(input::subsection_name("Material", material) +
                                "/Fracture/Epsilon factor",
                            "the neighbourhood radius C_eps h = " + std::to_string(eps) +
                                " in cells of size h = " + std::to_string(h) +
                                " is smaller than the particle spacing " +
                                std::to_string(spacing) + " of " + body_section +
                                "; raise it to at least " +
                                std::to_string(H / (h * particles_per_cell))));
  }
}

template <int dim>
double FractureCoupling<dim>::reach_at(const double h) const
{
  if (!any_model)
    return 0;
  double r = 0;
  for (const auto &f : models)
    if (f)
      r = std::max(r, f->search_radius(h));
  double band = 0;
  for (const double b : fields.band_reach)
    band = std::max(band, b);
  return r + band * h;
}

template <int dim>
double FractureCoupling<dim>::update_spacings(const ParticleStore<dim> &store)
{
  const std::size_t n = store.size();
  double h_largest    = grid->min_spacing();
  if (uniform_grid)
  {
    fields.spacing.clear();
    return h_largest;
  }
  // Sorted by cell since the last call: the lengths follow the sort's permutation,
  // without locating every particle again.
  const bool just_sorted = prepared_size == n && fields.spacing.size() == n &&
                           store.sorted_version() == store.order_version() &&
                           prepared_version + 1 == store.order_version();
  if (just_sorted)
  {
    const std::vector<std::uint32_t> &from = store.sort_permutation();
    spacing_scratch.resize(n);
    parallel::for_range(n,
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t p = b; p < e; ++p)
                            spacing_scratch[p] = fields.spacing[from[p]];
                        });
    fields.spacing.swap(spacing_scratch);
  }
  else
  {
    fields.spacing.resize(n);
    parallel::for_range(n,
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t p = b; p < e; ++p)
                          {
                            std::array<unsigned int, dim> cell;
                            grid->locate(store.reference_position[p], cell);
                            double h = grid->spacing(0, cell[0]);
                            for (unsigned int d = 1; d < dim; ++d)
                              h = std::min(h, grid->spacing(d, cell[d]));
                            fields.spacing[p] = h;
                          }
                        });
  }
  for (const double h : fields.spacing)
    h_largest = std::max(h_largest, h);
  return h_largest;
}

template <int dim>
void FractureCoupling<dim>::prepare(ParticleStore<dim> &store)
{
  const std::size_t n = store.size();
  // Per-particle lengths follow the particles: recomputed when they were reordered
  // (sorted by cell, or exchanged between ranks).
  if (prepared_size == n && prepared_version == store.order_version())
    return;
  // On a graded grid each particle's lengths follow the cell it started in; the
  // neighbourhood is searched to the widest radius, and each model keeps the
  // neighbours within its particle's own.
  double h_largest = update_spacings(store);
  // Every rank searches to the radius of all the particles. Their spacings are of their
  // reference positions and none is added or removed, so the largest over the ranks
  // is found once, at the first prepare() (the same step on every rank): later ones
  // follow a rank's own reorders, which the other ranks need not share.
  if (ranks)
  {
    if (h_all_ranks < 0)
      h_all_ranks = ranks->max(h_largest);
    Assert(h_largest <= h_all_ranks, ExcInternalError());
    h_largest = h_all_ranks;
  }
  if (!strengths_assigned)
    assign_strengths(store);
  radius         = 0;
  seeded_rows    = true;
  measures_bands = false;
  reads_stresses = false;
  thresholds.fill(std::numeric_limits<double>::infinity());
  for (unsigned int m = 0; m < models.size(); ++m)
    if (const auto &f = models[m])
    {
      radius                  = std::max(radius, f->search_radius(h_largest));
      measures_bands          = measures_bands || f->reads_crack_strains();
      reads_stresses          = reads_stresses || f->reads_stress_tensors();
      const FractureTrigger t = f->trigger(h_largest);
      if (t.field == FractureTrigger::Field::none)
        seeded_rows = false;
      else
      {
        double &bound = thresholds[static_cast<unsigned int>(t.field)];
        bound         = std::min(bound, t.threshold * strength_floor[m]);
      }
    }
  // Rows kept across steps where every model tests the distances itself. The skin
  // is a tenth of the radius: the rows are longer by about a fifth (2D) or a third
  // (3D), and are made anew once a particle has moved a twentieth of the radius.
  bool skin_rows = any_model;
  for (const auto &f : models)
    skin_rows = skin_rows && (!f || f->reads_rows_with_skin());
  neighbours.keep_lists(skin_rows ? skin_fraction * radius : 0);
  update_row_reaches(store);
  fields.max_principal_stress.resize(n);
  fields.energy_density.resize(n);
  fields.crack_opening.resize(n);
  fields.crack_strain.resize(measures_bands ? n : 0);
  fields.stress.resize(
      reads_stresses ? n * SymmetricTensor<2, dim>::n_independent_components : 0);
  fields.cracked.resize(reads_stresses ? n : 0);
  seeds.resize(n);
  prepared_size    = n;
  prepared_version = store.order_version();
}

template <int dim>
void FractureCoupling<dim>::update_row_reaches(const ParticleStore<dim> &store)
{
  // On a graded grid the rows are searched to the reach of the widest cell; a
  // particle in a fine cell reads only its own (a quarter of the row at half the
  // spacing in 2D). Each row is cut to it where every model says how far it reads.
  bool cut = !uniform_grid && any_model;
  for (const auto &f : models)
    cut = cut && (!f || std::isfinite(f->row_reach(grid->min_spacing(), 0)));
  if (!cut)
  {
    row_reaches.clear();
    return;
  }
  const std::size_t n = store.size();
  row_reaches.resize(n);
  parallel::for_range(
      n,
      [&](const std::size_t b, const std::size_t e)
      {
        // Neighbours in the store mostly share material, body and cell size: one
        // model call per change.
        unsigned int last_material = static_cast<unsigned int>(-1),
                     last_body     = static_cast<unsigned int>(-1);
        double last_h = -1, last_reach = radius;
        for (std::size_t p = b; p < e; ++p)
        {
          const unsigned int m = store.material_id[p], body = store.body_id[p];
          const double h = fields.spacing_of(p, grid->min_spacing());
          if (m != last_material || body != last_body || h != last_h)
          {
            // A slack of 1e-12 over the model's own distance tests (rounding of the
            // products); no model: the row (never taken) keeps the radius.
            last_reach = models[m] ? models[m]->row_reach(h, fields.band_reach_of(body)) *
                                         (1 + 1e-12)
                                   : radius;
            last_material = m, last_body = body, last_h = h;
          }
          row_reaches[p] = last_reach;
        }
      });
}

template <int dim>
void FractureCoupling<dim>::assign_strengths(ParticleStore<dim> &store)
{
  // A factor depends on the seed, the material and the particle alone: the same on
  // any number of threads and ranks, and again after a restart.
  for (unsigned int m = 0; m < strength_fields.size(); ++m)
  {
    const StrengthField<dim> &field = strength_fields[m];
    if (!field.active())
      continue;
    parallel::for_range(store.size(),
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t p = b; p < e; ++p)
                            if (store.material_id[p] == m)
                              store.strength[p] =
                                  field.factor(store.id[p], store.reference_position[p]);
                        });
    double lowest = 1e300;
    for (std::size_t p = 0; p < store.size(); ++p)
      if (store.material_id[p] == m)
        lowest = std::min(lowest, store.strength[p]);
    strength_floor[m] = ranks ? -ranks->max(-lowest) : lowest;
  }
  strengths_assigned = true;
}

template <int dim>
void FractureCoupling<dim>::take_snapshot(const ParticleStore<dim> &store,
                                          const std::size_t begin, const std::size_t end)
{
  using Field = FractureTrigger::Field;
  const double stress_bound =
                   thresholds[static_cast<unsigned int>(Field::max_principal_stress)],
               energy_bound =
                   thresholds[static_cast<unsigned int>(Field::energy_density)];
  for (std::size_t p = begin; p < end; ++p)
  {
    const bool alive   = !store.failed[p];
    const bool cracked = has_crack_normal(store, p);
    const double s     = alive ? max_principal(store.stress[p]) : 0.0;
    const double w =
        !alive    ? 0.0
        : cracked ? stored_energy_density(store, p)
                  : 0.5 * (1 - store.damage[p]) * (store.stress[p] * store.strain[p]);
    fields.max_principal_stress[p] = s;
    if (reads_stresses)
    {
      // A cracked particle's stress follows its crack's law: the onset means of
      // crack-oriented damage leave it out.
      fields.cracked[p] = cracked;
      const SymmetricTensor<2, dim> sigma =
          alive ? store.stress[p] : SymmetricTensor<2, dim>();
      constexpr unsigned int n_c = SymmetricTensor<2, dim>::n_independent_components;
      unsigned int c             = 0;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          fields.stress[p * n_c + c++] = sigma[i][j];
    }
    fields.energy_density[p] = w;
    fields.crack_opening[p]  = store.crack_opening[p];
    // Only softening and failed particles have one (a principal strain each), and only
    // a model that measures its band reads them.
    if (measures_bands)
    {
      // Along the crack's normal where the particle has one.
      const double chi = store.failed[p] ? 1.0 : store.damage[p];
      if (chi > 0)
      {
        const double strain =
            cracked ? store.crack_normal[p] * (store.strain[p] * store.crack_normal[p])
                    : max_principal(store.strain[p]);
        fields.crack_strain[p] = chi * std::max(0.0, strain);
      }
      else
        fields.crack_strain[p] = 0;
    }
    // Only alive particles of a material with a model read their row; a softening
    // particle reads it every step where its band shares their openings or is
    // measured from them.
    const bool reads = alive && models[store.material_id[p]] != nullptr;
    const bool softening =
        (shares_openings || measures_bands) && alive && store.onset_strain[p] != 0;
    seeds[p] =
        (s > stress_bound || w > energy_bound || softening ? Neighbourhood<dim>::seed
                                                           : 0) |
        (reads ? Neighbourhood<dim>::takes_row : 0);
  }
}

template <int dim>
void FractureCoupling<dim>::update(ParticleStore<dim> &store, const CrackSet<dim> *cracks,
                                   const bool snapshot_taken)
{
  const std::size_t n = store.size();
  if (!snapshot_taken)
  {
    prepare(store);
    parallel::for_range(n, [&](const std::size_t b, const std::size_t e)
                        { take_snapshot(store, b, e); });
  }
  Assert(prepared_size == n, ExcInternalError());
  // Neighbours from the particle's own body only: a tool pressed against a specimen
  // must not enter its onset or energy averages; nor from the other face of an
  // explicit crack. Rows only where a model can act (none before fracture starts).
  const std::vector<std::uint8_t> *row_seeds = seeded_rows ? &seeds : nullptr;
  // Named at each build, so that the neighbourhood never keeps a pointer into a
  // coupling that has since been copied or moved.
  neighbours.cut_rows_to(row_reaches.empty() ? nullptr : &row_reaches);
  if (cracks && !cracks->empty())
  {
    crack_bins.build(cracks->polylines(), radius);
    neighbours.build(
        store, *grid, radius,
        [&](const std::size_t p, const std::size_t q)
        { return crack_bins.separates(store.position[p], store.position[q]); },
        row_seeds,
        [&](const std::size_t p) { return crack_bins.may_separate(store.position[p]); });
  }
  else
    neighbours.build(store, *grid, radius, {}, row_seeds);
  rows_built += neighbours.n_rows();
  updates += 1;
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (unsigned int m = 0; m < models.size(); ++m)
                          if (models[m])
                            models[m]->update(store, neighbours, fields, b, e, m);
                      });
}

template <int dim>
void FractureCoupling<dim>::add_statistics(const ParticleStore<dim> &store,
                                           std::map<std::string, double> &results) const
{
  for (const auto &f : models)
    if (f)
      for (const auto &s : f->statistics())
        results[f->name() + "_" + s.first] = s.second;
  if (!any_model)
    return;
  std::size_t failed = 0;
  for (const auto f : store.failed)
    failed += f;
  results["failed_particles"] = failed;
  // The crack band's width and reach in cells: one entry each if every body has the
  // same, else one per body.
  for (const auto &[name, values] :
       {std::make_pair(std::string("crack_band_cells"), &fields.band_cells),
        std::make_pair(std::string("crack_band_reach_cells"), &fields.band_reach)})
  {
    const auto &v = *values;
    if (!v.empty() &&
        std::all_of(v.begin(), v.end(), [&](double b) { return b == v[0]; }))
      results[name] = v[0];
    else
      for (std::size_t b = 0; b < v.size(); ++b)
        results[name + "_body_" + std::to_string(b + 1)] = v[b];
  }
  // How much of the neighbourhood work the triggers left: 1 = every particle, every
  // step.
  if (updates > 0 && store.size() > 0)
    results["fracture_neighbourhood_share"] = rows_built / (updates * store.size());
  // How often the rows were searched anew (1 = every step; less where they are kept
  // with a skin).
  if (updates > 0)
    results["fracture_neighbour_searches_per_step"] =
        double(neighbours.n_list_builds()) / updates;
}

template class FractureCoupling<2>;
template class FractureCoupling<3>;
} // namespace lme_mpm
