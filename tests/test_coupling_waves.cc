// Waves through the overlap band (issue 6): the energy the band reflects back into the particle
// region, for both coupling methods, in a strip (1D-like) and in a square patch (2D).
#include "test_coupling_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// The library's wave benchmarks (apps/coupling_benchmarks/coupling_benchmarks.h: the pulse, the reference run of
/// the particles alone, the difference energy in the free discs), reported.
WaveRecord reported(const WaveRecord &record, const PatchGeometry &g, double pulse_width, bool blob)
{
  std::cout << "band of " << g.band_width << " spacings, pulse width " << pulse_width << " spacings"
            << (blob ? " (2D)" : "") << ": reflected energy fraction " << record.reflected << ", in the continuum "
            << record.transmitted << " (" << record.n_steps << " steps)" << std::endl;
  return record;
}

/// The 1D-like strip of 40 spacings of particles and 40 of continuum (cells of one spacing).
WaveRecord strip_crossing(const CouplingMethod &method, double band_width, double pulse_width)
{
  const StripSpec spec{band_width, pulse_width, 40.0, 1.0};
  return reported(benchmarks::strip_crossing(method, spec), strip_geometry(spec), pulse_width, false);
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
  const WaveRecord record =
    reported(crossing(LagrangeMultiplierCoupling{}, g, blob, (10.0 + 4.0 + 10.0) * d, shear_speed), g, 4.0, true);
  EXPECT_LT(record.reflected, 1e-2);
  EXPECT_GT(record.transmitted, 0.5);
}
} // namespace
