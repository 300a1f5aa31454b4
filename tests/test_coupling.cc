// The DEM-FEM coupling (issue 6): the overlap band and its energy weights, the branch weight of a
// contact, the particles located in the mesh, the closed-form moduli of a hexagonal lattice checked
// against a DEM run of the lattice; then the coupled stepper (penalty and Lagrange multipliers),
// the patch test and the energy balance.
#include "coupling/band_points.h"
#include "apps/coupling_benchmarks/hexagonal_lattice.h"
#include "coupling/overlap_band.h"
#include "dem/measurements.h"
#include "test_coupling_support.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// u(x) = a + G x.
class AffineField : public dealii::Function<2>
{
public:
  AffineField(const dealii::Tensor<1, 2> &a, const dealii::Tensor<2, 2> &G) : dealii::Function<2>(2), a_(a), G_(G) {}
  double value(const dealii::Point<2> &x, unsigned int c) const override { return a_[c] + G_[c][0] * x[0] + G_[c][1] * x[1]; }

private:
  dealii::Tensor<1, 2> a_;
  dealii::Tensor<2, 2> G_;
};

TEST(OverlapBand, WeightsShareTheEnergyLinearlyAcrossTheBand)
{
  // Band along y, 0.1 m wide, particle edge at x = 0.3, continuum on the right.
  const OverlapBand band(Vec2(0.3, 7.0), Vec2(2.0, 0.0), 0.1);
  EXPECT_DOUBLE_EQ(band.continuum_weight(Vec2(0.2, 0.0)), 0.0);
  EXPECT_DOUBLE_EQ(band.particle_weight(Vec2(0.2, 0.0)), 1.0);
  EXPECT_NEAR(band.continuum_weight(Vec2(0.325, -3.0)), 0.25, 1e-14);
  EXPECT_NEAR(band.particle_weight(Vec2(0.325, -3.0)), 0.75, 1e-14);
  EXPECT_DOUBLE_EQ(band.continuum_weight(Vec2(0.45, 1.0)), 1.0);
  EXPECT_TRUE(band.in_band(Vec2(0.35, 0.0)));
  EXPECT_FALSE(band.in_band(Vec2(0.3, 0.0)));
  EXPECT_FALSE(band.in_band(Vec2(0.4, 0.0)));
  for (double x = 0.25; x < 0.45; x += 0.013)
    EXPECT_NEAR(band.continuum_weight(Vec2(x, 0.0)) + band.particle_weight(Vec2(x, 0.0)), 1.0, 1e-15);
}

TEST(OverlapBand, BranchWeightIsTheExactMeanAlongTheBranch)
{
  const OverlapBand band(Vec2(0.0, 0.0), Vec2(0.6, 0.8), 0.05);
  // Reference: the composite midpoint rule with 2e6 pieces on the piecewise linear weight (exact
  // on every piece without a kink: error below 1e-12 from the two pieces holding the kinks).
  const auto numerical = [&](const Vec2 &a, const Vec2 &b) {
    const int n = 2000000;
    long double sum = 0.0; // 2e6 terms: a double sum would lose 1e-10 to round-off
    for (int k = 0; k < n; ++k)
      sum += band.particle_weight(a + (k + 0.5) / n * (b - a));
    return static_cast<double>(sum / n);
  };
  const Vec2 segments[][2] = {
    {Vec2(-0.02, 0.01), Vec2(0.03, 0.02)},  // from the particle region into the band
    {Vec2(0.01, 0.01), Vec2(0.04, 0.05)},   // across the continuum edge
    {Vec2(-0.05, -0.01), Vec2(0.1, 0.08)},  // across the whole band
    {Vec2(0.01, 0.02), Vec2(0.02, 0.01)},   // inside the band
    {Vec2(0.04, 0.03), Vec2(-0.04, 0.03)},  // reversed, both kinks
    {Vec2(0.01, 0.0), Vec2(0.01 + 0.8e-13, -0.6e-13)}, // almost along the band (no cancellation)
  };
  for (const auto &s : segments)
    EXPECT_NEAR(band.branch_particle_weight(s[0], s[1]), numerical(s[0], s[1]), 1e-11);
  // Symmetric in its ends; a point segment is the point's weight.
  EXPECT_DOUBLE_EQ(band.branch_particle_weight(segments[2][0], segments[2][1]),
                   band.branch_particle_weight(segments[2][1], segments[2][0]));
  EXPECT_DOUBLE_EQ(band.branch_particle_weight(Vec2(0.01, 0.02), Vec2(0.01, 0.02)),
                   band.particle_weight(Vec2(0.01, 0.02)));
}

TEST(OverlapBand, BadInputNamesTheParameter)
{
  EXPECT_NE(invalid_argument_message([] { OverlapBand(Vec2(0, 0), Vec2(1, 0), -0.1); }).find("band width"), std::string::npos);
  EXPECT_NE(invalid_argument_message([] { OverlapBand(Vec2(0, 0), Vec2(1, 0), 0.0); }).find("band width"), std::string::npos);
  EXPECT_NE(invalid_argument_message([] { OverlapBand(Vec2(0, 0), Vec2(0, 0), 0.1); }).find("band normal"), std::string::npos);
  EXPECT_NE(invalid_argument_message([] { hexagonal_lattice_moduli(-1.0, 1.0); }).find("normal stiffness"), std::string::npos);
  EXPECT_NE(invalid_argument_message([] { hexagonal_lattice_moduli(1.0, 6.0); }).find("shear stiffness"), std::string::npos);
}

TEST(HexagonalLattice, ClosedFormMatchesTheLiterature)
{
  // 2D Young modulus 2 sqrt(3) kn (kn + ks) / (3 kn + ks) and Poisson ratio (kn - ks) / (3 kn + ks)
  // (Griffiths & Mustoe 2001) from the Lame constants; the plane-strain pair gives them back.
  const double kn = 7e7, ks = 3.5e7;
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(kn, ks);
  const double lambda = m.lame_lambda, mu = m.shear_modulus;
  EXPECT_NEAR(4.0 * mu * (lambda + mu) / (lambda + 2.0 * mu), 2.0 * std::sqrt(3.0) * kn * (kn + ks) / (3 * kn + ks),
              1e-12 * kn);
  EXPECT_NEAR(lambda / (lambda + 2.0 * mu), (kn - ks) / (3 * kn + ks), 1e-14);
  const double E = m.young_modulus_plane_strain, nu = m.poisson_ratio_plane_strain;
  EXPECT_NEAR(nu, (kn - ks) / (4.0 * kn), 1e-15);
  EXPECT_NEAR(E * nu / ((1 + nu) * (1 - 2 * nu)), lambda, 1e-12 * kn);
  EXPECT_NEAR(E / (2 * (1 + nu)), mu, 1e-12 * kn);
}

TEST(HexagonalLattice, ModuliMatchADemRunOfTheLattice)
{
  // 14 x 14 discs (r = 5 mm) pre-compressed by an overlap of 1e-5 of the spacing, then strained
  // uniformly by eps (all discs moved affinely at constant velocity for 50 steps, so that the
  // incremental tangential springs load as they would in a slow test, without rotation). The
  // Love-Weber stress change over the 8 x 8 interior discs (a region of exactly 64 lattice cells)
  // must be lambda tr(eps) I + 2 mu eps. Deviations come from the prestress (force directions
  // turning by ~eps, relative 1e-5) and the region's area change: tolerance 1e-4 of |sigma|.
  // Measured: 1.4e-5 (printed).
  const double r = 0.005, d = 2.0 * r * (1.0 - 1e-5), kn = 1e8, ks = 0.5e8;
  dem::ParticleSet particles = hexagonal_lattice(14, 14, r, d, 2650.0);
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    particles.fix_body(b);
  dem::DemSystem system(std::move(particles), lattice_law(kn, ks), undamped_settings(1e-6));
  system.initialise_forces();
  const double h = d * std::sqrt(3.0) / 2.0;
  const dem::Region interior{2.75 * d, 2.5 * h, 10.75 * d, 10.5 * h};
  const auto sigma0 = dem::love_weber_stress(system, interior);

  const double eps[2][2] = {{1.0e-6, 0.4e-6}, {0.4e-6, -0.5e-6}};
  const unsigned int n_steps = 50;
  const double duration = n_steps * system.time_step();
  dem::ParticleSet &p = system.particles();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      p.vx[b] = (eps[0][0] * p.x[b] + eps[0][1] * p.y[b]) / duration;
      p.vy[b] = (eps[1][0] * p.x[b] + eps[1][1] * p.y[b]) / duration;
    }
  system.run_steps(n_steps);
  const auto sigma1 = dem::love_weber_stress(system, interior);

  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(kn, ks);
  const double trace = eps[0][0] + eps[1][1];
  const double expected[3] = {m.lame_lambda * trace + 2 * m.shear_modulus * eps[0][0],
                              m.lame_lambda * trace + 2 * m.shear_modulus * eps[1][1], 2 * m.shear_modulus * eps[0][1]};
  const double scale = std::hypot(expected[0], expected[1], expected[2]);
  double error = 0.0;
  for (int k = 0; k < 3; ++k)
    error = std::max(error, std::abs(sigma1[k] - sigma0[k] - expected[k]) / scale);
  std::cout << "lattice moduli: largest relative stress error " << error << std::endl;
  EXPECT_LT(error, 1e-4);
}

TEST(BandPoints, InterpolateALinearFieldExactlyAndRefusePointsOutsideTheMesh)
{
  for (unsigned int degree : {1u, 2u})
    {
      dealii::parallel::distributed::Triangulation<fem::dim> mesh(MPI_COMM_WORLD);
      dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {4, 3}, dealii::Point<2>(0, 0), dealii::Point<2>(0.4, 0.3));
      const fem::DisplacementSpace space(mesh, degree);
      BandPoints::Vector u(space.locally_owned_dofs(), space.locally_relevant_dofs(), MPI_COMM_WORLD);
      // u = a + G x, which Q1 and Q2 interpolate exactly.
      dealii::Vector<double> values(space.dof_handler().n_dofs());
      const dealii::Tensor<1, 2> a({1e-3, -2e-3});
      const dealii::Tensor<2, 2> G({{2e-3, -1e-3}, {3e-3, -4e-3}});
      dealii::VectorTools::interpolate(space.mapping(), space.dof_handler(), AffineField(a, G), values);
      for (unsigned int i = 0; i < values.size(); ++i)
        u[i] = values[i];
      u.update_ghost_values();
      const std::vector<Vec2> points = {Vec2(0.013, 0.29), Vec2(0.2, 0.15), Vec2(0.4, 0.0), Vec2(0.331, 0.07)};
      const BandPoints located(space, u, points);
      ASSERT_EQ(located.size(), points.size());
      for (std::size_t p = 0; p < points.size(); ++p)
        {
          const Vec2 value = located.interpolate(u, p);
          for (unsigned int c = 0; c < 2; ++c)
            EXPECT_NEAR(value[c], a[c] + G[c][0] * points[p].x() + G[c][1] * points[p].y(), 1e-15);
        }
      EXPECT_THROW(BandPoints(space, u, {Vec2(0.41, 0.1)}), std::invalid_argument);
    }
}
} // namespace
