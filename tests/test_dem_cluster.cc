// Mass properties of two-disc clusters: the closed forms of two_disc_geometry (sector minus
// triangle for the lens) against a brute-force integration over the union of the two discs, and
// the bookkeeping of ParticleSet::add_two_disc_cluster (mass, inertia, disc positions).
#include "dem/particles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace geohybrid::dem;

namespace
{
struct GridMoments
{
  double area = 0.0, centroid_x = 0.0, centroid_y = 0.0, polar_moment = 0.0;
};

/// Midpoint rule on an n x n grid over the bounding box of the union of a disc of radius r1 at
/// the origin and a disc of radius r2 at (d, 0). Independent of the segment formulas: a cell
/// counts if its centre lies in either disc.
GridMoments integrate_union(double r1, double r2, double d, int n = 2000)
{
  const double x0 = std::min(-r1, d - r2), x1 = std::max(r1, d + r2);
  const double y0 = -std::max(r1, r2), y1 = -y0;
  const double hx = (x1 - x0) / n, hy = (y1 - y0) / n, cell = hx * hy;
  // Accumulate the second moments about the large disc centre, then shift (parallel axis): the
  // sums stay well conditioned because the box is centred near the origin.
  double a = 0.0, sx = 0.0, sy = 0.0, j0 = 0.0;
  for (int iy = 0; iy < n; ++iy)
    {
      const double y = y0 + (iy + 0.5) * hy;
      double row_a = 0.0, row_sx = 0.0, row_xx = 0.0;
      for (int ix = 0; ix < n; ++ix)
        {
          const double x = x0 + (ix + 0.5) * hx;
          const bool in1 = x * x + y * y < r1 * r1;
          const bool in2 = (x - d) * (x - d) + y * y < r2 * r2;
          if (in1 || in2)
            {
              row_a += 1.0;
              row_sx += x;
              row_xx += x * x;
            }
        }
      a += row_a;
      sx += row_sx;
      sy += row_a * y;
      j0 += row_xx + row_a * y * y;
    }
  GridMoments m;
  m.area = a * cell;
  m.centroid_x = sx / a;
  m.centroid_y = sy / a;
  m.polar_moment = j0 * cell - m.area * (m.centroid_x * m.centroid_x + m.centroid_y * m.centroid_y);
  return m;
}

struct Case
{
  const char *name;
  double r_large, r_small, spacing;
};

// Disjoint, touching from outside, light and heavy overlap, equal radii, and the two cases where
// the chord of the lens lies beyond a disc centre (r_small > spacing, r_large > spacing), which
// exercise the segments with half-angle above 90 degrees.
const Case cases[] = {
  {"disjoint", 1.0, 0.6, 2.0},
  {"touching", 1.0, 0.6, 1.6},
  {"light overlap", 1.0, 0.6, 1.4},
  {"heavy overlap", 1.0, 0.6, 0.9},
  {"equal radii", 0.8, 0.8, 0.5},
  {"r_small > spacing", 1.0, 0.8, 0.5},
  {"r_large > spacing > r_small", 1.0, 0.3, 0.8},
  {"nearly internally tangent", 1.0, 0.5, 0.52},
};
} // namespace

// Area, centroid and polar moment against a 2000 x 2000 midpoint grid. The grid's error comes
// from the cells cut by the boundary: about (perimeter / h) cells of area h^2 with a random
// half-cell error that largely cancels, i.e. well under 1e-4 relative here (h = 1e-3 of the
// box); 1e-3 leaves a margin while any wrong term of the lens formulas (a lens of area >= 1 %
// of the union in all overlapping cases) shows up at the percent level.
TEST(TwoDiscGeometry, MatchesGridIntegration)
{
  for (const Case &c : cases)
    {
      const TwoDiscGeometry g = two_disc_geometry(c.r_large, c.r_small, c.spacing);
      const GridMoments m = integrate_union(c.r_large, c.r_small, c.spacing);
      EXPECT_NEAR(g.area, m.area, 1e-3 * m.area) << c.name;
      EXPECT_NEAR(g.centroid_from_large, m.centroid_x, 1e-3 * c.r_large) << c.name;
      EXPECT_NEAR(m.centroid_y, 0.0, 1e-3 * c.r_large) << c.name; // symmetry of the grid itself
      EXPECT_NEAR(g.polar_moment, m.polar_moment, 1e-3 * m.polar_moment) << c.name;
    }
}

// The disjoint and touching cases also have an exact closed form (two full discs), which pins the
// formulas to 1e-12 without the grid.
TEST(TwoDiscGeometry, DisjointDiscsExact)
{
  for (double d : {1.6, 2.0, 5.0})
    {
      const double r1 = 1.0, r2 = 0.6;
      const double a1 = pi * r1 * r1, a2 = pi * r2 * r2, area = a1 + a2;
      const double xc = a2 * d / area;
      const double j = 0.5 * a1 * r1 * r1 + a1 * xc * xc + 0.5 * a2 * r2 * r2 + a2 * (d - xc) * (d - xc);
      const TwoDiscGeometry g = two_disc_geometry(r1, r2, d);
      // Rounding only: a handful of operations on O(1) numbers.
      EXPECT_NEAR(g.area, area, 1e-12 * area) << "d = " << d;
      EXPECT_NEAR(g.centroid_from_large, xc, 1e-12 * d) << "d = " << d;
      EXPECT_NEAR(g.polar_moment, j, 1e-12 * j) << "d = " << d;
    }
}

// As the spacing tends to the internal tangency r_large - r_small, the union tends to the large
// disc alone (continuity of the formulas where the lens becomes the whole small disc).
TEST(TwoDiscGeometry, TendsToLargeDiscAtInternalTangency)
{
  const double r1 = 1.0, r2 = 0.4, eps = 1e-7;
  const TwoDiscGeometry g = two_disc_geometry(r1, r2, r1 - r2 + eps);
  // The part of the small disc outside the large one has area O(eps^(3/2)) ~ 1e-10 and lever
  // O(1): 1e-8 bounds every deviation.
  EXPECT_NEAR(g.area, pi * r1 * r1, 1e-8);
  EXPECT_NEAR(g.centroid_from_large, 0.0, 1e-8);
  EXPECT_NEAR(g.polar_moment, 0.5 * pi * r1 * r1 * r1 * r1, 1e-8);
}

// add_two_disc_cluster: mass = density x area, inertia = density x polar moment, and the disc
// centres sit on a line through the centre of mass at the given angle, `spacing` apart, with the
// centre of mass at the grid centroid's distance from the large disc.
TEST(TwoDiscCluster, MassAndDiscPositions)
{
  const double density = 2650.0, r1 = 0.01, r2 = 0.007, d = 0.012, angle = 0.7;
  const Vec2 com(0.3, -0.2);
  ParticleSet p;
  p.add_disc(Vec2(5.0, 5.0), 0.01, density); // a body before, so indices are not trivially 0
  const std::size_t b = p.add_two_disc_cluster(com, r1, r2, d, angle, density, 42);
  ASSERT_EQ(p.n_bodies(), 2u);
  ASSERT_EQ(p.n_discs[b], 2u);
  EXPECT_EQ(p.body_id[b], 42);
  const std::uint32_t large = p.first_disc[b], small = large + 1;
  EXPECT_EQ(p.disc_body[large], b);
  EXPECT_EQ(p.disc_body[small], b);
  EXPECT_EQ(p.disc_radius[large], r1);
  EXPECT_EQ(p.disc_radius[small], r2);

  const GridMoments m = integrate_union(r1, r2, d);
  // Grid accuracy as in MatchesGridIntegration.
  EXPECT_NEAR(p.mass[b], density * m.area, 1e-3 * density * m.area);
  EXPECT_NEAR(p.inertia[b], density * m.polar_moment, 1e-3 * density * m.polar_moment);
  EXPECT_NEAR(p.body_area(b), m.area, 1e-3 * m.area);
  EXPECT_DOUBLE_EQ(p.inverse_mass[b], 1.0 / p.mass[b]);
  EXPECT_DOUBLE_EQ(p.inverse_inertia[b], 1.0 / p.inertia[b]);

  const auto check_positions = [&](double theta, const Vec2 &centre, const char *when) {
    const Vec2 axis(std::cos(theta), std::sin(theta));
    const Vec2 pl(p.disc_x[large], p.disc_y[large]), ps(p.disc_x[small], p.disc_y[small]);
    // Positions are O(0.3) m built from a few products: 1e-12 m is rounding.
    EXPECT_NEAR((ps - pl).norm(), d, 1e-12) << when;
    EXPECT_NEAR(cross(axis, ps - pl), 0.0, 1e-12) << when; // along the axis...
    EXPECT_GT(axis.dot(ps - pl), 0.0) << when;             // ...from large to small
    // Centre of mass on the axis, at the centroid distance from the large disc (grid tolerance).
    EXPECT_NEAR((centre - pl).dot(axis), m.centroid_x, 1e-3 * r1) << when;
    EXPECT_NEAR(cross(axis, centre - pl), 0.0, 1e-12) << when;
  };
  check_positions(angle, com, "after creation");

  // Move and rotate the body, then update: the discs follow rigidly.
  p.x[b] = -1.0;
  p.y[b] = 2.0;
  p.rotation[b] = angle + 2.0;
  p.update_disc_positions();
  check_positions(angle + 2.0, Vec2(-1.0, 2.0), "after rotation");

  // The untouched single disc stays where it is, at its body's centre.
  EXPECT_EQ(p.disc_x[0], 5.0);
  EXPECT_EQ(p.disc_y[0], 5.0);
}

// One disc inside the other (or internally tangent), a non-positive radius, a negative spacing or
// a non-positive density are refused.
TEST(TwoDiscCluster, InvalidInputThrows)
{
  EXPECT_THROW(two_disc_geometry(1.0, 0.3, 0.5), std::invalid_argument);  // inside
  EXPECT_THROW(two_disc_geometry(1.0, 0.5, 0.5), std::invalid_argument);  // internally tangent
  EXPECT_THROW(two_disc_geometry(1.0, 1.0, 0.0), std::invalid_argument);  // coincident
  EXPECT_THROW(two_disc_geometry(0.3, 1.0, 0.5), std::invalid_argument);  // inside, swapped radii
  EXPECT_THROW(two_disc_geometry(-1.0, 0.5, 1.0), std::invalid_argument); // negative radius
  EXPECT_THROW(two_disc_geometry(1.0, -0.5, 1.0), std::invalid_argument);
  EXPECT_THROW(two_disc_geometry(1.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(two_disc_geometry(1.0, 0.5, -1.0), std::invalid_argument); // negative spacing

  ParticleSet p;
  EXPECT_THROW(p.add_two_disc_cluster(Vec2::Zero(), 0.01, 0.003, 0.005, 0.0, 2650.0), std::invalid_argument);
  EXPECT_THROW(p.add_two_disc_cluster(Vec2::Zero(), -0.01, 0.003, 0.01, 0.0, 2650.0), std::invalid_argument);
  EXPECT_THROW(p.add_two_disc_cluster(Vec2::Zero(), 0.01, 0.007, 0.012, 0.0, 0.0), std::invalid_argument);
  EXPECT_EQ(p.n_bodies(), 0u); // nothing half-added
  EXPECT_EQ(p.n_discs_total(), 0u);
}
