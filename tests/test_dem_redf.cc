// REDF sample preparation (Chareyre & Villard 2005): the target porosity and the confining
// stress are met within tolerance; impossible targets are refused with a clear message.
#include "dem/laboratory/sample_preparation.h"
#include "dem/measurements.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace geohybrid::dem;

namespace
{
RedfSpec small_spec()
{
  RedfSpec s;
  s.n_particles = 300;
  s.width = 0.06;
  s.height = 0.1;
  s.shape = ParticleShape::two_disc_cluster;
  s.target_porosity = 0.2;
  s.target_stress = 20e3;
  s.particle_contact.normal_stiffness = 7e7;
  s.particle_contact.shear_stiffness = 3.5e7;
  s.particle_contact.friction_angle_deg = 10.0;
  s.wall_contact = s.particle_contact;
  s.wall_contact.friction_angle_deg = 0.0;
  s.n_threads = 1;
  return s;
}
} // namespace

TEST(Redf, ReachesTargetPorosityAndStress)
{
  const RedfSpec spec = small_spec();
  RedfSample sample = make_redf_sample(spec);
  // Porosity from the box and the solid area, independent of the REDF bookkeeping.
  const double porosity = 1.0 - total_solid_area(sample.system.particles()) / sample.box.area(sample.system);
  EXPECT_NEAR(porosity, spec.target_porosity, spec.porosity_tolerance);
  EXPECT_NEAR(sample.box.horizontal_stress(sample.system), spec.target_stress, 0.02 * spec.target_stress);
  EXPECT_NEAR(sample.box.vertical_stress(sample.system), spec.target_stress, 0.02 * spec.target_stress);
  // The Love-Weber stress inside agrees with the walls (both compressive: sign flip).
  const double w = sample.box.width(sample.system), h = sample.box.height(sample.system);
  const Region inner{0.0, 0.0, w, h};
  const auto stress = love_weber_stress(sample.system, Region{sample.system.walls()[sample.box.left].start.x(),
                                                              sample.system.walls()[sample.box.bottom].start.y(),
                                                              sample.system.walls()[sample.box.right].start.x(),
                                                              sample.system.walls()[sample.box.top].start.y()});
  (void)inner;
  EXPECT_NEAR(-stress[0], spec.target_stress, 0.05 * spec.target_stress);
  EXPECT_NEAR(-stress[1], spec.target_stress, 0.05 * spec.target_stress);
  std::cout << "REDF: porosity " << porosity << ", growth friction " << sample.result.growth_friction_deg
            << " deg, steps " << sample.result.n_steps << ", coordination " << coordination_number(sample.system)
            << '\n';
}

// ---- size distribution ----

TEST(SizeDistribution, BadInputRefused)
{
  using Class = SizeDistribution::SizeClass;
  EXPECT_THROW(SizeDistribution::uniform(0.0), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::uniform(1.5), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::fractions({}), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::fractions({{1.0, 0.6}, {0.5, 0.3}}), std::invalid_argument); // sums to 0.9
  EXPECT_THROW(SizeDistribution::fractions({{1.0, 0.6}, {-0.5, 0.4}}), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::fractions({{1.0, 1.0}, {0.5, 0.0}}), std::invalid_argument);
  EXPECT_THROW(SizeDistribution::fractions({{1.0, 0.5}, {1.0, 0.5}}), std::invalid_argument);
  try
    {
      SizeDistribution::fractions({Class{1.0, 0.7}, Class{0.5, 0.2}});
      FAIL() << "fractions summing to 0.9 were accepted";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("sum to 0.9"), std::string::npos) << e.what();
    }
  // A class too small to get one particle among few is refused, not silently dropped.
  UniformRandom random(1);
  EXPECT_THROW(SizeDistribution::fractions({{1.0, 0.999}, {0.1, 0.001}}).relative_sizes(3, random),
               std::invalid_argument);
}

// The counts of a fractions distribution: class i of size s_i and area fraction f_i gets
// N_i ~ n (f_i / s_i^2) / sum_j (f_j / s_j^2) particles, rounded so that sum N_i = n; each
// class's area share N_i s_i^2 / sum_j N_j s_j^2 is then f_i within two particles of the largest
// class (whole counts: each N_i is off its ideal value by less than one).
TEST(SizeDistribution, FractionsGiveTheirAreaShares)
{
  const SizeDistribution sizes = SizeDistribution::fractions({{0.5, 0.2}, {1.0, 0.5}, {0.7, 0.3}});
  ASSERT_EQ(sizes.classes().size(), 3u);
  EXPECT_EQ(sizes.classes().front().relative_size, 1.0); // sorted by decreasing size
  UniformRandom random(7);
  const std::size_t n = 1000;
  const std::vector<double> u = sizes.relative_sizes(n, random);
  ASSERT_EQ(u.size(), n);
  double total = 0.0;
  for (double x : u)
    total += x * x;
  for (const auto &c : sizes.classes())
    {
      double share = 0.0;
      for (double x : u)
        share += x == c.relative_size ? x * x : 0.0;
      EXPECT_NEAR(share / total, c.area_fraction, 2.0 / total) << "size " << c.relative_size;
    }
}

namespace
{
/// Share of the solid area of each size class in a sample: each body goes to the class whose
/// relative size is nearest its large-disc radius over the largest one.
std::vector<double> class_area_shares(const ParticleSet &p, const SizeDistribution &sizes)
{
  double r_max = 0.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    r_max = std::max(r_max, p.disc_radius[p.first_disc[b]]);
  const double s_max = sizes.classes().front().relative_size;
  std::vector<double> share(sizes.classes().size(), 0.0);
  double total = 0.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      const double relative = p.disc_radius[p.first_disc[b]] / r_max * s_max;
      std::size_t nearest = 0;
      for (std::size_t i = 1; i < share.size(); ++i)
        if (std::abs(sizes.classes()[i].relative_size - relative) <
            std::abs(sizes.classes()[nearest].relative_size - relative))
          nearest = i;
      share[nearest] += p.body_area(b);
      total += p.body_area(b);
    }
  for (double &s : share)
    s /= total;
  return share;
}
} // namespace

// A grading given as area fractions per size is reproduced in the sample (REDF grows all sizes
// by one factor, so the shares of the placement survive), and REDF still meets its porosity.
TEST(Redf, SizeFractionsReproducedAtTargetPorosity)
{
  RedfSpec spec = small_spec();
  spec.n_particles = 180;
  spec.width = 0.045;
  spec.height = 0.075;
  spec.size_distribution = SizeDistribution::fractions({{1.0, 0.5}, {0.7, 0.3}, {0.5, 0.2}});
  RedfSample sample = make_redf_sample(spec);
  const ParticleSet &p = sample.system.particles();
  const double solid = total_solid_area(p);
  EXPECT_NEAR(1.0 - solid / sample.box.area(sample.system), spec.target_porosity, spec.porosity_tolerance);
  // Tolerance: two particles of the largest class (see FractionsGiveTheirAreaShares).
  double largest = 0.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    largest = std::max(largest, p.body_area(b));
  const double tolerance = 2.0 * largest / solid;
  const std::vector<double> shares = class_area_shares(p, spec.size_distribution);
  for (std::size_t i = 0; i < shares.size(); ++i)
    EXPECT_NEAR(shares[i], spec.size_distribution.classes()[i].area_fraction, tolerance)
      << "size " << spec.size_distribution.classes()[i].relative_size;
  EXPECT_NEAR(sample.box.horizontal_stress(sample.system), spec.target_stress, 0.02 * spec.target_stress);
  EXPECT_NEAR(sample.box.vertical_stress(sample.system), spec.target_stress, 0.02 * spec.target_stress);
  std::cout << "REDF with size fractions: porosity " << sample.result.porosity << ", shares " << shares[0] << ' '
            << shares[1] << ' ' << shares[2] << " (tolerance " << tolerance << "), steps " << sample.result.n_steps
            << '\n';
}

// ---- wall polygons ----

// Uniform pressure p on every side of any convex polygon is the isotropic stress p; a rectangle
// with sigma_x on its sides and sigma_y on its ends has the mean stress (sigma_x + sigma_y) / 2.
TEST(WallPolygon, MeanStressOfUniformWallPressures)
{
  ParticleSet one;
  one.add_disc(Vec2(0.3, 0.2), 0.01, 2650.0);
  DemSystem system(one, LinearContactLaw(ContactParameters{}), DemSettings{});
  const std::vector<Vec2> pentagon = {Vec2(0.0, 0.0), Vec2(0.6, -0.1), Vec2(0.8, 0.4), Vec2(0.4, 0.7), Vec2(-0.1, 0.3)};
  const WallPolygon polygon = WallPolygon::add_to(system, pentagon, LinearContactLaw(ContactParameters{}), 0.05);
  EXPECT_NEAR(polygon.area(system), polygon_area(pentagon), 1e-12);
  const std::vector<Vec2> corners = polygon.vertices(system);
  for (std::size_t k = 0; k < corners.size(); ++k)
    EXPECT_NEAR((corners[k] - pentagon[k]).norm(), 0.0, 1e-12);
  const double p = 12.5e3;
  for (const std::size_t w : polygon.walls)
    {
      Wall &wall = system.walls()[w];
      wall.force_from_particles = -p * wall.stress_length() * wall.normal(); // pushed outward
    }
  EXPECT_NEAR(polygon.mean_stress(system), p, 1e-9 * p);
  EXPECT_NEAR(polygon.largest_relative_stress_error(system, p), 0.0, 1e-12);

  DemSystem box_system(one, LinearContactLaw(ContactParameters{}), DemSettings{});
  const WallPolygon box = WallPolygon::add_to(box_system, {Vec2(0.0, 0.0), Vec2(0.5, 0.0), Vec2(0.5, 0.3), Vec2(0.0, 0.3)},
                                              LinearContactLaw(ContactParameters{}), 0.05);
  const double sigma[4] = {30e3, 10e3, 30e3, 10e3}; // bottom, right, top, left
  for (std::size_t k = 0; k < 4; ++k)
    {
      Wall &wall = box_system.walls()[box.walls[k]];
      wall.force_from_particles = -sigma[k] * wall.stress_length() * wall.normal();
    }
  EXPECT_NEAR(box.mean_stress(box_system), 20e3, 1e-9 * 20e3);
}

TEST(WallPolygon, OnlyConvexCounterClockwisePolygons)
{
  const Vec2 a(0.0, 0.0), b(1.0, 0.0), c(1.0, 1.0), d(0.0, 1.0);
  EXPECT_NO_THROW(check_convex_polygon({a, b, c, d}));
  EXPECT_THROW(check_convex_polygon({a, d, c, b}), std::invalid_argument);             // clockwise
  EXPECT_THROW(check_convex_polygon({a, b, Vec2(0.5, 0.4), d}), std::invalid_argument); // dented
  EXPECT_THROW(check_convex_polygon({a, b}), std::invalid_argument);
  EXPECT_THROW(check_convex_polygon({a, b, b, c}), std::invalid_argument);
  EXPECT_THROW(check_convex_polygon({a, Vec2(0.5, 0.0), b, c, d}), std::invalid_argument); // straight
  // A pentagram turns left at every vertex but goes round twice.
  std::vector<Vec2> star;
  for (int k = 0; k < 5; ++k)
    star.emplace_back(std::cos(4.0 * pi * k / 5.0), std::sin(4.0 * pi * k / 5.0));
  EXPECT_THROW(check_convex_polygon(star), std::invalid_argument);
}

// REDF in a trapezoid of walls (two sides slanted at 70 degrees): the target porosity of the
// polygon, every wall at the target stress (each servo-controlled along its normal), and every
// particle inside.
TEST(Redf, TrapezoidReachesTargetPorosityAndStress)
{
  RedfSpec spec = small_spec();
  spec.n_particles = 150;
  const std::vector<Vec2> trapezoid = {Vec2(0.0, 0.0), Vec2(0.07, 0.0), Vec2(0.0518, 0.05), Vec2(0.0182, 0.05)};
  RedfPolygonSample sample = make_redf_sample_in_polygon(spec, trapezoid, {});
  const DemSystem &system = sample.system;
  const std::vector<Vec2> corners = sample.boundary.vertices(system);
  const double porosity = 1.0 - total_solid_area(system.particles()) / polygon_area(corners);
  EXPECT_NEAR(porosity, spec.target_porosity, spec.porosity_tolerance);
  EXPECT_NEAR(sample.boundary.mean_stress(system), spec.target_stress, 0.02 * spec.target_stress);
  for (const std::size_t w : sample.boundary.walls)
    EXPECT_NEAR(system.walls()[w].normal_stress(), spec.target_stress, 0.02 * spec.target_stress)
      << system.walls()[w].name;
  // Inside: each disc's centre at least its radius from every side's line, less the elastic
  // overlap (about 20 kPa x d / kn = 1e-6 m, far below 1 % of a radius).
  const ParticleSet &p = system.particles();
  double worst = 1.0;
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    for (std::size_t k = 0; k < corners.size(); ++k)
      {
        const Vec2 inward = perp(corners[(k + 1) % corners.size()] - corners[k]).normalized();
        worst = std::min(worst, inward.dot(Vec2(p.disc_x[d], p.disc_y[d]) - corners[k]) / p.disc_radius[d]);
      }
  EXPECT_GT(worst, 0.99);
  std::cout << "REDF in a trapezoid: porosity " << porosity << ", mean stress " << sample.boundary.mean_stress(system)
            << " Pa, growth friction " << sample.result.growth_friction_deg << " deg, steps "
            << sample.result.n_steps << '\n';
}
