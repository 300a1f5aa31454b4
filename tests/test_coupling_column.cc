// The geostatic column across the band (issue 6: "vertical stress continuous within 2 %"):
// gravity and local damping on both sides of the coupled stepper, run to rest, and the vertical
// stress of each model against the weight above it.
#include "test_coupling_patch.h"

#include "apps/coupling_benchmarks/coupling_benchmarks.h"
#include "apps/coupling_benchmarks/standing_lattice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::benchmarks;
using namespace geohybrid::coupling::testing;

namespace
{
ColumnRecord reported_column(const CouplingMethod &method, const char *name, const ColumnSpec &spec = {})
{
  const ColumnRecord record = geostatic_column(method, spec);
  std::cout << name << ": at rest after " << record.n_steps << " steps of " << record.time_step
            << " s; base stress rho g H = " << record.base_stress << " Pa\n";
  for (const ColumnSample &s : record.samples)
    std::cout << "  " << (s.particles ? "particles " : "continuum ") << "x = " << s.height << " m: sigma_v "
              << s.measured << " Pa, weight above " << s.closed_form << " Pa, error " << s.relative_error() << "\n";
  std::cout << "  jump across the band " << record.jump_across_band() << "; tied discs off the continuum by "
            << record.tied_mismatch << " m of " << record.tied_displacement << " m; energy balance error at rest "
            << record.energy_balance_error << std::endl;
  return record;
}

// Both models carry the weight above them within 2 %, and the stress has no step across the band
// larger than 2 % (windows of 4 spacings; the lattice's windows are Love-Weber averages).
TEST(GeostaticColumn, VerticalStressIsTheWeightAboveAcrossTheBandWithMultipliers)
{
  const ColumnRecord record = reported_column(LagrangeMultiplierCoupling{}, "multipliers");
  ASSERT_GE(record.samples.size(), 6u);
  EXPECT_LT(record.largest_relative_error(), 0.02);
  EXPECT_LT(std::abs(record.jump_across_band()), 0.02);
  // The tied discs and the nodes they follow are exempt from damping, so the multipliers hold
  // them on the continuum to round-off through the damped run (damping them opens a gap of the
  // damping's impulse each step).
  EXPECT_GT(record.tied_displacement, 1e-7);
  EXPECT_LT(record.tied_mismatch, 1e-9 * record.tied_displacement); // measured 1.4e-15 m: round-off of positions ~0.2 m
}

TEST(GeostaticColumn, VerticalStressIsTheWeightAboveAcrossTheBandWithPenalty)
{
  const ColumnRecord record = reported_column(PenaltyCoupling{}, "penalty");
  ASSERT_GE(record.samples.size(), 6u);
  EXPECT_LT(record.largest_relative_error(), 0.02);
  EXPECT_LT(std::abs(record.jump_across_band()), 0.02);
}

// The band's inertia scaled (a quasi-static run's choice, dem::CouplingAttachment::scale_band_inertia): the
// step goes back to the unweighted particles' bound and the statics stay within the same 2 %.
TEST(GeostaticColumn, ScalingTheBandsInertiaKeepsTheStressAndRaisesTheStep)
{
  ColumnSpec scaled;
  scaled.scale_band_inertia = true;
  const ColumnRecord weighted = geostatic_column(LagrangeMultiplierCoupling{}, ColumnSpec{});
  const ColumnRecord record = reported_column(LagrangeMultiplierCoupling{}, "multipliers, band inertia scaled", scaled);
  ASSERT_GE(record.samples.size(), 6u);
  EXPECT_LT(record.largest_relative_error(), 0.02);
  EXPECT_LT(std::abs(record.jump_across_band()), 0.02);
  EXPECT_LT(record.tied_mismatch, 1e-9 * record.tied_displacement);
  std::cout << "  step " << record.time_step << " s against " << weighted.time_step << " s with the weighted inertia"
            << std::endl;
  EXPECT_GT(record.time_step, 1.5 * weighted.time_step);
  // The same statics: each window's stress within 0.5 % of the weighted run's.
  ASSERT_EQ(record.samples.size(), weighted.samples.size());
  for (std::size_t k = 0; k < record.samples.size(); ++k)
    EXPECT_NEAR(record.samples[k].measured, weighted.samples[k].measured, 5e-3 * weighted.samples[k].measured);
}

// The coupled system's energy balance with gravity and local damping on both sides
// (CouplingDiagnostics::ledger_total: the particles' budget, the continuum's work ledger, the
// coupling's stored energy; the coupling forces' work cancels between the sides): what is left
// from release to rest is the two integrators' discretisation error, which falls as dt^2.
TEST(GeostaticColumn, EnergyBalanceClosesWithGravityAndDamping)
{
  for (const bool multipliers : {true, false})
    {
      const CouplingMethod method =
        multipliers ? CouplingMethod{LagrangeMultiplierCoupling{}} : CouplingMethod{PenaltyCoupling{}};
      const ColumnRecord full = geostatic_column(method, ColumnSpec{});
      ColumnSpec halved;
      halved.time_step = 0.5 * full.time_step;
      const ColumnRecord half = geostatic_column(method, halved);
      std::cout << (multipliers ? "multipliers" : "penalty") << ": energy balance error at rest "
                << full.energy_balance_error << " at dt = " << full.time_step << " s, " << half.energy_balance_error
                << " at dt / 2 (largest on the way " << full.largest_energy_balance_error << ", "
                << half.largest_energy_balance_error << ")" << std::endl;
      EXPECT_LT(std::abs(full.energy_balance_error), 1e-4);
      EXPECT_GT(full.energy_balance_error / half.energy_balance_error, 3.0); // O(dt^2): 4
    }
}

// Method 3: the lattice (8 columns, 24 rows) stands on the continuum (20 cells deep) across the
// non-overlapping interface (the matched springs, 30 deg); each carries the weight above it, with
// no step across the interface. The issue asks 2 %; measured 3.0e-5 (the lattice's windows, the
// geometry of its compression) and 9.4e-7 (the continuum's), asked 1e-4. (The interface forces
// reach the lattice as the hook's, not as contacts: its window starts at the second row.)
TEST(GeostaticColumn, VerticalStressIsTheWeightAboveAcrossTheInterface)
{
  const ColumnRecord record = interface_geostatic_column(matched_interface(PatchGeometry{}));
  std::cout << "interface: at rest after " << record.n_steps << " steps of " << record.time_step
            << " s; base stress " << record.base_stress << " Pa\n";
  for (const ColumnSample &s : record.samples)
    std::cout << "  " << (s.particles ? "particles " : "continuum ") << "y = " << s.height << " m: sigma_v "
              << s.measured << " Pa, weight above " << s.closed_form << " Pa, error " << s.relative_error() << "\n";
  std::cout << "  jump across the interface " << record.jump_across_band() << std::endl;
  ASSERT_GE(record.samples.size(), 8u);
  EXPECT_LT(record.largest_relative_error(), 1e-4);
  EXPECT_LT(std::abs(record.jump_across_band()), 1e-4);
}

TEST(GeostaticColumn, RefusesTheInterfaceCoupling)
{
  EXPECT_NE(invalid_argument_message([] { geostatic_column(InterfaceCoupling{}); }).find("method 3"),
            std::string::npos);
}
} // namespace
