// The DEM region as a convex polygon (issue 6: a polygon round the anchorage, the FE mesh over the
// rest of the tank): the band's weights round a polygon, the exact branch weight across a corner
// and the DEM's linear interpolation's error there, the tank's mesh with the core removed, and
// the patch test through a polygonal band.
#include "coupling/continuum_region.h"
#include "coupling/overlap_band.h"
#include "test_coupling_patch.h"

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <vector>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// The rectangle [x0, x1] x [y0, y1], counter-clockwise.
std::vector<Vec2> rectangle(double x0, double y0, double x1, double y1)
{
  return {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
}

/// The mean of the particle weight along [a, b] by the composite midpoint rule on 1e6 pieces: exact
/// on every piece without a kink, so its error (from the few pieces holding a kink) is below 1e-11.
double numerical_branch_weight(const OverlapBand &band, const Vec2 &a, const Vec2 &b)
{
  const int n = 1000000;
  long double sum = 0.0; // 1e6 terms: a double sum would lose 1e-10 to round-off
  for (int k = 0; k < n; ++k)
    sum += band.particle_weight(a + (k + 0.5) / n * (b - a));
  return static_cast<double>(sum / n);
}

/// The DEM's contact weight of the branch [a, b]: the pair loop's linear interpolation between the
/// two bodies' band coordinates (dem/energy_weights.h).
double dem_contact_weight(const OverlapBand &band, const Vec2 &a, const Vec2 &b)
{
  dem::EnergyWeights weights;
  weights.band_width = band.width();
  weights.body_band_coordinate.resize(2);
  weights.body_band_coordinate[0] = band.coordinate(a);
  weights.body_band_coordinate[1] = band.coordinate(b);
  return weights.contact_weight(0, 1);
}

TEST(RegionBand, WeightsRoundARectangularCore)
{
  // Core [0, 1] x [0, 0.5], band 0.1 m wide.
  const OverlapBand band = OverlapBand::around_convex_region(rectangle(0.0, 0.0, 1.0, 0.5), 0.1);
  EXPECT_DOUBLE_EQ(band.width(), 0.1);
  // Inside: s is minus the distance to the nearest side, the weight 0.
  EXPECT_NEAR(band.coordinate(Vec2(0.5, 0.2)), -0.2, 1e-15);
  EXPECT_DOUBLE_EQ(band.continuum_weight(Vec2(0.5, 0.2)), 0.0);
  EXPECT_DOUBLE_EQ(band.particle_weight(Vec2(0.5, 0.2)), 1.0);
  // Beside each side, at distance s: s / w.
  EXPECT_NEAR(band.continuum_weight(Vec2(1.03, 0.25)), 0.3, 1e-14);
  EXPECT_NEAR(band.continuum_weight(Vec2(0.4, -0.05)), 0.5, 1e-14);
  EXPECT_NEAR(band.continuum_weight(Vec2(-0.07, 0.1)), 0.7, 1e-14);
  EXPECT_NEAR(band.continuum_weight(Vec2(0.9, 0.52)), 0.2, 1e-14);
  EXPECT_NEAR(band.particle_weight(Vec2(0.9, 0.52)), 0.8, 1e-14);
  EXPECT_TRUE(band.in_band(Vec2(0.9, 0.52)));
  // On a side: 0, not in the band; past the band: 1.
  EXPECT_DOUBLE_EQ(band.continuum_weight(Vec2(1.0, 0.3)), 0.0);
  EXPECT_FALSE(band.in_band(Vec2(1.0, 0.3)));
  EXPECT_DOUBLE_EQ(band.continuum_weight(Vec2(1.2, 0.25)), 1.0);
  EXPECT_DOUBLE_EQ(band.continuum_weight(Vec2(0.5, 0.65)), 1.0);
  EXPECT_FALSE(band.in_band(Vec2(0.5, 0.65)));
  // Past a corner: the larger of the two sides' distances (a square corner of the band).
  EXPECT_NEAR(band.coordinate(Vec2(1.03, 0.54)), 0.04, 1e-15);
  EXPECT_NEAR(band.continuum_weight(Vec2(1.03, 0.54)), 0.4, 1e-14);
  EXPECT_NEAR(band.continuum_weight(Vec2(-0.06, -0.02)), 0.6, 1e-14);
  EXPECT_DOUBLE_EQ(band.continuum_weight(Vec2(1.11, 0.55)), 1.0);
}

TEST(RegionBand, WeightsRoundASlantedSide)
{
  // A triangle whose hypotenuse from (1, 0) to (0, 1) has the outward normal (1, 1) / sqrt(2).
  const OverlapBand band = OverlapBand::around_convex_region({Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, 0.2);
  const Vec2 normal = Vec2(1.0, 1.0) / std::sqrt(2.0), foot(0.6, 0.4); // foot: a point of the hypotenuse
  for (const double s : {-0.05, 0.0, 0.05, 0.13, 0.2, 0.3})
    {
      EXPECT_NEAR(band.coordinate(foot + s * normal), s, 1e-15);
      EXPECT_NEAR(band.continuum_weight(foot + s * normal), std::clamp(s / 0.2, 0.0, 1.0), 1e-14);
      EXPECT_NEAR(band.continuum_weight(foot + s * normal) + band.particle_weight(foot + s * normal), 1.0, 1e-15);
    }
}

TEST(RegionBand, BadRegionsNameTheParameter)
{
  const auto refusal = [](const std::vector<Vec2> &region, double width) {
    return invalid_argument_message([&] { OverlapBand::around_convex_region(region, width); });
  };
  const auto names = [](const std::string &message, const std::string &parameter) {
    return message.find(parameter) != std::string::npos;
  };
  EXPECT_TRUE(names(refusal({Vec2(0, 0), Vec2(1, 0)}, 0.1), "'DEM region'"));
  std::vector<Vec2> clockwise = rectangle(0, 0, 1, 1);
  std::reverse(clockwise.begin(), clockwise.end());
  EXPECT_TRUE(names(refusal(clockwise, 0.1), "'DEM region'"));
  EXPECT_TRUE(names(refusal(clockwise, 0.1), "counter-clockwise"));
  // An arrow head: counter-clockwise, one reflex vertex.
  EXPECT_TRUE(names(refusal({Vec2(0, 0), Vec2(1, 0.5), Vec2(0, 1), Vec2(0.3, 0.5)}, 0.1), "convex"));
  // A straight angle, a repeated vertex, a point not finite, a star that winds twice.
  EXPECT_TRUE(names(refusal({Vec2(0, 0), Vec2(0.5, 0), Vec2(1, 0), Vec2(0, 1)}, 0.1), "'DEM region'"));
  EXPECT_TRUE(names(refusal({Vec2(0, 0), Vec2(1, 0), Vec2(1, 0), Vec2(0, 1)}, 0.1), "'DEM region'"));
  EXPECT_TRUE(names(refusal({Vec2(0, 0), Vec2(1, 0), Vec2(std::nan(""), 1)}, 0.1), "'DEM region'"));
  std::vector<Vec2> pentagram;
  for (int k = 0; k < 5; ++k)
    pentagram.emplace_back(std::cos(4.0 * M_PI * k / 5.0), std::sin(4.0 * M_PI * k / 5.0));
  EXPECT_TRUE(names(refusal(pentagram, 0.1), "more than once"));
  // The width.
  EXPECT_TRUE(names(refusal(rectangle(0, 0, 1, 1), 0.0), "'band width'"));
  EXPECT_TRUE(names(refusal(rectangle(0, 0, 1, 1), -0.1), "'band width'"));
  EXPECT_TRUE(names(refusal(rectangle(0, 0, 1, 1), std::numeric_limits<double>::infinity()), "'band width'"));
  // A good one passes.
  EXPECT_EQ(refusal(rectangle(0, 0, 1, 1), 0.1), "no exception");
}

TEST(RegionBand, BranchWeightIsExactAcrossCorners)
{
  const OverlapBand band = OverlapBand::around_convex_region(rectangle(0.0, 0.0, 1.0, 0.5), 0.05);
  // An acute corner too: at (1, 0) of this triangle the sides' normals are (0, -1) and (0.6, 0.8).
  const OverlapBand acute = OverlapBand::around_convex_region({Vec2(-1, 0), Vec2(1, 0), Vec2(-0.2, 0.6)}, 0.05);
  const Vec2 segments[][2] = {
    {Vec2(0.97, 0.53), Vec2(1.03, 0.47)},   // across the corner's bisector, in the band
    {Vec2(0.98, 0.46), Vec2(1.06, 0.56)},   // from the core across the corner past the band
    {Vec2(1.02, 0.44), Vec2(0.96, 0.52)},   // from the right side's band to the top's
    {Vec2(0.9, 0.51), Vec2(1.08, 0.49)},    // along the top, round the corner, down the right side
    {Vec2(1.01, 0.49), Vec2(1.01 + 0.8e-13, 0.49 + 0.6e-13)}, // tiny
    {Vec2(-0.03, 0.52), Vec2(1.03, -0.04)}, // from one corner's band to the opposite one's
  };
  for (const auto &s : segments)
    {
      EXPECT_NEAR(band.branch_particle_weight(s[0], s[1]), numerical_branch_weight(band, s[0], s[1]), 1e-9);
      EXPECT_NEAR(band.branch_particle_weight(s[0], s[1]), band.branch_particle_weight(s[1], s[0]), 1e-15);
    }
  const Vec2 acute_segments[][2] = {
    {Vec2(0.98, 0.03), Vec2(1.04, -0.02)},
    {Vec2(0.95, -0.01), Vec2(1.06, 0.02)},
    {Vec2(1.0, 0.0), Vec2(1.03, 0.0)},
  };
  for (const auto &s : acute_segments)
    EXPECT_NEAR(acute.branch_particle_weight(s[0], s[1]), numerical_branch_weight(acute, s[0], s[1]), 1e-9);
  // A point: its own weight.
  EXPECT_DOUBLE_EQ(band.branch_particle_weight(Vec2(1.01, 0.52), Vec2(1.01, 0.52)), band.particle_weight(Vec2(1.01, 0.52)));
}

TEST(RegionBand, StraightBandBranchWeightIsTheFormerFormula)
{
  // The former formula, 1 - mean_continuum_share(s_a / w, s_b / w), bit for bit.
  const OverlapBand band(Vec2(0.0, 0.0), Vec2(0.6, 0.8), 0.05);
  const Vec2 segments[][2] = {
    {Vec2(-0.02, 0.01), Vec2(0.03, 0.02)}, {Vec2(0.01, 0.01), Vec2(0.04, 0.05)},
    {Vec2(-0.05, -0.01), Vec2(0.1, 0.08)}, {Vec2(0.04, 0.03), Vec2(-0.04, 0.03)},
  };
  for (const auto &s : segments)
    {
      const double former = 1.0 - dem::mean_continuum_share(band.coordinate(s[0]) / 0.05, band.coordinate(s[1]) / 0.05);
      EXPECT_EQ(band.branch_particle_weight(s[0], s[1]), former);
      EXPECT_EQ(dem_contact_weight(band, s[0], s[1]), former);
    }
}

TEST(RegionBand, DemInterpolationIsExactAwayFromCornersAndBoundedNearThem)
{
  // Core [0, 1] x [0, 0.5], band w = 0.04, branches of length L = 0.01 (a band of 4 branches).
  const double w = 0.04, L = 0.01;
  const OverlapBand band = OverlapBand::around_convex_region(rectangle(0.0, 0.0, 1.0, 0.5), w);
  // Which side is the largest at x (right: 0, top: 1; the test stays near the corner (1, 0.5)).
  const auto side_of = [](const Vec2 &x) { return x.x() - 1.0 >= x.y() - 0.5 ? 0 : 1; };
  const double bound = std::sqrt(2.0) * L / (8.0 * w); // |n_right - n_top| L / (8 w)
  double largest_error = 0.0, largest_error_one_side = 0.0;
  int n_one_side = 0, n_across = 0;
  for (double x = 1.0 - 2 * L; x <= 1.0 + w + 2 * L; x += 0.0013)
    for (double y = 0.5 - 2 * L; y <= 0.5 + w + 2 * L; y += 0.0011)
      for (int k = 0; k < 24; ++k)
        {
          const double angle = M_PI * k / 24.0;
          const Vec2 a(x, y), b = a + L * Vec2(std::cos(angle), std::sin(angle));
          const double exact = band.branch_particle_weight(a, b), dem = dem_contact_weight(band, a, b);
          // The chord lies above the convex s: the DEM's weight is never the larger.
          EXPECT_LE(dem, exact + 1e-15);
          const double error = exact - dem;
          const bool one_side = side_of(a) == side_of(b) || (band.coordinate(a) <= 0.0 && band.coordinate(b) <= 0.0);
          if (one_side)
            largest_error_one_side = std::max(largest_error_one_side, std::abs(error)), ++n_one_side;
          else
            largest_error = std::max(largest_error, error), ++n_across;
        }
  ASSERT_GT(n_one_side, 1000);
  ASSERT_GT(n_across, 1000);
  EXPECT_LT(largest_error_one_side, 1e-14);
  EXPECT_LE(largest_error, bound * (1.0 + 1e-9));
  EXPECT_GT(largest_error, 0.9 * bound); // the bound is sharp: a branch across the bisector in the band
  RecordProperty("largest_corner_error", std::to_string(largest_error));
  RecordProperty("corner_bound", std::to_string(bound));
  std::printf("DEM contact weight near a right-angled corner, L / w = %.2f: largest error %.6e, bound "
              "sqrt(2) L / (8 w) = %.6e\n", L / w, largest_error, bound);
}

TEST(ContinuumRegion, TankMeshWithTheCoreRemoved)
{
  // A 1.5 x 0.6 m tank in 24 x 12 cells (0.0625 x 0.05 m); the core x in [0.5, 1.6] (past the
  // right wall), y in [0.15, 0.3], on mesh lines: 16 x 3 cells removed.
  dealii::Triangulation<2> tank;
  dealii::GridGenerator::subdivided_hyper_rectangle(tank, {24, 12}, dealii::Point<2>(0.0, 0.0),
                                                    dealii::Point<2>(1.5, 0.6), true);
  const OverlapBand band = OverlapBand::around_convex_region(rectangle(0.5, 0.15, 1.6, 0.3), 0.1);
  const auto mesh = continuum_region_mesh(tank, band);
  EXPECT_EQ(mesh->n_active_cells(), 24u * 12u - 16u * 3u);
  EXPECT_NEAR(dealii::GridTools::volume(*mesh), 1.5 * 0.6 - 1.0 * 0.15, 1e-12);

  // The hole's faces: the bottom and top sides (16 faces each) and the left one (3); the right
  // side lies past the wall, whose faces keep the tank's id 1.
  unsigned int n_hole = 0, n_outer = 0;
  const double tol = 1e-12;
  for (const auto &cell : mesh->active_cell_iterators())
    {
      // Every cell carries some of the continuum's energy.
      double largest_weight = 0.0;
      for (const unsigned int v : cell->vertex_indices())
        largest_weight = std::max(largest_weight, band.continuum_weight(Vec2(cell->vertex(v)[0], cell->vertex(v)[1])));
      EXPECT_GT(largest_weight, 0.0);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const dealii::Point<2> c = cell->face(f)->center();
            const bool on_hole = ((std::abs(c[1] - 0.15) < tol || std::abs(c[1] - 0.3) < tol) && c[0] > 0.5) ||
                                 (std::abs(c[0] - 0.5) < tol && c[1] > 0.15 && c[1] < 0.3);
            if (on_hole)
              {
                EXPECT_EQ(cell->face(f)->boundary_id(), dem_core_boundary_id);
                ++n_hole;
              }
            else
              {
                const unsigned int expected = std::abs(c[0]) < tol ? 0 : std::abs(c[0] - 1.5) < tol ? 1
                                              : std::abs(c[1]) < tol ? 2 : 3;
                EXPECT_EQ(cell->face(f)->boundary_id(), expected) << "face at " << c;
                ++n_outer;
              }
          }
    }
  EXPECT_EQ(n_hole, 16u + 16u + 3u);
  EXPECT_EQ(n_outer, 2u * 24u + 2u * 12u - 3u);

  // The continuum on it takes the region's weight (no massless node).
  PatchGeometry g;
  fem::ExplicitSolver continuum(*mesh, matching_soil(g), fem::BoundaryConditions{}, patch_continuum_settings(g));
  EXPECT_NO_THROW(continuum.set_energy_weight(
    [&band](const dealii::Point<2> &x) { return band.continuum_weight(Vec2(x[0], x[1])); }));
  EXPECT_GT(continuum.stable_time_step(), 0.0);
}

TEST(ContinuumRegion, RefusesACoreOverTheWholeTank)
{
  dealii::Triangulation<2> tank;
  dealii::GridGenerator::subdivided_hyper_rectangle(tank, {4, 2}, dealii::Point<2>(0.0, 0.0), dealii::Point<2>(1.0, 0.5));
  const OverlapBand band = OverlapBand::around_convex_region(rectangle(-0.1, -0.1, 1.1, 0.6), 0.1);
  EXPECT_NE(invalid_argument_message([&] { continuum_region_mesh(tank, band); }).find("'DEM region'"), std::string::npos);
}

TEST(RegionBand, PatchTestThroughAPolygonMatchesTheStraightBand)
{
  // The patch's band (vertical, x = a) as the one active side of a rectangle far larger than the
  // patch: the same physics through the polygon's code path.
  const PlaneStrain strain{1.0e-7, -0.4e-7, 0.3e-7};
  const PatchGeometry g;
  const double a = g.band_start * g.spacing();
  const OverlapBand polygon = OverlapBand::around_convex_region(rectangle(-10.0, -10.0, a, 10.0), g.band_width * g.spacing());
  const PatchTestResult straight = patch_test(LagrangeMultiplierCoupling{}, strain, g);
  const PatchTestResult through_polygon = patch_test(LagrangeMultiplierCoupling{}, strain, g, polygon);
  EXPECT_EQ(through_polygon.n_particles, straight.n_particles);
  EXPECT_NEAR(through_polygon.ghost.continuum_nodes, straight.ghost.continuum_nodes, 1e-12);
  EXPECT_NEAR(through_polygon.ghost.particles_outside_band, straight.ghost.particles_outside_band, 1e-12);
  EXPECT_NEAR(through_polygon.ghost.largest(), straight.ghost.largest(), 1e-12);
  EXPECT_NEAR(straight.ghost.largest(), 1.86e-2, 0.05 * 1.86e-2); // coupling/README.md
  std::printf("patch test, ghost force: straight band %.17g, through the polygon %.17g\n", straight.ghost.largest(),
              through_polygon.ghost.largest());
}

/// The patch test across a horizontal side: the lattice's rows run along the band (the straight
/// patch's run across it). `columns` discs per row, rows up to one spacing past the band; the
/// continuum from the band's particle edge y = a up to `end`, as wide as the rows (each disc
/// carries one spacing of it), cells 2.4 x 2 spacings. The same measure as ghost_forces, its
/// layout turned: discs and nodes near the free sides and the far ends left out; a node's residual
/// over |sigma| times the cell's size across the band, as the straight patch's.
struct HorizontalPatch
{
  PatchGeometry g;
  unsigned int columns = 12, cells_x = 5, cells_y = 4;
  double a = 5.3, end = 13.3; ///< the band's particle edge and the mesh's top, in spacings
  /// The lattice's rows lie below this, one spacing past the band [spacings].
  double rows_end() const { return a + g.band_width + 1.0; }
};

struct HorizontalPatchResult
{
  GhostForces ghost;
  unsigned int n_discs_measured = 0, n_nodes_measured = 0, n_tied = 0, n_driven = 0;
};

HorizontalPatchResult horizontal_side_patch_test(const HorizontalPatch &layout, const PlaneStrain &eps)
{
  const PatchGeometry &g = layout.g;
  const double d = g.spacing(), h = g.row_height(), w = g.band_width * d;
  dem::ParticleSet discs;
  for (unsigned int j = 0; j * h < layout.rows_end() * d; ++j)
    for (unsigned int i = 0; i < layout.columns; ++i)
      discs.add_disc(Vec2(i * d + (j % 2) * 0.5 * d, j * h), g.radius, g.density, lattice_id(i, j));
  const auto particles = strained_lattice(std::move(discs), g, eps);

  const double x_left = -0.25 * d, x_right = (layout.columns - 0.25) * d;
  PatchMesh mesh(MPI_COMM_WORLD);
  dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {layout.cells_x, layout.cells_y},
                                                    dealii::Point<2>(x_left, layout.a * d),
                                                    dealii::Point<2>(x_right, layout.end * d), true);
  fem::ExplicitSolver continuum(mesh, matching_soil(g), fem::BoundaryConditions{}, patch_continuum_settings(g));
  strain_continuum(continuum, g, eps);
  // The band as the one active side of a rectangle far larger than the patch: normal (0, 1).
  const OverlapBand band = OverlapBand::around_convex_region(rectangle(-10.0, -10.0, 10.0, layout.a * d), w);
  const CoupledStepper stepper(*particles, continuum, band, LagrangeMultiplierCoupling{});

  const double cell_x = (x_right - x_left) / layout.cells_x, cell_y = (layout.end - layout.a) * d / layout.cells_y;
  const dem::ParticleSet &p = particles->particles();
  const BandParticles &tied = stepper.band_particles();
  // Away from the free sides and the lattice's free bottom (the band's discs are far from it).
  const auto interior_disc = [&](std::size_t b) {
    return !(p.x[b] < 1.0 * d || p.x[b] > (layout.columns - 2.0) * d) && p.y[b] > 1.2 * d;
  };
  const auto interior_node = [&](const dealii::Point<2> &x) {
    return !(x[0] < x_left + 1.5 * cell_x || x[0] > x_right - 1.5 * cell_x || x[1] > layout.end * d - 0.5 * cell_y);
  };
  const GhostForceMeasure measure =
    measure_ghost_forces(p, continuum, tied, stress_norm(g, eps), d, cell_y, interior_disc, interior_node);
  HorizontalPatchResult result;
  result.ghost = measure.ghost;
  result.n_discs_measured = static_cast<unsigned int>(measure.n_discs);
  result.n_nodes_measured = static_cast<unsigned int>(measure.n_nodes);
  result.n_tied = tied.size();
  result.n_driven = tied.driven_body.size();
  return result;
}

TEST(RegionBand, PatchTestAcrossAHorizontalSide)
{
  const PlaneStrain strain{1.0e-7, -0.4e-7, 0.3e-7};
  const HorizontalPatchResult result = horizontal_side_patch_test(HorizontalPatch{}, strain);
  const GhostForces &ghost = result.ghost;
  std::printf("patch test across a horizontal side (rows along the band): ghost force at the nodes %.3e (%u DoFs), "
              "on the untied discs %.3e (%u discs); %u tied, %u driven\n", ghost.continuum_nodes, result.n_nodes_measured,
              ghost.particles_outside_band, result.n_discs_measured, result.n_tied, result.n_driven);
  // 12 columns x 12 rows: the untied rows 2 to 4 (rows 0 and 1 at the free bottom, those within a
  // branch of the band tied) of 9 interior columns; the nodes of 2 interior columns on 4 rows.
  EXPECT_EQ(result.n_discs_measured, 27u);
  EXPECT_GE(result.n_nodes_measured, 8u);
  EXPECT_GT(result.n_driven, 0u);
  RecordProperty("ghost_force_continuum_nodes", std::to_string(ghost.continuum_nodes));
  EXPECT_LT(ghost.particles_outside_band, 1e-6); // round-off, as the straight patch's untied discs
  EXPECT_LT(ghost.continuum_nodes, 5e-2);
  EXPECT_GT(ghost.continuum_nodes, 1e-4); // the band's quadrature error (README), not round-off
}

// A driven grain whose centre stands a little above the continuum's free top (a grain at the fill's
// surface where a particle box reaches it: the largest tank's box at a 0.25 m margin stopped so,
// 0.3 mm above the mesh) is located by extrapolation, as a tied grain just outside the mesh is; a
// grain more than a branch (here two radii) outside is refused, naming its position.
TEST(RegionBand, DrivenGrainsJustAboveTheMeshTopAreLocated)
{
  HorizontalPatch layout;
  const PatchGeometry &g = layout.g;
  const double h = g.row_height() / g.spacing();
  unsigned int top_row = 0;
  while ((top_row + 1) * h < layout.rows_end())
    ++top_row;
  // The mesh's top a tenth of a radius below the top row's centres.
  layout.end = top_row * h - 0.1 * g.radius / g.spacing();
  const HorizontalPatchResult near = horizontal_side_patch_test(layout, PlaneStrain{1.0e-7, -0.4e-7, 0.3e-7});
  EXPECT_GE(near.n_driven, layout.columns); // the top row at least
  EXPECT_LT(near.ghost.particles_outside_band, 1e-6);
  // Three radii below them: the top row lies beyond the extrapolation.
  layout.end = top_row * h - 3.0 * g.radius / g.spacing();
  const std::string far =
    invalid_argument_message([&] { horizontal_side_patch_test(layout, PlaneStrain{1.0e-7, -0.4e-7, 0.3e-7}); });
  EXPECT_NE(far.find("lies outside the continuum's mesh"), std::string::npos) << far;
}
} // namespace
