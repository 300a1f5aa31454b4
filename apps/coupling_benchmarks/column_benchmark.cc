// The geostatic column across the band (coupling_benchmarks.h): gravity and damping in the
// coupled stepper, checked against the weight above each point.
#include "apps/coupling_benchmarks/coupling_benchmarks.h"
#include "apps/coupling_benchmarks/hexagonal_lattice.h"
#include "dem/measurements.h"

#include <cmath>
#include <stdexcept>

namespace geohybrid::coupling::benchmarks
{
double ColumnRecord::largest_relative_error() const
{
  double largest = 0.0;
  for (const ColumnSample &s : samples)
    largest = std::max(largest, std::abs(s.relative_error()));
  return largest;
}

double ColumnRecord::jump_across_band() const
{
  const ColumnSample *below = nullptr, *above = nullptr;
  for (const ColumnSample &s : samples)
    if (s.particles)
      below = &s;
    else if (!above)
      above = &s;
  if (!below || !above)
    throw std::logic_error("geostatic column: no window on one side of the band");
  return above->measured / above->closed_form - below->measured / below->closed_form;
}

namespace
{
/// The continuum's mean sigma_xx over the cells whose centre lies in [x0, x1] [Pa] (cells of equal
/// area, Gauss points of equal weight: a plain mean).
double continuum_mean_stress_xx(fem::ExplicitSolver &continuum, double x0, double x1)
{
  double sum = 0.0;
  unsigned int n = 0;
  for (const auto &cell : continuum.space().dof_handler().active_cell_iterators())
    if (cell->is_locally_owned() && cell->center()[0] > x0 && cell->center()[0] < x1)
      for (const auto &point : continuum.material_points().at(cell))
        {
          sum += point->stress[0][0];
          ++n;
        }
  if (n == 0)
    throw std::logic_error("geostatic column: a stress window holds no cell");
  return sum / n;
}
} // namespace

std::vector<double> run_column_to_rest(CoupledStepper &stepper, const std::function<std::vector<double>()> &measure,
                                       double tolerance, unsigned int max_steps, ColumnRecord &record,
                                       const std::string &what)
{
  std::vector<double> previous = measure();
  for (;;)
    {
      stepper.run_steps(500);
      record.n_steps += 500;
      const std::vector<double> now = measure();
      double change = 0.0;
      for (std::size_t k = 0; k < now.size(); ++k)
        change = std::max(change, std::abs(now[k] - previous[k]) / record.base_stress);
      previous = now;
      if (change < tolerance)
        return previous;
      if (record.n_steps >= max_steps)
        throw std::invalid_argument(what + ": not at rest after 'max steps' = " + std::to_string(max_steps) +
                                    " (stress change " + std::to_string(change) + ")");
    }
}

ColumnRecord geostatic_column(const CouplingMethod &method, const ColumnSpec &spec)
{
  if (!has_band(method))
    throw std::invalid_argument("geostatic column: the interface coupling (method 3) has no band");
  PatchGeometry g;
  g.rows = spec.rows;
  g.band_start = spec.band_start;
  g.band_width = spec.band_width;
  g.continuum_end = spec.continuum_end;
  g.cells_x = static_cast<unsigned int>(std::lround(spec.continuum_end - spec.band_start)); // one spacing each
  g.cells_y = spec.rows / 2;
  const double d = g.spacing(), h = g.row_height();

  // Multi-rate: the particles at the lockstep's step over the ratio, the continuum at the
  // lockstep's (the same continuum step, so that only the stepping differs).
  const unsigned int ratio = spec.continuum_step_ratio;
  double particle_step = spec.time_step;
  if (ratio > 1 && particle_step == 0.0)
    {
      ColumnSpec lockstep = spec;
      lockstep.continuum_step_ratio = 1;
      lockstep.max_steps = 0; // built, not run
      particle_step = geostatic_column(method, lockstep).time_step / ratio;
    }
  CoupledPatch patch;
  patch.geometry = g;
  dem::DemSettings particle_settings = undamped_settings(particle_step);
  particle_settings.gravity = Vec2(-spec.gravity, 0.0);
  particle_settings.local_damping = spec.local_damping;
  dem::ParticleSet discs = patch_particles(g);
  for (std::size_t b = 0; b < discs.n_bodies(); ++b)
    if (discs.x[b] < 0.75 * d) // the first disc of every row: the rigid base
      discs.fix_body(b);
  patch.particles = std::make_unique<dem::DemSystem>(std::move(discs), bonded_lattice_law(g.kn, g.ks), particle_settings);
  patch.particles->initialise_forces();
  patch.particles->bond_touching_contacts();
  patch.mesh = patch_mesh(g);
  fem::ExplicitSettings continuum_settings = patch_continuum_settings(g);
  continuum_settings.gravity[0] = -spec.gravity;
  continuum_settings.damping.local = spec.local_damping;
  patch.continuum =
    std::make_unique<fem::ExplicitSolver>(*patch.mesh, matching_soil(g), fem::BoundaryConditions{}, continuum_settings);
  patch.stepper = std::make_unique<CoupledStepper>(*patch.particles, *patch.continuum, patch_band(g), method,
                                                   BandTreatment{0.0, spec.scale_band_inertia}, MultiRate{ratio});

  ColumnRecord record;
  record.time_step = patch.stepper->time_step();
  record.continuum_step_ratio = patch.stepper->continuum_step_ratio();
  if (spec.max_steps == 0)
    return record;
  const double rho = continuum_settings.density, top = spec.continuum_end * d;
  record.base_stress = rho * spec.gravity * top;
  // Windows of `window` spacings, from the base's second spacing to the tied margin below the
  // band (a branch, two spacings, below it), and from the band's continuum edge to the surface.
  // A lattice window [x0, x0 + k d) with x0 = (n + 1/4) d holds k discs of every row.
  struct Window
  {
    double x0, x1;
    bool particles;
  };
  std::vector<Window> windows;
  for (double x0 = 1.25; x0 + spec.window <= spec.band_start - 2.0; x0 += spec.window)
    windows.push_back({x0 * d, (x0 + spec.window) * d, true});
  for (double x0 = spec.band_start + spec.band_width; x0 + spec.window <= spec.continuum_end + 1e-9; x0 += spec.window)
    windows.push_back({x0 * d, (x0 + spec.window) * d, false});
  const CouplingDiagnostics start = patch.stepper->diagnostics();
  const auto measure = [&] {
    record.energy_balance_error = energy_balance_error(start, patch.stepper->diagnostics());
    record.largest_energy_balance_error =
      std::max(record.largest_energy_balance_error, std::abs(record.energy_balance_error));
    std::vector<double> stress;
    for (const Window &w : windows)
      {
        const double sxx =
          w.particles ? dem::love_weber_stress(*patch.particles, dem::Region{w.x0, -0.5 * h, w.x1, (g.rows - 0.5) * h})[0]
                      : continuum_mean_stress_xx(*patch.continuum, w.x0, w.x1);
        stress.push_back(-sxx);
      }
    return stress;
  };
  const std::vector<double> previous =
    run_column_to_rest(*patch.stepper, measure, spec.tolerance, spec.max_steps, record, "geostatic column");
  const BandParticles &band = patch.stepper->band_particles();
  const dem::ParticleSet &p = patch.particles->particles();
  for (std::size_t q = 0; q < band.size(); ++q)
    {
      const Vec2 disc = Vec2(p.x[band.body[q]], p.y[band.body[q]]) - band.reference_position[q];
      const Vec2 continuum = band.points.interpolate(patch.continuum->displacement(), q);
      record.tied_mismatch = std::max(record.tied_mismatch, (disc - continuum).norm());
      record.tied_displacement = std::max(record.tied_displacement, disc.norm());
    }
  for (std::size_t k = 0; k < windows.size(); ++k)
    {
      const double centre = 0.5 * (windows[k].x0 + windows[k].x1);
      record.samples.push_back({centre, previous[k], rho * spec.gravity * (top - centre), windows[k].particles});
    }
  return record;
}
} // namespace geohybrid::coupling::benchmarks
