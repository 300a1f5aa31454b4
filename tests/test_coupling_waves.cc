// Waves through the overlap band (issue 6): the energy the band reflects back into the particle
// region, for both coupling methods, in a strip (1D-like) and in a square patch (2D).
#include "test_coupling_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <unordered_map>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// A strip 6 rows high: particles over 40 spacings, a band of `band_width` spacings, the continuum
/// 40 spacings beyond it in cells of one spacing.
PatchGeometry strip(double band_width)
{
  PatchGeometry g;
  g.rows = 6;
  g.band_start = 40.3;
  g.band_width = band_width;
  g.continuum_end = g.band_start + band_width + 40.0;
  g.cells_x = static_cast<unsigned int>(band_width + 40.0);
  g.cells_y = 3;
  return g;
}

/// The pulse: x-velocity V exp(-((x - x0) / s)^2), x0 = 20 spacings, s in spacings (for s = 4 its
/// spectrum lies at wavelengths above about 2 pi s / 2 ~ 12 spacings: long waves), on the free discs. It splits
/// into a left- and a right-going half; the right-going one crosses the band.
/// The pulse's shape: 1D (a function of x only) or 2D (a blob round (x0, y0)).
struct Pulse
{
  double x0 = 0.0, y0 = 0.0, width = 0.0; ///< [m]
  bool blob = false;
  double value(double x, double y) const
  {
    const double r2 = std::pow(x - x0, 2) + (blob ? std::pow(y - y0, 2) : 0.0);
    return 1e-3 * std::exp(-r2 / (width * width));
  }
};

void launch(dem::DemSystem &system, const std::vector<bool> &moving, const Pulse &pulse)
{
  dem::ParticleSet &p = system.particles();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (moving[b])
      p.vx[b] = pulse.value(p.x[b], p.y[b]);
}

/// The fraction of the incident (right-going, half the initial) energy that the band sends back
/// into the free particles: the energy of the difference between the coupled run and a run of the
/// particles alone over the whole strip (the reference: no band, no reflection), summed over the
/// coupled run's free discs (kinetic, and the linearised springs of the contacts between them),
/// once the pulse has crossed the band and runs 20 spacings into the continuum.
struct WaveRecord
{
  double reflected = 0.0, transmitted = 0.0;
};
/// The run: `travel` is how far [m] the slowest wave of interest must go before the measurement,
/// at `speed` [m/s].
WaveRecord crossing(const CouplingMethod &method, const PatchGeometry &g, const Pulse &pulse, double travel,
                    double speed)
{
  CoupledPatch patch = coupled_patch_at_rest(method, g);
  dem::DemSystem &coupled = *patch.particles;
  const dem::ParticleSet &pc = coupled.particles();
  std::vector<bool> free_disc(pc.n_bodies(), true);
  for (const auto b : patch.stepper->band_particles().body)
    free_disc[b] = false;
  for (std::size_t b = 0; b < pc.n_bodies(); ++b)
    free_disc[b] = free_disc[b] && pc.inverse_mass[b] > 0.0;
  launch(coupled, free_disc, pulse);

  PatchGeometry whole = g;
  whole.band_start = g.continuum_end; // the lattice over the whole strip
  dem::DemSystem reference(patch_particles(whole), bonded_lattice_law(g.kn, g.ks),
                           undamped_settings(patch.stepper->time_step()));
  reference.initialise_forces();
  reference.bond_touching_contacts();
  const dem::ParticleSet &pr = reference.particles();
  launch(reference, std::vector<bool>(pr.n_bodies(), true), pulse);
  const double initial = reference.energy().kinetic;

  const auto n_steps = static_cast<unsigned int>(travel / speed / patch.stepper->time_step());
  patch.stepper->run_steps(n_steps);
  reference.run_steps(n_steps);

  // The coupled run's free discs in the reference, by lattice id.
  std::unordered_map<std::int64_t, std::size_t> in_reference;
  for (std::size_t b = 0; b < pr.n_bodies(); ++b)
    in_reference[pr.body_id[b]] = b;
  std::vector<long> coupled_of(pr.n_bodies(), -1);
  double difference = 0.0;
  for (std::size_t b = 0; b < pc.n_bodies(); ++b)
    if (free_disc[b])
      {
        const std::size_t r = in_reference.at(pc.body_id[b]);
        coupled_of[r] = static_cast<long>(b);
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
  WaveRecord record;
  // A 1D pulse sends half its energy each way; a 2D blob, less than half toward the band: the
  // fraction is of half the initial energy in both cases (a bound from above for the blob's).
  record.reflected = difference / (0.5 * initial);
  const CouplingDiagnostics diagnostics = patch.stepper->diagnostics();
  record.transmitted = (diagnostics.continuum_kinetic + diagnostics.continuum_elastic) / (0.5 * initial);
  std::cout << "band of " << g.band_width << " spacings, pulse width " << pulse.width / g.spacing()
            << " spacings" << (pulse.blob ? " (2D)" : "") << ": reflected energy fraction " << record.reflected
            << ", in the continuum " << record.transmitted << " (" << n_steps << " steps)" << std::endl;
  return record;
}

/// The 1D-like strip: the pulse 20 spacings in, measured when it runs 20 spacings into the
/// continuum at the bar speed sqrt(E_2D / rho) (the long-wave speed of a strip with free sides).
WaveRecord strip_crossing(const CouplingMethod &method, double band_width, double pulse_width)
{
  const PatchGeometry g = strip(band_width);
  const double d = g.spacing();
  const auto m = hexagonal_lattice_moduli(g.kn, g.ks);
  const double bar_speed = std::sqrt(4.0 * m.shear_modulus * (m.lame_lambda + m.shear_modulus) /
                                     (m.lame_lambda + 2.0 * m.shear_modulus) / (g.density * m.density_factor));
  const Pulse pulse{20.0 * d, 0.0, pulse_width * d, false};
  return crossing(method, g, pulse, (g.band_start - 20.0 + band_width + 20.0) * d, bar_speed);
}

// The issue asks for a reflected energy fraction below 1e-2 for long waves (wavelength >= 10
// particle diameters) with method 1. Measured (strip of 6 rows, band 4 spacings, cells of one
// spacing): multipliers 1.5e-4 for the long pulse (s = 4 spacings, 98.6 % of the incident energy in
// the continuum after the crossing), 1.5e-2 for a short one (s = 1 spacing), which must reflect
// more (the measure sees reflections); penalty (factor 1) 4.7e-3 for the long pulse.
TEST(WaveThroughTheBand, MultipliersReflectLittleOfALongWave)
{
  const WaveRecord long_wave = strip_crossing(LagrangeMultiplierCoupling{}, 4.0, 4.0);
  EXPECT_LT(long_wave.reflected, 1e-2);
  EXPECT_GT(long_wave.transmitted, 0.9); // the pulse did cross
  const WaveRecord short_wave = strip_crossing(LagrangeMultiplierCoupling{}, 4.0, 1.0);
  EXPECT_GT(short_wave.reflected, 3.0 * long_wave.reflected);
}

TEST(WaveThroughTheBand, PenaltyReflectsLittleOfALongWave)
{
  const WaveRecord long_wave = strip_crossing(PenaltyCoupling{}, 4.0, 4.0);
  EXPECT_LT(long_wave.reflected, 1e-2);
  EXPECT_GT(long_wave.transmitted, 0.9);
}
// The same through a square patch: a blob of x-velocity (width 4 spacings) 10 spacings from the
// band sends P and S waves at all angles; measured once the S waves have run 10 spacings past
// the band (the P waves are then 40 spacings on, short of the continuum's far end). Measured:
// reflected 1.1e-4 of half the initial energy, 77 % of it in the continuum (40 rows, 1,300 discs
// coupled, 2,600 in the reference run, 144 steps).
TEST(WaveThroughTheBand, MultipliersReflectLittleOfA2DWave)
{
  PatchGeometry g;
  g.rows = 40;
  g.band_start = 30.3;
  g.band_width = 4.0;
  g.continuum_end = g.band_start + 4.0 + 46.0;
  g.cells_x = 50;
  g.cells_y = 35;
  const double d = g.spacing();
  const auto m = hexagonal_lattice_moduli(g.kn, g.ks);
  const double shear_speed = std::sqrt(m.shear_modulus / (g.density * m.density_factor));
  const Pulse blob{20.3 * d, 0.5 * (g.rows - 1) * g.row_height(), 4.0 * d, true};
  const WaveRecord record = crossing(LagrangeMultiplierCoupling{}, g, blob, (10.0 + 4.0 + 10.0) * d, shear_speed);
  EXPECT_LT(record.reflected, 1e-2);
  EXPECT_GT(record.transmitted, 0.5);
}
} // namespace
