// Method 3's benchmarks (coupling_benchmarks.h): the patch test, the long wave and the undamped
// energy run of a lattice standing on the continuum across the non-overlapping interface
// (standing_lattice.h). The measures are those of methods 1 and 2 (patch_benchmark.cc,
// wave_benchmark.cc), across the interface y = 0 instead of a band.
#include "coupling_benchmarks.h"

#include "apps/coupling_benchmarks/hexagonal_lattice.h"
#include "apps/coupling_benchmarks/standing_lattice.h"
#include "dem/measurements.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace geohybrid::coupling::benchmarks
{
InterfacePatchTestResult interface_patch_test(const InterfaceCoupling &interface, const PlaneStrain &eps,
                                              const PatchGeometry &lattice)
{
  if (eps.xy != 0.0)
    throw std::invalid_argument("interface patch test: shear strain eps_xy = " + std::to_string(eps.xy) +
                                " cannot be applied (a disc-edge contact formed at the strained state starts with an "
                                "unloaded tangential spring); set it to 0");
  if (eps.xx == 0.0 && eps.yy == 0.0)
    throw std::invalid_argument("interface patch test: the strain is 0 (the ghost forces are relative to its stress)");
  StandingLattice s = standing_lattice(lattice, 14, 9, 6, interface);
  const PatchGeometry &g = s.g;
  const double d = g.spacing(), h = g.row_height();
  s.particles = strained_lattice(s.discs(), g, eps);
  strain_continuum(*s.continuum, g, eps); // its edge y = 0 moves with the same field
  s.stepper = std::make_unique<CoupledStepper>(*s.particles, *s.continuum, s.interface); // forces at t = 0

  InterfacePatchTestResult result;
  result.stress = stress_norm(g, eps);
  result.n_particles = s.particles->particles().n_bodies();
  result.n_cells = s.mesh->n_active_cells();
  // Away from the free sides: their discs and nodes carry the uniform stress without a traction.
  const double x_low = 1.5 * d, x_high = (s.columns - 2.5) * d;
  const dem::ParticleSet &p = s.particles->particles();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (p.y[b] < s.bottom_row() + 0.5 * h && p.x[b] > x_low && p.x[b] < x_high)
      result.bottom_discs = std::max(result.bottom_discs, std::hypot(p.fx[b], p.fy[b]) / (result.stress * d));
  const fem::ExplicitSolver &c = *s.continuum;
  for (const InterfaceNode &n : s.stepper->interface_wall()->nodes())
    if (n.reference.x() > x_low && n.reference.x() < x_high)
      for (const unsigned int dof : {n.x_dof, n.y_dof})
        result.interface_nodes =
          std::max(result.interface_nodes, std::abs(c.external_force().local_element(dof) -
                                                    c.internal_force().local_element(dof)) / (result.stress * d));
  return result;
}

namespace
{
/// The downward pulse of the standing strip on every disc of `p`, centred `length / 2` spacings
/// above the bottom row at `bottom_row` [m].
void launch_downward_pulse(dem::ParticleSet &p, const StripSpec &spec, const PatchGeometry &g, double bottom_row)
{
  const double y0 = bottom_row + 0.5 * spec.length * g.spacing(), width = spec.pulse_width * g.spacing();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    p.vy[b] = -1e-3 * std::exp(-std::pow((p.y[b] - y0) / width, 2));
}

/// The long-wave (bar) speed of a strip with free sides, sqrt(E_2D / rho) [m/s].
double strip_bar_speed(const PatchGeometry &g)
{
  const auto m = hexagonal_lattice_moduli(g.kn, g.ks);
  return std::sqrt(4.0 * m.shear_modulus * (m.lame_lambda + m.shear_modulus) / (m.lame_lambda + 2.0 * m.shear_modulus) /
                   (g.density * m.density_factor));
}
} // namespace

WaveRecord interface_strip_crossing(const InterfaceCoupling &interface, const StripSpec &spec,
                                    const PatchGeometry &lattice)
{
  StandingLattice s = standing_strip(spec, interface, lattice);
  const PatchGeometry &g = s.g;
  dem::DemSystem &coupled = *s.particles;
  const dem::ParticleSet &pc = coupled.particles();
  launch_downward_pulse(coupled.particles(), spec, g, s.bottom_row());

  // The reference: the lattice continued below the interface in place of the continuum.
  const unsigned int rows_below = standing_strip_rows_below(spec);
  dem::DemSystem reference(s.discs(rows_below), bonded_lattice_law(g.kn, g.ks), undamped_settings(s.stepper->time_step()));
  reference.initialise_forces();
  reference.bond_touching_contacts();
  const dem::ParticleSet &pr = reference.particles();
  launch_downward_pulse(reference.particles(), spec, g, s.bottom_row());
  const double half_initial = 0.5 * reference.energy().kinetic;

  // Every coupled disc in the reference: disc (i, j) there is (i, j + rows_below).
  std::unordered_map<std::int64_t, std::size_t> in_reference;
  for (std::size_t b = 0; b < pr.n_bodies(); ++b)
    in_reference[pr.body_id[b]] = b;
  std::vector<long> coupled_of(pr.n_bodies(), -1);
  for (std::size_t b = 0; b < pc.n_bodies(); ++b)
    coupled_of[in_reference.at(pc.body_id[b] + lattice_id(0, rows_below))] = static_cast<long>(b);

  WaveRecord record;
  record.time_step = s.stepper->time_step();
  // Half the length down to the interface, half into the continuum.
  record.n_steps = static_cast<unsigned int>(spec.length * g.spacing() / strip_bar_speed(g) / record.time_step);
  record.n_particles = pc.n_bodies();
  record.n_cells = s.mesh->n_active_cells();
  run_beside_reference(*s.stepper, reference, coupled, coupled_of, g, half_initial, record);
  return record;
}

ColumnRecord interface_geostatic_column(const InterfaceCoupling &interface, const InterfaceColumnSpec &spec,
                                        const PatchGeometry &lattice)
{
  StandingLattice s = standing_lattice(lattice, spec.columns, spec.rows, spec.depth, interface);
  const PatchGeometry &g = s.g;
  const double d = g.spacing(), h = g.row_height();
  // The continuum again, with its base (y = min: boundary id 2 of the colorized rectangle) fixed,
  // under gravity and damped; the lattice under the same gravity and damping.
  fem::ExplicitSettings continuum_settings = patch_continuum_settings(g);
  continuum_settings.gravity[1] = -spec.gravity;
  continuum_settings.damping.local = spec.local_damping;
  fem::BoundaryConditions base;
  base.displacements.push_back({2, true, true, nullptr});
  s.continuum = std::make_unique<fem::ExplicitSolver>(*s.mesh, matching_soil(g), base, continuum_settings);
  dem::DemSettings particle_settings = undamped_settings();
  particle_settings.gravity = Vec2(0.0, -spec.gravity);
  particle_settings.local_damping = spec.local_damping;
  s.particles = std::make_unique<dem::DemSystem>(s.discs(), bonded_lattice_law(g.kn, g.ks), particle_settings);
  s.particles->initialise_forces();
  s.particles->bond_touching_contacts();
  s.stepper = std::make_unique<CoupledStepper>(*s.particles, *s.continuum, s.interface);

  ColumnRecord record;
  record.time_step = s.stepper->time_step();
  const double rho = continuum_settings.density;
  // The lattice's mass per area is rho (its discs' mass over d h each), from half a row below
  // the bottom row to half a row above the top one; the continuum's from y = 0 down.
  const double lattice_bottom = s.bottom_row() - 0.5 * h, lattice_top = lattice_bottom + spec.rows * h;
  const double lattice_weight = rho * spec.gravity * spec.rows * h;
  record.base_stress = lattice_weight + rho * spec.gravity * spec.depth * d;
  struct Window
  {
    double y0, y1;
    bool particles;
  };
  std::vector<Window> windows;
  const auto rows_per_window = static_cast<unsigned int>(std::max(1L, std::lround(spec.window * d / h)));
  std::vector<Window> lattice_windows;
  for (unsigned int j = 1; j + rows_per_window <= spec.rows; j += rows_per_window)
    lattice_windows.push_back({lattice_bottom + j * h, lattice_bottom + (j + rows_per_window) * h, true});
  windows.assign(lattice_windows.rbegin(), lattice_windows.rend());
  for (double y1 = 0.0; y1 - spec.window * d >= -1.0 * spec.depth * d - 1e-9 * d; y1 -= spec.window * d)
    windows.push_back({y1 - spec.window * d, y1, false});
  const auto continuum_mean_stress_yy = [&](double y0, double y1) {
    double sum = 0.0;
    unsigned int n = 0;
    for (const auto &cell : s.continuum->space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned() && cell->center()[1] > y0 && cell->center()[1] < y1)
        for (const auto &point : s.continuum->material_points().at(cell))
          {
            sum += point->stress[1][1];
            ++n;
          }
    if (n == 0)
      throw std::logic_error("interface geostatic column: a stress window holds no cell");
    return sum / n;
  };
  // Love-Weber over a region wider than the lattice by half a spacing on each side (the side
  // discs move sideways as the column is loaded, and a disc on the region's edge may fall out),
  // scaled to the lattice's width, columns x d (each disc stands for d x h).
  const double wide = spec.columns + 1.0;
  const auto measure = [&] {
    std::vector<double> stress;
    for (const Window &w : windows)
      stress.push_back(
        -(w.particles ? dem::love_weber_stress(*s.particles, dem::Region{-d, w.y0, spec.columns * d, w.y1})[1] * wide /
                          spec.columns
                      : continuum_mean_stress_yy(w.y0, w.y1)));
    return stress;
  };
  const std::vector<double> previous =
    run_column_to_rest(*s.stepper, measure, spec.tolerance, spec.max_steps, record, "interface geostatic column");
  for (std::size_t k = 0; k < windows.size(); ++k)
    {
      const double centre = 0.5 * (windows[k].y0 + windows[k].y1);
      const double weight_above = windows[k].particles ? rho * spec.gravity * (lattice_top - centre)
                                                       : lattice_weight - rho * spec.gravity * centre;
      record.samples.push_back({centre, previous[k], weight_above, windows[k].particles});
    }
  return record;
}

EnergyRecord interface_energy_record(const InterfaceCoupling &interface, const StripSpec &spec, unsigned int n_steps,
                                     double time_step, const PatchGeometry &lattice)
{
  StandingLattice s = standing_strip(spec, interface, lattice, time_step);
  launch_downward_pulse(s.particles->particles(), spec, s.g, s.bottom_row());
  return undamped_energy_record(*s.stepper, n_steps);
}
} // namespace geohybrid::coupling::benchmarks
