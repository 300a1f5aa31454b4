// Method 3's benchmarks (coupling_benchmarks.h): the patch test, the long wave and the undamped
// energy run of a lattice standing on the continuum across the non-overlapping interface
// (standing_lattice.h). The measures are those of methods 1 and 2 (patch_benchmark.cc,
// wave_benchmark.cc), across the interface y = 0 instead of a band.
#include "coupling_benchmarks.h"

#include "coupling/hexagonal_lattice.h"
#include "coupling/standing_lattice.h"

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

EnergyRecord interface_energy_record(const InterfaceCoupling &interface, const StripSpec &spec, unsigned int n_steps,
                                     double time_step, const PatchGeometry &lattice)
{
  StandingLattice s = standing_strip(spec, interface, lattice, time_step);
  launch_downward_pulse(s.particles->particles(), spec, s.g, s.bottom_row());
  return undamped_energy_record(*s.stepper, n_steps);
}
} // namespace geohybrid::coupling::benchmarks
