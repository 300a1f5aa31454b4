// A wave through the band (coupling_benchmarks.h): the energy the band reflects back into the
// particle region, measured against a run of the particles alone over the whole patch.
#include "coupling_benchmarks.h"

#include "apps/coupling_benchmarks/hexagonal_lattice.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace geohybrid::coupling::benchmarks
{
double Pulse::value(double x, double y) const
{
  const double r2 = std::pow(x - x0, 2) + (blob ? std::pow(y - y0, 2) : 0.0);
  return 1e-3 * std::exp(-r2 / (width * width));
}

namespace
{
void launch(dem::DemSystem &system, const std::vector<bool> &moving, const Pulse &pulse)
{
  dem::ParticleSet &p = system.particles();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (moving[b])
      p.vx[b] = pulse.value(p.x[b], p.y[b]);
}

} // namespace

double difference_energy(const dem::DemSystem &coupled, const dem::DemSystem &reference,
                         const std::vector<long> &coupled_of, const PatchGeometry &g)
{
  const dem::ParticleSet &pc = coupled.particles(), &pr = reference.particles();
  double difference = 0.0;
  for (std::size_t r = 0; r < pr.n_bodies(); ++r)
    if (coupled_of[r] >= 0)
      {
        const auto b = static_cast<std::size_t>(coupled_of[r]);
        difference += 0.5 * pr.mass[r] *
                      (std::pow(pc.vx[b] - pr.vx[r], 2) + std::pow(pc.vy[b] - pr.vy[r], 2)) +
                      0.5 * pr.inertia[r] * std::pow(pc.omega[b] - pr.omega[r], 2);
      }
  const auto &pairs = reference.pair_contacts();
  for (std::size_t q = 0; q < pairs.size(); ++q)
    {
      const std::size_t i = pr.disc_body[pairs.disc_i[q]], j = pr.disc_body[pairs.disc_j[q]];
      if (coupled_of[i] < 0 || coupled_of[j] < 0 || !pairs.state[q].touching)
        continue;
      const Vec2 branch(pr.x[j] - pr.x[i], pr.y[j] - pr.y[i]);
      const Vec2 n = branch.normalized(), t(-n.y(), n.x());
      const auto ci = static_cast<std::size_t>(coupled_of[i]), cj = static_cast<std::size_t>(coupled_of[j]);
      const Vec2 relative(pc.x[cj] - pr.x[j] - (pc.x[ci] - pr.x[i]), pc.y[cj] - pr.y[j] - (pc.y[ci] - pr.y[i]));
      difference += 0.5 * g.kn * std::pow(n.dot(relative), 2) + 0.5 * g.ks * std::pow(t.dot(relative), 2);
    }
  return difference;
}

void run_beside_reference(CoupledStepper &stepper, dem::DemSystem &reference, const dem::DemSystem &coupled,
                          const std::vector<long> &coupled_of, const PatchGeometry &g, double half_initial,
                          WaveRecord &record)
{
  const auto sample = [&] {
    const CouplingDiagnostics diagnostics = stepper.diagnostics();
    record.history.push_back({stepper.time(), difference_energy(coupled, reference, coupled_of, g) / half_initial,
                              (diagnostics.continuum_kinetic + diagnostics.continuum_elastic) / half_initial});
  };
  // Samples between windows only (both sides at one time: coupled_stepper.h).
  const unsigned int ratio = stepper.continuum_step_ratio();
  const unsigned int every = ratio * std::max(1u, record.n_steps / (200 * ratio));
  sample();
  for (unsigned int n = 0; n < record.n_steps;)
    {
      const unsigned int chunk = std::min(every, record.n_steps - n);
      stepper.run_steps(chunk);
      reference.run_steps(chunk);
      n += chunk;
      sample();
    }
  record.reflected = record.history.back().reflected;
  record.transmitted = record.history.back().in_continuum;
}

WaveRecord crossing(const CouplingMethod &method, const PatchGeometry &g, const Pulse &pulse, double travel,
                    double speed, unsigned int continuum_step_ratio)
{
  const unsigned int ratio = continuum_step_ratio;
  // Multi-rate: the lockstep's continuum step, the particles' divided by the ratio.
  const double particle_step = ratio == 1 ? 0.0 : coupled_patch_at_rest(method, g).stepper->time_step() / ratio;
  CoupledPatch patch = coupled_patch_at_rest(method, g, undamped_settings(particle_step), {}, MultiRate{ratio});
  dem::DemSystem &coupled = *patch.particles;
  const dem::ParticleSet &pc = coupled.particles();
  std::vector<bool> free_disc(pc.n_bodies(), true);
  for (const auto b : patch.stepper->band_particles().body)
    free_disc[b] = false;
  for (std::size_t b = 0; b < pc.n_bodies(); ++b)
    free_disc[b] = free_disc[b] && pc.inverse_mass[b] > 0.0;
  launch(coupled, free_disc, pulse);

  PatchGeometry whole = g;
  whole.band_start = g.continuum_end; // the lattice over the whole patch
  dem::DemSystem reference(patch_particles(whole), bonded_lattice_law(g.kn, g.ks),
                           undamped_settings(patch.stepper->time_step()));
  reference.initialise_forces();
  reference.bond_touching_contacts();
  const dem::ParticleSet &pr = reference.particles();
  launch(reference, std::vector<bool>(pr.n_bodies(), true), pulse);
  const double half_initial = 0.5 * reference.energy().kinetic;

  // The coupled run's free discs in the reference, by lattice id.
  std::unordered_map<std::int64_t, std::size_t> in_reference;
  for (std::size_t b = 0; b < pr.n_bodies(); ++b)
    in_reference[pr.body_id[b]] = b;
  std::vector<long> coupled_of(pr.n_bodies(), -1);
  for (std::size_t b = 0; b < pc.n_bodies(); ++b)
    if (free_disc[b])
      coupled_of[in_reference.at(pc.body_id[b])] = static_cast<long>(b);

  WaveRecord record;
  record.time_step = patch.stepper->time_step();
  record.n_steps = static_cast<unsigned int>(travel / speed / record.time_step);
  record.n_steps += (ratio - record.n_steps % ratio) % ratio; // whole windows: both sides at one time
  record.n_particles = pc.n_bodies();
  record.n_cells = patch.mesh->n_active_cells();
  run_beside_reference(*patch.stepper, reference, coupled, coupled_of, g, half_initial, record);
  return record;
}

PatchGeometry strip_geometry(const StripSpec &spec, const PatchGeometry &lattice)
{
  PatchGeometry g = lattice;
  g.rows = 6;
  g.band_start = spec.length + 0.3;
  g.band_width = spec.band_width;
  g.continuum_end = g.band_start + spec.band_width + spec.length;
  g.cells_x = static_cast<unsigned int>(std::max(1L, std::lround((spec.band_width + spec.length) / spec.cell_size)));
  g.cells_y = 3;
  return g;
}

WaveRecord strip_crossing(const CouplingMethod &method, const StripSpec &spec, const PatchGeometry &lattice)
{
  const PatchGeometry g = strip_geometry(spec, lattice);
  const double d = g.spacing();
  const auto m = hexagonal_lattice_moduli(g.kn, g.ks);
  const double bar_speed = std::sqrt(4.0 * m.shear_modulus * (m.lame_lambda + m.shear_modulus) /
                                     (m.lame_lambda + 2.0 * m.shear_modulus) / (g.density * m.density_factor));
  const double start = 0.5 * spec.length;
  const Pulse pulse{start * d, 0.0, spec.pulse_width * d, false};
  return crossing(method, g, pulse, (g.band_start - start + spec.band_width + 0.5 * spec.length) * d, bar_speed,
                  spec.continuum_step_ratio);
}
} // namespace geohybrid::coupling::benchmarks
