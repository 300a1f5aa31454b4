// The sheet as one chain across both models (coupling/sheet_crossing.h, issue 6): a DEM spar
// sheet cut at a node (DemSystem::cut_sheet) and joined to a truss sheet embedded in a continuum.
// Closed form: a tension-only bar of total length L, its far end held, its head pulled by delta
// and held, with nothing else on it (a frictionless interface in an unstressed block), comes to
// rest with one tension T = J delta / L in every segment: the DEM's, the joining one and the
// continuum's.
#include "test_fem_support.h"

#include "coupling/sheet_crossing.h"
#include "dem/dem_system.h"
#include "fem/explicit_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace geohybrid;
using namespace geohybrid::fem::testing;

namespace
{
constexpr double spacing = 0.01, y_sheet = 0.1;

struct CrossingBar
{
  Mesh mesh{MPI_COMM_WORLD};
  std::unique_ptr<fem::ExplicitSolver> continuum;
  dem::CouplingAttachment attachment; ///< the crossing's hook, as the coupled stepper's: outlives the particles
  std::unique_ptr<dem::DemSystem> particles;
  std::unique_ptr<coupling::SheetCrossing> crossing;
  std::size_t n_dem_nodes_before_cut = 0;

  CrossingBar()
  {
    // The continuum: an unstressed elastic block 0.4 m x 0.2 m, held on its four sides; its sheet
    // from x = 0.05 m to 0.35 m, the far end clamped where it is.
    make_rectangle(mesh, 20, 10, Point<fem::dim>(0.0, 0.0), Point<fem::dim>(0.4, 0.2));
    fem::BoundaryConditions bc;
    for (const dealii::types::boundary_id id : {left, right, bottom, top})
      bc.displacements.push_back({id, true, true, nullptr});
    fem::ExplicitSettings settings;
    settings.density = 2000.0;
    settings.damping.local = 0.7;
    continuum = std::make_unique<fem::ExplicitSolver>(mesh, elastic_soil(20e6, 0.3), bc, settings);
    std::vector<Point<fem::dim>> fe_nodes;
    for (unsigned int k = 0; k <= 30; ++k)
      fe_nodes.emplace_back(0.05 + spacing * k, y_sheet);
    fem::TrussSheetParameters truss;
    truss.interface.friction_angle_deg = 0.0; // frictionless: nothing holds the bar but its ends
    truss.interface.cohesion = 0.0;
    const fem::EmbeddedSheet unscaled(continuum->space(), fem::TrussSheet(fe_nodes, truss), {});
    truss.mass_scaling = 8.0 * std::pow(continuum->time_step() / unscaled.stable_time_step(), 2);
    const std::size_t far_end = fe_nodes.size() - 1;
    continuum->attach_sheet(fem::TrussSheet(fe_nodes, truss),
                            {{far_end, [](double) { return dealii::Tensor<1, fem::dim>(); }}});

    // The particles: one fixed disc far away, no gravity; the DEM sheet laid from x = -0.2 m to
    // 0.2 m, then cut after x = 0.04 m (its tail lay where the continuum's sheet is).
    dem::ParticleSet discs;
    discs.add_disc(dem::Vec2(-1.0, -1.0), 0.005, 2000.0);
    discs.fix_body(0);
    dem::DemSettings dem_settings;
    dem_settings.gravity = dem::Vec2(0.0, 0.0);
    dem_settings.local_damping = 0.7;
    dem_settings.time_step = continuum->time_step(); // the sheet's mass scaling is chosen for it
    particles = std::make_unique<dem::DemSystem>(std::move(discs), dem::LinearContactLaw(dem::ContactParameters{}),
                                                 dem_settings);
    std::vector<dem::Vec2> dem_nodes;
    for (int k = -20; k <= 20; ++k)
      dem_nodes.emplace_back(spacing * k, y_sheet);
    n_dem_nodes_before_cut = dem_nodes.size();
    dem::SheetParameters sheet;
    sheet.mass_scaling = truss.mass_scaling;
    particles->add_sheet(dem::SparSheet("crossing bar", dem_nodes, sheet));
    particles->cut_sheet(0, 25); // nodes x = -0.20 ... 0.04 m
    const double dt = std::min(particles->time_step(), continuum->time_step());
    particles->set_time_step(dt);
    continuum->set_time_step(dt);
    particles->initialise_forces();
    crossing = std::make_unique<coupling::SheetCrossing>(particles->sheets()[0], 0, *continuum->sheet(), spacing);
    crossing->apply(particles->sheets()[0], *continuum->sheet());
    attachment.set_sheet_force_hook([this](std::vector<dem::SparSheet> &sheets) {
      crossing->apply(sheets[0], *continuum->sheet());
    });
    particles->attach(attachment);
  }
  /// As the coupled stepper: the continuum first, then the particles (whose sheet hook joins them).
  void step()
  {
    continuum->step();
    particles->step();
  }
};
} // namespace

TEST(SheetCrossing, CutSheetKeepsItsFirstNodes)
{
  CrossingBar bar;
  const dem::SparSheet &sheet = bar.particles->sheets()[0];
  EXPECT_EQ(bar.n_dem_nodes_before_cut, 41u);
  ASSERT_EQ(sheet.n_nodes(), 25u);
  EXPECT_EQ(sheet.n_segments(), 24u);
  EXPECT_NEAR(sheet.x[24], 0.04, 1e-12);
  // The last node keeps its mass: half of the dropped segment is the joining segment's.
  EXPECT_DOUBLE_EQ(sheet.gravitational_mass[24], sheet.gravitational_mass[23]);
  EXPECT_THROW(bar.particles->cut_sheet(0, 1), std::invalid_argument);
}

TEST(SheetCrossing, ABarAcrossBothModelsCarriesOneTension)
{
  CrossingBar bar;
  const double dt = bar.particles->time_step();
  const double J = bar.particles->sheets()[0].axial_stiffness();
  // The head pulled back (towards -x) by delta at 0.01 m/s, then held.
  const double delta = 1e-3, rate = 0.01;
  const auto pull_steps = static_cast<unsigned int>(std::lround(delta / rate / dt));
  bar.particles->sheets()[0].prescribe_velocity(0, dem::Vec2(-delta / (pull_steps * dt), 0.0));
  for (unsigned int n = 0; n < pull_steps; ++n)
    bar.step();
  bar.particles->sheets()[0].prescribe_velocity(0, dem::Vec2(0.0, 0.0));
  for (unsigned int n = 0; n < 20000; ++n)
    bar.step();

  const dem::SparSheet &dem_sheet = bar.particles->sheets()[0];
  const double pulled = -0.2 - dem_sheet.x[0]; // the head started at x = -0.2 m
  const double length = 0.24 + spacing + 0.30;
  const double expected = J * pulled / length;
  std::cout << "head moved " << pulled << " m; T = J delta / L = " << expected << " N/m; crossing "
            << bar.crossing->tension() << " N/m, head reaction " << -dem_sheet.reaction(0).x() << " N/m" << std::endl;
  EXPECT_NEAR(pulled, delta, 1e-9);
  // At rest to round-off (measured: every tension within 1e-11 of J delta / L).
  for (std::size_t s = 0; s < dem_sheet.n_segments(); ++s)
    EXPECT_NEAR(J * dem_sheet.segment_strain(s), expected, 1e-6 * expected) << "DEM segment " << s;
  EXPECT_NEAR(bar.crossing->tension(), expected, 1e-6 * expected);
  const std::vector<double> axial = bar.continuum->sheet()->axial_forces();
  for (std::size_t s = 0; s < axial.size(); ++s)
    EXPECT_NEAR(axial[s], expected, 1e-6 * expected) << "continuum segment " << s;
  EXPECT_NEAR(-dem_sheet.reaction(0).x(), expected, 1e-6 * expected);
  EXPECT_NEAR(bar.continuum->sheet()->clamp_force(0)[0], expected, 1e-6 * expected);
}

TEST(SheetCrossing, RefusesAJoiningSegmentMuchShorterThanItsNeighbours)
{
  CrossingBar bar;
  EXPECT_THROW(coupling::SheetCrossing(bar.particles->sheets()[0], 0, *bar.continuum->sheet(), 0.5 * spacing),
               std::invalid_argument);
}
