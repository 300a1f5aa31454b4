// The coupled stepper in motion (issue 6): the multipliers hold the tied discs on the continuum to
// round-off, the coupling forces balance, an undamped coupled run keeps its energy, and bad
// set-ups are refused.
#include "test_coupling_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
TEST(CoupledStepper, MultipliersHoldTheTiedDiscsOnTheContinuum)
{
  CoupledPatch patch = coupled_patch_at_rest(LagrangeMultiplierCoupling{});
  launch_energy_pulse(patch, 1e-3); // the energy run's pulse (coupling_benchmarks.h)
  CoupledStepper &stepper = *patch.stepper;
  const auto &band = stepper.band_particles();
  const dem::ParticleSet &p = patch.particles->particles();
  double largest_gap = 0.0, largest_displacement = 0.0, largest_force_sum = 0.0, largest_force = 0.0;
  for (unsigned int n = 0; n < 600; ++n)
    {
      stepper.step();
      largest_gap = std::max(largest_gap, stepper.largest_velocity_gap());
      const auto forces = stepper.diagnostics().forces;
      largest_force_sum = std::max(largest_force_sum, (forces.on_particles + forces.on_continuum).norm());
      largest_force = std::max(largest_force, forces.on_particles.norm());
    }
  // The constraint acts on the half-step velocities that make the displacement increments, so the
  // tied discs' displacements equal the continuum's interpolated at them (both 0 when tied).
  double largest_mismatch = 0.0;
  for (std::size_t q = 0; q < band.size(); ++q)
    {
      const Vec2 disc = Vec2(p.x[band.body[q]], p.y[band.body[q]]) - band.reference_position[q];
      const Vec2 continuum = band.points.interpolate(patch.continuum->displacement(), q);
      largest_mismatch = std::max(largest_mismatch, (disc - continuum).norm());
      largest_displacement = std::max(largest_displacement, disc.norm());
    }
  std::cout << "multipliers: velocity gap " << largest_gap << " m/s, displacement mismatch " << largest_mismatch
            << " m of " << largest_displacement << " m, force sum " << largest_force_sum << " N/m of "
            << largest_force << " N/m" << std::endl;
  ASSERT_GT(largest_displacement, 1e-9); // the wave reached the band
  // Measured: gap 3.6e-19 m/s (pulse 1e-3 m/s), mismatch 2.2e-16 m of 1.4e-6 m, force sum 2.8e-14
  // N/m of 25 N/m.
  EXPECT_LT(largest_gap, 1e-12 * 1e-3);
  // Round-off of positions of ~0.1 m accumulated over the steps (an ulp is 1.4e-17 m).
  EXPECT_LT(largest_mismatch, 1e-14);
  EXPECT_LT(largest_force_sum, 1e-12 * largest_force);
}

/// The library's undamped energy run (apps/coupling_benchmarks/coupling_benchmarks.h), reported.
EnergyRecord reported_energy_record(const CouplingMethod &method, unsigned int n_steps, double dt = 0.0)
{
  const EnergyRecord record = energy_record(method, n_steps, dt);
  std::cout << "energy over " << n_steps << " steps of " << record.time_step << " s: drift " << record.drift
            << ", largest deviation " << record.largest_deviation << " (the continuum held up to "
            << record.continuum_share << " of it)" << std::endl;
  return record;
}

// The issue asks for a total energy drift below 1e-4 over 10,000 steps (method 1). The leapfrog
// conserves a shadow energy: the energy measured at full steps (the DEM's, and the continuum's
// velocity rebuilt at t_n) swings about it by O((omega dt)^2), here about 3e-3 at the stepper's
// own step for the pulse's frequencies, and the swing must shrink as dt^2 (16 times at dt / 4)
// while the mean must not move. Measured (12-row patch, pulse 1 mm/s, ~86 % of the energy in the
// continuum at its peak): multipliers, drift 2.0e-6 and swing 3.5e-3 at dt = 10.1 us, drift 1.0e-7
// and swing 2.2e-4 at dt / 4 (16.2 times less); penalty (factor 1), drift -4.4e-6, swing 2.4e-3 at
// dt = 9.1 us (the springs lower the step).
TEST(CoupledStepper, UndampedRunKeepsItsEnergyWithMultipliers)
{
  const EnergyRecord own = reported_energy_record(LagrangeMultiplierCoupling{}, 10000);
  EXPECT_GT(own.continuum_share, 0.5); // the wave did cross into the continuum
  EXPECT_LT(std::abs(own.drift), 1e-4);
  const EnergyRecord quarter = reported_energy_record(LagrangeMultiplierCoupling{}, 10000, 0.25 * own.time_step);
  EXPECT_LT(std::abs(quarter.drift), 1e-4);
  EXPECT_LT(quarter.largest_deviation, own.largest_deviation / 8.0); // dt^2 would give 16
}

TEST(CoupledStepper, UndampedRunKeepsItsEnergyWithPenalty)
{
  const EnergyRecord own = reported_energy_record(PenaltyCoupling{}, 10000);
  EXPECT_GT(own.continuum_share, 0.5);
  EXPECT_LT(std::abs(own.drift), 1e-4);
}

TEST(CoupledStepper, RefusesABandOutsideTheMeshAndAnUnstableStep)
{
  // The mesh starting two spacings into the band leaves band discs outside it.
  PatchGeometry g;
  g.band_start = 5.3;
  CoupledPatch patch;
  patch.particles = std::make_unique<dem::DemSystem>(patch_particles(g), bonded_lattice_law(g.kn, g.ks), undamped_settings());
  PatchGeometry shifted = g;
  shifted.band_start = 7.3;
  patch.mesh = patch_mesh(shifted);
  patch.continuum = std::make_unique<fem::ExplicitSolver>(*patch.mesh, matching_soil(g), fem::BoundaryConditions{},
                                                          patch_continuum_settings(g));
  const OverlapBand band(Vec2(g.band_start * g.spacing(), 0.0), Vec2(1.0, 0.0), g.band_width * g.spacing());
  EXPECT_NE(invalid_argument_message([&] { CoupledStepper(*patch.particles, *patch.continuum, band, LagrangeMultiplierCoupling{}); })
              .find("outside the continuum's mesh"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([&] { PenaltyCoupling{-1.0}.validate(); }).find("penalty factor"), std::string::npos);
  // A particle step the weighted band makes unstable (the band's light discs): refused, not lowered.
  EXPECT_NE(invalid_argument_message([&] { coupled_patch_at_rest(LagrangeMultiplierCoupling{}, {}, undamped_settings(2e-5)); })
              .find("above the stable limit"),
            std::string::npos);
}
} // namespace
