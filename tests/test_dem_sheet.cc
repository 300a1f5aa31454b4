// The spar sheet (Chareyre & Villard 2005) in the DEM engine, on its own: axial elasticity against
// T L / J and the wave speed sqrt(J / rho_A), no force in compression, and the refusal of bad input.
// Its interface with the grains: test_dem_sheet_interface.cc; in a system of grains (energy,
// threads, checkpoint, snapshots): test_dem_sheet_system.cc.
#include "dem/dem_system.h"
#include "dem_sheet_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace geohybrid::dem;
using namespace geohybrid::testing::dem_sheet_scenes;

namespace
{
/// Sheet parameters for the tests without discs: a soft interface, so that the nodes' own
/// dynamics sets the stable step.
SheetParameters free_sheet(double J, double areal_mass)
{
  return sheet_parameters(J, areal_mass, contact_law(1.0e6, 25.6));
}

/// Runs `f` and returns the message of the std::invalid_argument it throws ("" if none).
template <typename F>
std::string invalid_argument_of(F &&f)
{
  try
    {
      f();
    }
  catch (const std::invalid_argument &e)
    {
      return e.what();
    }
  return "";
}

/// A system holding only sheets: one fixed disc far away (DemSystem needs a particle set). The
/// settings must give the time step: there is no movable particle to set it from.
DemSystem sheet_only_system(const DemSettings &settings)
{
  ParticleSet p;
  const std::size_t b = p.add_disc(Vec2(100.0, 100.0), 0.01, 1000.0);
  p.fix_body(b);
  return DemSystem(std::move(p), LinearContactLaw(contact_law(1e6, 0.0)), settings);
}
} // namespace

// ---- axial elasticity ------------------------------------------------------------------------------

// A 1 m sheet fixed at one end (a clamp at rest) and pulled at the other by a constant load F
// comes to rest with every segment at T = F, elongation F L / J, and the clamp's reaction -F.
// Damped dynamic relaxation (local damping 0.7, about 50 periods 4 L / c): the tolerance (1e-6
// relative) is far below any wrong constant.
TEST(SheetAxial, StaticElongationIsFLOverJ)
{
  const double J = 1.0e5, F = 1.0e3, L = 1.0;
  DemSettings settings;
  settings.gravity = Vec2::Zero();
  settings.local_damping = 0.7;
  settings.time_step = 3.0e-5;
  DemSystem system = sheet_only_system(settings);
  SparSheet sheet("sheet", straight_nodes(Vec2(0.0, 0.0), Vec2(L, 0.0), 20), free_sheet(J, 1.0));
  sheet.prescribe_velocity(0, Vec2::Zero());
  sheet.set_load(20, Vec2(F, 0.0));
  system.add_sheet(sheet);
  system.run_steps(25000);

  const SparSheet &s = system.sheets()[0];
  EXPECT_NEAR(s.x[20] - L, F * L / J, 1e-6 * F * L / J);
  for (std::size_t k = 0; k < s.n_segments(); ++k)
    EXPECT_NEAR(s.tension[k], F, 1e-6 * F) << k;
  EXPECT_NEAR(s.reaction(0).x(), -F, 1e-6 * F);
  EXPECT_NEAR(s.reaction(0).y(), 0.0, 1e-9 * F);
  EXPECT_NEAR(s.y[20], 0.0, 1e-12);
}

// The same sheet undamped under a load applied suddenly: a tension wave runs at c = sqrt(J / rho_A);
// in the continuum the free end moves linearly to 2 F L / J at t = 2 L / c and back to 0 at
// 4 L / c (the strain stays between 0 and 2 F / J, so tension-only changes nothing). The 50-segment
// chain disperses the front a little: measured +1.0 % on the peak time, -1.0 % on the peak and
// +0.6 % on the period (0.4 %, 0.4 %, 0.3 % with 200 segments); 2 % is asked.
TEST(SheetAxial, SuddenLoadWavePeriodAndOvershoot)
{
  const double J = 1.0e5, F = 1.0e3, L = 1.0, rho = 1.0;
  const double c = std::sqrt(J / rho), t_peak = 2.0 * L / c;
  DemSettings settings;
  settings.gravity = Vec2::Zero();
  settings.local_damping = 0.0;
  settings.time_step = 2.0e-5;
  DemSystem system = sheet_only_system(settings);
  const std::size_t n = 50;
  SparSheet sheet("sheet", straight_nodes(Vec2(0.0, 0.0), Vec2(L, 0.0), n), free_sheet(J, rho));
  sheet.prescribe_velocity(0, Vec2::Zero());
  sheet.set_load(n, Vec2(F, 0.0));
  system.add_sheet(sheet);

  double u_max = 0.0, t_max = 0.0;
  while (system.time() < 1.5 * t_peak)
    {
      system.step();
      const double u = system.sheets()[0].x[n] - L;
      if (u > u_max)
        {
          u_max = u;
          t_max = system.time();
        }
    }
  double u_min = u_max, t_min = 0.0; // the return, one period after the start
  while (system.time() < 3.0 * t_peak)
    {
      system.step();
      const double u = system.sheets()[0].x[n] - L;
      if (u < u_min)
        {
          u_min = u;
          t_min = system.time();
        }
    }
  EXPECT_NEAR(t_max, t_peak, 0.02 * t_peak);
  EXPECT_NEAR(u_max, 2.0 * F * L / J, 0.02 * 2.0 * F * L / J);
  EXPECT_NEAR(t_min, 2.0 * t_peak, 0.02 * 2.0 * t_peak);
  EXPECT_LT(u_min, 0.02 * 2.0 * F * L / J);
}

// Tension only: a shortened segment carries nothing, a stretched one J (l - l0) / l0, and the
// elastic energy counts only the stretched one.
TEST(SheetAxial, NoForceInCompression)
{
  const double J = 2.0e5;
  SparSheet sheet("sheet", {Vec2(0.0, 0.0), Vec2(0.1, 0.0), Vec2(0.2, 0.0)},
                  sheet_parameters(J, 1.0, default_interface_parameters()));
  sheet.x[1] = 0.09;  // segment 0 shortened by 10 %
  sheet.x[2] = 0.201; // segment 1 stretched from 0.1 to 0.111
  sheet.start_forces(Vec2::Zero());
  sheet.add_axial_forces();
  EXPECT_EQ(sheet.tension[0], 0.0);
  const double T1 = J * (0.111 - 0.1) / 0.1;
  EXPECT_NEAR(sheet.tension[1], T1, 1e-9 * T1);
  EXPECT_EQ(sheet.fx[0], 0.0);
  EXPECT_NEAR(sheet.fx[1], T1, 1e-9 * T1);
  EXPECT_NEAR(sheet.fx[2], -T1, 1e-9 * T1);
  EXPECT_NEAR(sheet.elastic_energy(), 0.5 * J / 0.1 * 0.011 * 0.011, 1e-12);

  // In a system: a slack sheet (every segment shortened) without gravity stays at rest.
  DemSettings settings;
  settings.gravity = Vec2::Zero();
  settings.local_damping = 0.0;
  settings.time_step = 1.0e-5;
  DemSystem system = sheet_only_system(settings);
  SparSheet slack("slack", straight_nodes(Vec2(0.0, 0.0), Vec2(0.2, 0.0), 10), free_sheet(J, 1.0));
  for (std::size_t k = 0; k < slack.n_nodes(); ++k)
    slack.x[k] *= 0.9;
  system.add_sheet(slack);
  system.run_steps(100);
  for (std::size_t k = 0; k < slack.n_nodes(); ++k)
    {
      EXPECT_EQ(system.sheets()[0].vx[k], 0.0);
      EXPECT_EQ(system.sheets()[0].x[k], slack.x[k]);
    }
  EXPECT_EQ(system.energy().sheet_elastic, 0.0);
}

// ---- bad input -------------------------------------------------------------------------------------

TEST(SheetBadInput, RefusedNamingTheParameter)
{
  const std::vector<Vec2> nodes{Vec2(0.0, 0.0), Vec2(0.1, 0.0), Vec2(0.2, 0.0)};
  const auto message_for = [&](const SheetParameters &parameters, const std::vector<Vec2> &chain) {
    return invalid_argument_of([&] { SparSheet("geotextile", chain, parameters); });
  };
  SheetParameters good = free_sheet(1.0e5, 0.62);
  EXPECT_EQ(message_for(good, nodes), "");

  SheetParameters bad = good;
  bad.axial_stiffness = 0.0;
  std::string m = message_for(bad, nodes);
  EXPECT_NE(m.find("'axial stiffness J'"), std::string::npos) << m;
  EXPECT_NE(m.find("geotextile"), std::string::npos) << m;
  bad.axial_stiffness = -5.0;
  EXPECT_NE(message_for(bad, nodes).find("'axial stiffness J'"), std::string::npos);

  bad = good;
  bad.thickness = 0.0;
  m = message_for(bad, nodes);
  EXPECT_NE(m.find("'thickness'"), std::string::npos) << m;
  bad.thickness = -1e-3;
  EXPECT_NE(message_for(bad, nodes).find("'thickness'"), std::string::npos);

  bad = good;
  bad.areal_mass = 0.0;
  EXPECT_NE(message_for(bad, nodes).find("'areal mass'"), std::string::npos);
  bad = good;
  bad.mass_scaling = 0.5;
  EXPECT_NE(message_for(bad, nodes).find("'mass scaling'"), std::string::npos);
  bad = good;
  bad.interface.friction_angle_deg = 90.0;
  m = message_for(bad, nodes);
  EXPECT_NE(m.find("interface"), std::string::npos) << m;
  EXPECT_NE(m.find("'friction angle'"), std::string::npos) << m;

  m = message_for(good, {Vec2(0.0, 0.0)});
  EXPECT_NE(m.find("'nodes'"), std::string::npos) << m;
  EXPECT_NE(m.find("at least 2"), std::string::npos) << m;
  EXPECT_NE(message_for(good, {}).find("'nodes'"), std::string::npos);

  m = message_for(good, {Vec2(0.0, 0.0), Vec2(0.1, 0.0), Vec2(0.1, 0.0), Vec2(0.2, 0.0)});
  EXPECT_NE(m.find("'nodes'"), std::string::npos) << m;
  EXPECT_NE(m.find("segment 1"), std::string::npos) << m;
  EXPECT_NE(m.find("zero length"), std::string::npos) << m;

  // A time step chosen by the user that the sheet's nodes cannot follow is refused, pointing at
  // the mass scaling.
  DemSettings settings;
  settings.time_step = 1.0e-3;
  ParticleSet p;
  p.add_disc(Vec2(1.0, 1.0), 0.05, 2650.0); // stable up to 4.6e-3 s
  DemSystem system(std::move(p), LinearContactLaw(contact_law(1.0e6, 20.0)), settings);
  m = invalid_argument_of([&] { system.add_sheet(SparSheet("geotextile", nodes, good)); });
  EXPECT_NE(m.find("mass scaling"), std::string::npos) << m;
  EXPECT_NE(m.find("geotextile"), std::string::npos) << m;
  EXPECT_TRUE(system.sheets().empty()); // refused, and the system still runs
  system.run_steps(10);
  // With mass scaling the same sheet fits the step.
  SparSheet scaled("geotextile", nodes, good);
  scaled.set_mass_scaling(scaled.required_mass_scaling(1.0e-3 / 0.5, system.sheet_contact_stiffness() + 1.0e6));
  EXPECT_EQ(system.add_sheet(scaled), 0u);
  EXPECT_GE(system.critical_time_step(), 1.0e-3);
}
