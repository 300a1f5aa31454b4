// Elastic and strength behaviour of DEM assemblies against closed forms, and the biaxial test.
#include "dem/laboratory/biaxial_test.h"
#include "dem/laboratory/sample_preparation.h"
#include "dem/measurements.h"

#include <gtest/gtest.h>

#include <functional>

using namespace geohybrid::dem;

// A regular hexagonal packing of equal discs has the isotropic 2D stiffness (per unit thickness)
//   E = 2 sqrt(3) kn (kn + ks) / (3 kn + ks),   nu = (kn - ks) / (3 kn + ks).
// Under a pure strain the affine field without particle rotation is the equilibrium (every disc
// is a centre of symmetry, and the six tangential moments cancel), so the lattice is strained by
// driving every disc kinematically with v = D x and the stress is read with Love-Weber inside.
TEST(HexagonalPacking, ElasticModuliMatchClosedForm)
{
  for (const double ratio : {0.0, 0.25, 0.5, 1.0})
    {
      const double kn = 1e8, ks = ratio * kn, r = 1e-3;
      ParticleSet p;
      const int nx = 20, ny = 20;
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          {
            const double x = 2.0 * r * i + (j % 2) * r, y = std::sqrt(3.0) * r * j;
            const std::size_t b = p.add_disc(Vec2(x, y), r, 2650.0);
            p.fix_body(b);
          }
      const double strain_rate = -1.0; // eps_yy rate [1/s]; eps_xx = 0
      for (std::size_t b = 0; b < p.n_bodies(); ++b)
        p.vy[b] = strain_rate * p.y[b];
      ContactParameters c;
      c.normal_stiffness = kn;
      c.shear_stiffness = ks;
      c.friction_angle_deg = 89.0;   // no slip
      c.tensile_strength = 1e9;      // the laterally stretched contacts hold tension
      c.shear_strength = 1e9;
      DemSettings settings;
      settings.gravity = Vec2::Zero();
      settings.local_damping = 0.0;
      settings.time_step = 1e-7;
      DemSystem system(p, LinearContactLaw(c), settings);
      system.bond_touching_contacts();
      const int n_steps = 1000; // eps_yy = -1e-4
      system.run_steps(n_steps);
      const double eps = strain_rate * n_steps * settings.time_step;
      const double height = std::sqrt(3.0) * r * (ny - 1);
      const Region inner{6 * r, 0.25 * height * (1 + eps), 2.0 * r * (nx - 4), 0.75 * height * (1 + eps)};
      const auto sigma = love_weber_stress(system, inner);
      // Love-Weber sums over the bodies inside; each disc of the lattice has the area
      // 2 sqrt(3) r^2 (its Voronoi cell), so normalise by cells, not by the region's area.
      std::size_t n_inside = 0;
      for (std::size_t b = 0; b < system.particles().n_bodies(); ++b)
        n_inside += inner.contains(system.particles().x[b], system.particles().y[b]);
      const double cell_area = 2.0 * std::sqrt(3.0) * r * r * (1.0 + eps);
      const double scale = inner.area() / (n_inside * cell_area);
      const double C11 = sigma[1] * scale / eps, C12 = sigma[0] * scale / eps;
      const double E = C11 - C12 * C12 / C11, nu = C12 / C11;
      const double E_expected = 2.0 * std::sqrt(3.0) * kn * (kn + ks) / (3.0 * kn + ks);
      const double nu_expected = (kn - ks) / (3.0 * kn + ks);
      EXPECT_NEAR(E, E_expected, 0.01 * E_expected) << "ks/kn = " << ratio;
      EXPECT_NEAR(nu, nu_expected, 0.01 * std::max(nu_expected, 0.05)) << "ks/kn = " << ratio;
    }
}

// Mohr-Coulomb fit: points on the line t = c cos(phi) + s sin(phi) give back phi and c.
TEST(MohrCoulomb, FitRecoversAngleAndCohesion)
{
  const double phi = 35.0 * pi / 180.0, c = 5e3;
  std::vector<double> s1, s3;
  for (double sigma_3 : {10e3, 20e3, 50e3})
    {
      // sigma_1 = sigma_3 Kp + 2 c sqrt(Kp), Kp = (1 + sin phi) / (1 - sin phi)
      const double Kp = (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
      s3.push_back(sigma_3);
      s1.push_back(sigma_3 * Kp + 2.0 * c * std::sqrt(Kp));
    }
  const auto [phi_deg, cohesion] = fit_mohr_coulomb(s1, s3);
  EXPECT_NEAR(phi_deg, 35.0, 1e-9);
  EXPECT_NEAR(cohesion, c, 1e-6);
  const auto [phi_one, c_one] = fit_mohr_coulomb({s1[0] - 2.0 * c * std::sqrt((1 + std::sin(phi)) / (1 - std::sin(phi)))}, {s3[0]});
  EXPECT_NEAR(phi_one, 35.0, 1e-9);
  EXPECT_EQ(c_one, 0.0);
}

// The continuum of the same soil: a plane-strain isotropic continuum (E, nu) in a biaxial test
// has E_2D = E / (1 - nu^2) and nu_2D = nu / (1 - nu); continuum_equivalent inverts that. On the
// hexagonal lattice above (nu_2D = (kn - ks) / (3 kn + ks)) it gives nu = (kn - ks) / (4 kn), the
// plane-strain ratio of apps/coupling_benchmarks/hexagonal_lattice.h, derived there from the lattice's Lame moduli.
TEST(Biaxial, ContinuumEquivalentIsThePlaneStrainSoilWithTheSameResponse)
{
  BiaxialParameters b;
  const double E = 20e6, nu = 0.3;
  b.young_modulus = E / (1.0 - nu * nu);
  b.poisson_ratio = nu / (1.0 - nu);
  b.peak_friction_angle_deg = 38.4;
  b.cohesion = 1e3;
  b.dilatancy_angle_deg = 10.0;
  ContinuumEquivalent c = continuum_equivalent(b);
  EXPECT_TRUE(c.invalid_reason.empty()) << c.invalid_reason;
  EXPECT_NEAR(c.young_modulus, E, 1e-9 * E);
  EXPECT_NEAR(c.poisson_ratio, nu, 1e-14);
  EXPECT_EQ(c.friction_angle_deg, 38.4);
  EXPECT_EQ(c.cohesion, 1e3);
  EXPECT_EQ(c.dilatancy_angle_deg, 10.0);

  for (const double ratio : {0.1, 0.5, 1.0})
    {
      const double kn = 7e7, ks = ratio * kn;
      b.poisson_ratio = (kn - ks) / (3.0 * kn + ks);
      EXPECT_NEAR(continuum_equivalent(b).poisson_ratio, (kn - ks) / (4.0 * kn), 1e-14) << ratio;
    }

  // A fit's negative cohesion or dilatancy, or a dilatancy above the friction angle, is bounded.
  b.cohesion = -50.0;
  b.dilatancy_angle_deg = -2.0;
  EXPECT_EQ(continuum_equivalent(b).cohesion, 0.0);
  EXPECT_EQ(continuum_equivalent(b).dilatancy_angle_deg, 0.0);
  b.dilatancy_angle_deg = 45.0;
  EXPECT_EQ(continuum_equivalent(b).dilatancy_angle_deg, 38.4);
  // A plane Poisson ratio of 1 or more has no plane-strain continuum (nu would reach 0.5).
  b.poisson_ratio = 1.2;
  c = continuum_equivalent(b);
  EXPECT_NE(c.invalid_reason.find("Poisson ratio"), std::string::npos) << c.invalid_reason;
}

namespace
{
RedfSpec tiny_sample(double friction_deg)
{
  RedfSpec s;
  s.n_particles = 250;
  s.width = 0.05;
  s.height = 0.1;
  s.target_porosity = 0.2;
  s.porosity_tolerance = 0.01;
  s.target_stress = 20e3;
  s.particle_contact.normal_stiffness = 7e7;
  s.particle_contact.shear_stiffness = 3.5e7;
  s.particle_contact.friction_angle_deg = friction_deg;
  s.wall_contact = s.particle_contact;
  s.wall_contact.friction_angle_deg = 0.0;
  s.initial_growth_friction_deg = 10.0;
  s.seed = 3;
  return s;
}

BiaxialCurve shear(const RedfSpec &spec)
{
  RedfSample sample = make_redf_sample(spec);
  BiaxialSpec test;
  test.confining_stress = spec.target_stress;
  test.final_axial_strain = 0.05;
  test.target_inertial_number = 5e-4;
  const double d = 2.0 * std::sqrt(total_solid_area(sample.system.particles()) / (pi * spec.n_particles));
  return run_biaxial_test(sample.system, sample.box, test, d, spec.density);
}
} // namespace

// On a small random sample the peak friction angle grows with the inter-particle friction, and
// the lateral servo holds sigma_0 within 2 % (after the first 0.5 % of strain, at I = 5e-4).
TEST(Biaxial, PeakFrictionGrowsWithContactFrictionAndServoHolds)
{
  double previous_phi = 0.0;
  for (const double delta : {2.0, 25.0})
    {
      const RedfSpec spec = tiny_sample(delta);
      const BiaxialCurve curve = shear(spec);
      double max_error = 0.0;
      for (const BiaxialPoint &p : curve.points)
        if (p.axial_strain > 0.005)
          max_error = std::max(max_error, std::abs(p.lateral_stress / spec.target_stress - 1.0));
      EXPECT_LT(max_error, 0.02) << "delta = " << delta;
      const double phi = analyse_biaxial_curves({curve}).peak_friction_angle_deg;
      EXPECT_GT(phi, previous_phi + 3.0) << "delta = " << delta;
      previous_phi = phi;
    }
}

// A sample made at 20 kPa and consolidated to 50 kPa holds 50 kPa on both wall pairs within the
// tolerance, in equilibrium; consolidating it again to the same stress takes no step.
TEST(Biaxial, ConsolidationReachesTheStress)
{
  RedfSpec small = tiny_sample(10.0);
  small.n_particles = 120; // the test needs an equilibrium, not a representative sample
  small.width = 0.03;
  small.height = 0.04;
  RedfSample sample = make_redf_sample(small);
  ConsolidationSpec spec;
  spec.stress = 50e3;
  const std::uint64_t steps = consolidate_isotropically(sample.system, sample.box, spec);
  EXPECT_GT(steps, 0u);
  EXPECT_NEAR(sample.box.horizontal_stress(sample.system), 50e3, 0.02 * 50e3);
  EXPECT_NEAR(sample.box.vertical_stress(sample.system), 50e3, 0.02 * 50e3);
  EXPECT_LT(unbalanced_force_ratio(sample.system), 1e-3);
  EXPECT_EQ(consolidate_isotropically(sample.system, sample.box, spec), 0u);
}

// A test whose system moves to another thread count mid-run (as a campaign gives a running test
// the thread of one that finished) records the same curve, bit for bit, as the straight run on
// one thread: 1 -> 2 threads during the speed ramp, 2 -> 1 and 1 -> 2 again later.
TEST(Biaxial, MovedToOtherThreadCountsMidRunIsBitForBitTheStraightRun)
{
  RedfSpec small = tiny_sample(10.0);
  small.n_particles = 120;
  small.width = 0.03;
  small.height = 0.04;
  const RedfSample sample = make_redf_sample(small);
  BiaxialSpec test;
  test.confining_stress = 30e3; // consolidated first: the move happens after that too
  test.final_axial_strain = 0.01;
  test.ramp_strain = 0.004;
  test.record_interval = 5e-4;
  test.target_inertial_number = 1e-3;
  const double d = 2.0 * std::sqrt(total_solid_area(sample.system.particles()) / (pi * small.n_particles));

  RedfSample straight = sample;
  const BiaxialCurve expected = run_biaxial_test(straight.system, straight.box, test, d, small.density);
  ASSERT_GT(expected.compression_steps, 2000u);
  EXPECT_EQ(expected.final_threads, 1);

  RedfSample moved = sample;
  std::uint64_t polls = 0;
  const std::function<int()> budget = [&] {
    ++polls;
    return polls < 300 ? 1 : polls < 1000 ? 2 : polls < 1500 ? 1 : 2;
  };
  const BiaxialCurve curve = run_biaxial_test(moved.system, moved.box, test, d, small.density, {}, budget);
  EXPECT_EQ(polls, curve.compression_steps);
  EXPECT_EQ(curve.final_threads, 2);
  EXPECT_EQ(moved.system.settings().n_threads, 2);
  EXPECT_EQ(curve.compression_steps, expected.compression_steps);
  ASSERT_EQ(curve.points.size(), expected.points.size());
  for (std::size_t k = 0; k < curve.points.size(); ++k)
    {
      EXPECT_EQ(curve.points[k].axial_strain, expected.points[k].axial_strain) << "point " << k;
      EXPECT_EQ(curve.points[k].lateral_strain, expected.points[k].lateral_strain) << "point " << k;
      EXPECT_EQ(curve.points[k].axial_stress, expected.points[k].axial_stress) << "point " << k;
      EXPECT_EQ(curve.points[k].lateral_stress, expected.points[k].lateral_stress) << "point " << k;
    }
  // The whole state too: positions and velocities of every body.
  const ParticleSet &a = straight.system.particles(), &b = moved.system.particles();
  ASSERT_EQ(a.n_bodies(), b.n_bodies());
  for (std::size_t i = 0; i < a.n_bodies(); ++i)
    {
      ASSERT_EQ(a.x[i], b.x[i]) << "body " << i;
      ASSERT_EQ(a.y[i], b.y[i]) << "body " << i;
      ASSERT_EQ(a.vx[i], b.vx[i]) << "body " << i;
      ASSERT_EQ(a.omega[i], b.omega[i]) << "body " << i;
    }
  EXPECT_THROW(move_to_threads(moved.system, 0), std::invalid_argument);
}

TEST(Biaxial, BadInputRefused)
{
  RedfSpec spec = tiny_sample(10.0);
  spec.target_porosity = 0.02; // no 2D assembly is that dense
  EXPECT_THROW(make_redf_sample(spec), std::invalid_argument);
  spec = tiny_sample(10.0);
  spec.n_particles = 1; // one particle scaled to fill 80 % of the box cannot be placed in it
  EXPECT_THROW(make_redf_sample(spec), std::invalid_argument);
  spec = tiny_sample(10.0);
  spec.target_porosity = 0.45; // looser than any frictional jam at this stress: stays loose
  try
    {
      make_redf_sample(spec);
      FAIL() << "an unreachable porosity was accepted";
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find("porosity"), std::string::npos) << e.what();
    }
  BiaxialSpec zero_speed;
  zero_speed.top_wall_speed = 0.0;
  zero_speed.target_inertial_number = 0.0;
  DemSystem empty(ParticleSet{}, LinearContactLaw{}, [] { DemSettings s; s.time_step = 1e-6; return s; }());
  RectangularBox box = RectangularBox::add_to(empty, 0, 0, 1, 1, LinearContactLaw{}, 0.1);
  EXPECT_THROW(run_biaxial_test(empty, box, zero_speed, 1e-3, 2650.0), std::invalid_argument);
  BiaxialSpec long_ramp;
  long_ramp.ramp_strain = long_ramp.final_axial_strain; // the test would end before reaching V
  EXPECT_THROW(run_biaxial_test(empty, box, long_ramp, 1e-3, 2650.0), std::invalid_argument);
}
