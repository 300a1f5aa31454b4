// Closed-form checks of friction, gravity loading and bonds in (quasi-)static configurations:
// a disc rolling or slipping down an incline, a two-disc cluster sticking or sliding, the forces
// in a resting column of discs, and the tensile and shear failure of a bonded contact.
// Inclines are made by tilting gravity, g = 9.81 (sin a, -cos a), over a horizontal floor wall.
#include "dem/dem_system.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace geohybrid::dem;

namespace
{
constexpr double density = 2650.0, radius = 0.01, kn = 1.0e6, g = 9.81;

ContactParameters law(double friction_deg, double restitution = 1.0)
{
  ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = 0.5 * kn;
  c.friction_angle_deg = friction_deg;
  c.restitution = restitution;
  return c;
}

DemSettings incline_settings(double angle)
{
  DemSettings s;
  s.gravity = g * Vec2(std::sin(angle), -std::cos(angle));
  s.local_damping = 0.0;
  // dt = 0.2 sqrt(m / kn): 2 pi / 0.2 ~ 30 steps per period of the contact. The critical step
  // assumes a dense packing, 2 / sqrt(12 kn / m) = sqrt(m / kn) / sqrt(3) for a disc with
  // ks = kn / 2 (DemSystem::critical_time_step), so this is sqrt(3) x 0.2 of it.
  s.time_step_safety = 0.2 * std::sqrt(3.0);
  return s;
}

double deg(double d) { return degrees_to_radians(d); }

struct DiscOnIncline
{
  double acceleration;   ///< of the centre, from velocities after the start-up transient
  double angular_acceleration;
  double centre_travel;  ///< from t1 to t2
  double contact_travel; ///< displacement of the material point at the contact, t1 to t2
  double slip_acceleration; ///< d/dt of the contact-point velocity v + omega lever, t1 to t2
  double lever;          ///< r - overlap/2, the contact lever used by the code
  double mass, inertia;
  double friction_dissipated; ///< from t1 to t2
  double t1, t2;
};

/// A disc released at rest on the floor, at its static overlap so that no normal oscillation
/// starts; measured between t1 = 0.02 s and t2 = 0.3 s. The first ~5 steps, while the tangential
/// spring builds up from zero, are a transient that shifts velocities by a constant: only rates
/// and travels between t1 and t2 are compared with the closed forms.
DiscOnIncline roll_disc(double angle, double friction_deg)
{
  ParticleSet p;
  const double m = density * pi * radius * radius;
  const double overlap = m * g * std::cos(angle) / kn;
  p.add_disc(Vec2(0.0, radius - overlap), radius, density);
  DemSystem system(p, LinearContactLaw(law(friction_deg)), incline_settings(angle));
  system.add_wall(Wall("floor", Vec2(-1.0, 0.0), Vec2(1.0, 0.0), LinearContactLaw(law(friction_deg))));
  const ParticleSet &q = system.particles();
  DiscOnIncline r{};
  const auto steps_to = [&](double t) { return static_cast<std::uint64_t>(t / system.time_step()); };
  system.run_steps(steps_to(0.02));
  r.t1 = system.time();
  const double x1 = q.x[0], v1 = q.vx[0], w1 = q.omega[0], rot1 = q.rotation[0];
  const double friction1 = system.energy().friction_dissipated;
  system.run_steps(steps_to(0.3) - system.step_count());
  r.t2 = system.time();
  r.lever = radius - 0.5 * (radius - q.y[0]);
  r.acceleration = (q.vx[0] - v1) / (r.t2 - r.t1);
  r.angular_acceleration = (q.omega[0] - w1) / (r.t2 - r.t1);
  r.centre_travel = q.x[0] - x1;
  // The point at the bottom of the disc moves by dx + omega x (0, -lever) integrated: dx + lever dtheta.
  r.contact_travel = r.centre_travel + r.lever * (q.rotation[0] - rot1);
  r.slip_acceleration = r.acceleration + r.angular_acceleration * r.lever;
  r.mass = q.mass[0];
  r.inertia = q.inertia[0];
  r.friction_dissipated = system.energy().friction_dissipated - friction1;
  return r;
}
} // namespace

// Rolling without slip (tan a < 3 mu): a = g sin a / (1 + I/(m r^2)) = (2/3) g sin a, alpha = -a/r.
// Here tan a = 0.27 and 3 mu = 0.8; even the start-up overshoot of the tangential spring (twice
// the static friction force m g sin a / 3) stays under mu N, so the slider never activates.
TEST(Incline, DiscRollsWithoutSlipping)
{
  const double a = deg(15.0), friction = 15.0;
  ASSERT_LT(std::tan(a), 3.0 * std::tan(deg(friction)));
  const DiscOnIncline r = roll_disc(a, friction);
  const double expected = 2.0 / 3.0 * g * std::sin(a);
  // The code's contact lever is r - overlap/2 (overlap/r = 8e-4), which changes the rolling
  // acceleration by 3e-4 relative; the tangential spring oscillation (amplitude ~1 um) adds 1e-5.
  EXPECT_NEAR(r.acceleration, expected, 1e-3 * expected);
  EXPECT_NEAR(r.angular_acceleration, -expected / radius, 1e-3 * expected / radius);
  // No slip: the contact point moves only by the elastic extension of the tangential spring,
  // at most 2 x (m g sin a / 3) / ks ~ 3 um, over a centre travel of ~9 cm; 1e-4 is 9 um.
  EXPECT_GT(r.centre_travel, 0.05);
  EXPECT_NEAR(r.contact_travel, 0.0, 1e-4 * r.centre_travel);
  // The slider never activated, so no energy went into slip: exactly zero, not approximately.
  EXPECT_EQ(r.friction_dissipated, 0.0);
}

// Slipping (tan a > 3 mu): Coulomb friction mu N opposes the slip, so a = g (sin a - mu cos a),
// and its torque mu N r spins the disc up, alpha = -mu m g cos a r / I (clockwise). The contact
// point keeps slipping at v_c = v + omega r growing as g (sin a - 3 mu cos a) t.
TEST(Incline, DiscSlipsWhenSteep)
{
  const double a = deg(45.0), friction = 15.0, mu = std::tan(deg(friction));
  ASSERT_GT(std::tan(a), 3.0 * mu);
  const DiscOnIncline r = roll_disc(a, friction);
  const double expected = g * (std::sin(a) - mu * std::cos(a));
  // Sliding friction is exactly mu N at every step, with N = m g cos a (released at its static
  // overlap, the disc has no normal motion), and the lever r - overlap/2 is the code's: the rates
  // are exact but for rounding accumulated over ~1500 steps (measured 1e-14), hence 1e-6.
  EXPECT_NEAR(r.acceleration, expected, 1e-6 * expected);
  const double expected_alpha = -mu * r.mass * g * std::cos(a) * r.lever / r.inertia;
  EXPECT_NEAR(r.angular_acceleration, expected_alpha, 1e-6 * std::abs(expected_alpha));
  // The contact point slips at a rate a + alpha lever = g (sin a - 3 mu cos a) (lever = r).
  const double slip_acceleration = expected + expected_alpha * r.lever;
  ASSERT_GT(slip_acceleration, 0.0);
  EXPECT_NEAR(r.slip_acceleration, slip_acceleration, 1e-6 * slip_acceleration);
  // Energy dissipated by the slider between t1 and t2 = mu N x (slip distance of the contact
  // point): the bookkeeping of friction_work against the measured kinematics. The spring stays
  // at mu N, so each step's slip work is mu N x the contact point's step: equal up to rounding
  // (measured 1e-15), hence 1e-9.
  EXPECT_GT(r.contact_travel, 0.02);
  const double expected_work = mu * r.mass * g * std::cos(a) * r.contact_travel;
  EXPECT_NEAR(r.friction_dissipated, expected_work, 1e-9 * expected_work);
}

namespace
{
struct ClusterOnIncline
{
  double total_travel;  ///< centre displacement along x from release to t2
  double late_travel;   ///< from t1 to t2
  double acceleration;  ///< from velocities at t1 and t2
  double rotation_change; ///< from t1 to t2
  double t1, t2;
};

/// A cluster (r_large 1 cm, r_small 0.7 cm, centres 1.2 cm apart) lying on both discs: its axis
/// is tilted so that both discs touch the floor, the small disc downhill. It is released with
/// zero overlap; a floor dashpot (e = 0.3) damps the normal settling within a few milliseconds
/// without acting on a steady slide. Measured from t1 = 0.05 s to t2 = 0.3 s.
ClusterOnIncline slide_cluster(double angle, double friction_deg)
{
  const double r_large = 0.01, r_small = 0.007, spacing = 0.012;
  const double axis = -std::asin((r_large - r_small) / spacing);
  const TwoDiscGeometry geometry = two_disc_geometry(r_large, r_small, spacing);
  const Vec2 large_centre(0.0, r_large);
  ParticleSet p;
  p.add_two_disc_cluster(large_centre + geometry.centroid_from_large * Vec2(std::cos(axis), std::sin(axis)),
                         r_large, r_small, spacing, axis, density);
  DemSystem system(p, LinearContactLaw(law(friction_deg)), incline_settings(angle));
  system.add_wall(Wall("floor", Vec2(-1.0, 0.0), Vec2(1.0, 0.0), LinearContactLaw(law(friction_deg, 0.3))));
  const ParticleSet &q = system.particles();
  const double x0 = q.x[0];
  const auto steps_to = [&](double t) { return static_cast<std::uint64_t>(t / system.time_step()); };
  system.run_steps(steps_to(0.05));
  EXPECT_EQ(system.n_touching_wall_contacts(), 2u); // lying on both discs
  ClusterOnIncline r{};
  r.t1 = system.time();
  const double x1 = q.x[0], v1 = q.vx[0], rot1 = q.rotation[0];
  system.run_steps(steps_to(0.3) - system.step_count());
  EXPECT_EQ(system.n_touching_wall_contacts(), 2u); // and still on both: no tipping
  r.t2 = system.time();
  r.total_travel = q.x[0] - x0;
  r.late_travel = q.x[0] - x1;
  r.acceleration = (q.vx[0] - v1) / (r.t2 - r.t1);
  r.rotation_change = q.rotation[0] - rot1;
  return r;
}
} // namespace

// tan a = 0.9 mu: the cluster sticks. While the normal forces build up from zero in the first
// millisecond the contacts slip a little (measured 1.2e-5 m); afterwards the body is at rest,
// only the springs' elastic extension m g sin a / (2 ks) ~ 4 um being possible.
TEST(Incline, ClusterSticksBelowFrictionAngle)
{
  const double friction = 20.0, mu = std::tan(deg(friction)), a = std::atan(0.9 * mu);
  const ClusterOnIncline r = slide_cluster(a, friction);
  // Reference: the distance a frictionless slide would cover, 0.5 g sin a t^2 = 0.14 m. Sticking
  // means three orders of magnitude less in total...
  const double free_travel = 0.5 * g * std::sin(a) * r.t2 * r.t2;
  EXPECT_LT(std::abs(r.total_travel), 1e-3 * free_travel);
  // ...and, once settled, no motion beyond 1 um (1e-5 of the free slide over the same window).
  EXPECT_LT(std::abs(r.late_travel), 1e-6);
  EXPECT_LT(std::abs(r.acceleration), 1e-5 * g);
}

// tan a = 1.5 mu: the cluster slides without rotating. Both contacts are at the Coulomb limit, so
// the total friction is mu (N1 + N2) = mu m g cos a whatever the split of N between the discs:
// a = g (sin a - mu cos a).
TEST(Incline, ClusterSlidesAboveFrictionAngle)
{
  const double friction = 20.0, mu = std::tan(deg(friction)), a = std::atan(1.5 * mu);
  const ClusterOnIncline r = slide_cluster(a, friction);
  const double expected = g * (std::sin(a) - mu * std::cos(a));
  // After the normal settling, friction is exactly mu N at both contacts. The dashpot (e = 0.3)
  // divides the normal oscillation by ~3 per period of ~1 ms, so by t1 = 50 ms its residue is
  // at the rounding level (measured 2e-10 relative): 1e-6.
  EXPECT_NEAR(r.acceleration, expected, 1e-6 * expected);
  // A sliding body on two contacts does not roll: rotation limited to the normal settling, a
  // change in overlap (~1e-5 m) over the base (~1 cm), so < 1e-3 rad.
  EXPECT_LT(std::abs(r.rotation_change), 1e-3);
}

// A vertical column of N equal discs on a floor, settled by local damping. Statics: the floor
// carries the whole weight, N m g, and the contact between the k-th and (k+1)-th disc from the
// top carries the weight of the k discs above it, k m g: linear in depth.
TEST(Column, ForcesEqualWeightAbove)
{
  constexpr int n = 10;
  ParticleSet p;
  for (int k = 0; k < n; ++k) // disc 0 at the bottom, touching its neighbours at zero overlap
    p.add_disc(Vec2(0.0, radius + 2.0 * radius * k), radius, density);
  DemSettings settings;
  settings.local_damping = 0.7;
  DemSystem system(p, LinearContactLaw(law(20.0)), settings);
  const std::size_t floor =
    system.add_wall(Wall("floor", Vec2(-0.1, 0.0), Vec2(0.1, 0.0), LinearContactLaw(law(20.0))));
  system.run_steps(3000); // ~1.4 s, some 35 periods of the column's slowest mode
  const ParticleSet &q = system.particles();
  const double weight = q.mass[0] * g;
  ASSERT_EQ(system.n_touching_pairs(), static_cast<std::size_t>(n - 1));

  // Local damping removes a fixed fraction of the energy each cycle, so the out-of-balance force
  // decays geometrically: after 35 slow periods it is at the rounding level (measured 1e-14 of
  // the weight); 1e-9 of the weight is tight yet safely above rounding.
  const Wall &w = system.walls()[floor];
  EXPECT_NEAR(w.normal_stress() * w.length(), n * weight, 1e-9 * n * weight);
  EXPECT_NEAR(w.force_from_particles.y(), -n * weight, 1e-9 * n * weight);
  EXPECT_NEAR(w.force_from_particles.x(), 0.0, 1e-12 * n * weight); // symmetry: exactly vertical

  // Pair forces, and the overlaps they imply from the positions (an independent reading).
  const PairContacts &c = system.pair_contacts();
  int checked = 0;
  for (std::size_t k = 0; k < c.size(); ++k)
    {
      if (!c.state[k].touching)
        continue;
      const std::uint32_t lower = std::min(c.disc_i[k], c.disc_j[k]);
      ASSERT_EQ(std::max(c.disc_i[k], c.disc_j[k]), lower + 1);
      const int above = n - 1 - static_cast<int>(lower); // discs resting on this contact
      EXPECT_NEAR(c.elastic_normal_force[k], above * weight, 1e-9 * n * weight) << "contact " << lower;
      const double overlap = 2.0 * radius - (q.y[lower + 1] - q.y[lower]);
      EXPECT_NEAR(kn * overlap, above * weight, 1e-9 * n * weight) << "contact " << lower;
      ++checked;
    }
  EXPECT_EQ(checked, n - 1);
  // The bottom disc's overlap with the floor carries all n weights.
  EXPECT_NEAR(kn * (radius - q.y[0]), n * weight, 1e-9 * n * weight);
}

namespace
{
constexpr double tensile_strength = 50.0, shear_strength = 30.0; // a_n, a_s [N/m]

// Bonds are installed once on the assembled pair (bond_touching_contacts, as PFC installs contact
// bonds), not on every contact that forms: with bond_new_contacts = true a contact that separates
// forgets its history and bonds again when it re-forms, which would hide the "stays broken" check.
ContactParameters bonded_law()
{
  ContactParameters c = law(20.0);
  c.tensile_strength = tensile_strength;
  c.shear_strength = shear_strength;
  c.bond_new_contacts = false;
  return c;
}

/// Disc 0 fixed at the origin, disc 1 a kinematic body (fixed, then moved at a prescribed
/// velocity) starting `overlap` into contact on its right. Both are immovable, so the critical
/// step is unbounded and a step is given: 1e-5 s, with speeds of 5 mm/s, moves 5e-8 m per step,
/// 1e-3 of the bond's breaking gap a_n / kn = 5e-5 m.
struct BondRig
{
  DemSystem system;
  static constexpr double dt = 1e-5, speed = 5e-3;

  explicit BondRig(double overlap) : system(make_particles(overlap), LinearContactLaw(bonded_law()), settings())
  {
    system.step(); // the contact forms...
    system.bond_touching_contacts(); // ...and is glued
    EXPECT_TRUE(system.pair_contacts().state.at(0).bonded);
  }
  static ParticleSet make_particles(double overlap)
  {
    ParticleSet p;
    p.add_disc(Vec2(0.0, 0.0), radius, density);
    p.add_disc(Vec2(2.0 * radius - overlap, 0.0), radius, density);
    p.fix_body(0);
    p.fix_body(1);
    return p;
  }
  static DemSettings settings()
  {
    DemSettings s;
    s.gravity = Vec2::Zero();
    s.time_step = dt;
    return s;
  }
  ParticleSet &p() { return system.particles(); }
  /// Gap between the discs from their positions (negative in overlap).
  double gap() { return std::hypot(p().x[1] - p().x[0], p().y[1] - p().y[0]) - 2.0 * radius; }
  void move(const Vec2 &velocity)
  {
    p().vx[1] = velocity.x();
    p().vy[1] = velocity.y();
  }
};
} // namespace

// Pulled apart, a bonded contact holds a tension kn x gap up to a_n, then breaks: the force drops
// to zero and stays zero, even after the discs are pushed back into contact and pulled again.
TEST(Bond, TensileFailure)
{
  // Initial overlap chosen so that no step lands exactly on the breaking gap: the gaps are
  // -1.23e-6 + k 5e-8 m, and 5e-5 m falls between two of them (k = 1024.6).
  BondRig rig(1.23e-6);
  const double kn_gap_tolerance = 1e-9 * tensile_strength; // same numbers, a few roundings apart
  rig.move(Vec2(BondRig::speed, 0.0));
  double max_tension = 0.0;
  bool broke = false;
  for (int k = 0; k < 2000 && !broke; ++k)
    {
      rig.system.step();
      // Force on the kinematic disc 1: the bond pulls it back, fx = kn x overlap = -kn x gap.
      const double fx = rig.p().fx[1];
      if (rig.system.n_broken_bonds() == 0)
        {
          EXPECT_NEAR(fx, -kn * rig.gap(), kn_gap_tolerance) << "step " << k;
          max_tension = std::max(max_tension, -fx);
        }
      else
        {
          broke = true;
          // Broken at the first gap beyond a_n / kn, within one step's increment of it.
          EXPECT_GT(kn * rig.gap(), tensile_strength);
          EXPECT_LT(kn * rig.gap(), tensile_strength + kn * BondRig::speed * BondRig::dt);
          EXPECT_EQ(fx, 0.0); // nothing left: no bond, no overlap
        }
    }
  ASSERT_TRUE(broke);
  // The tension reached the strength to within one step's increment kn v dt = 0.05 N/m (1e-3).
  EXPECT_LE(max_tension, tensile_strength);
  EXPECT_GT(max_tension, tensile_strength - kn * BondRig::speed * BondRig::dt);

  // Push back into contact (to an overlap of 2e-6 m): plain compression kn x overlap...
  rig.move(Vec2(-BondRig::speed, 0.0));
  double max_compression = 0.0;
  while (rig.gap() > -2e-6)
    {
      rig.system.step();
      EXPECT_NEAR(rig.p().fx[1], -kn * std::min(rig.gap(), 0.0), kn_gap_tolerance);
      max_compression = std::max(max_compression, rig.p().fx[1]);
    }
  EXPECT_GT(max_compression, 0.0);
  // ...then pull again to twice the breaking gap: no tension at any step (fx never negative),
  // since a broken bond does not heal.
  rig.move(Vec2(BondRig::speed, 0.0));
  double min_fx = 0.0;
  while (rig.gap() < 2.0 * tensile_strength / kn)
    {
      rig.system.step();
      min_fx = std::min(min_fx, rig.p().fx[1]);
    }
  EXPECT_EQ(min_fx, 0.0);
  EXPECT_EQ(rig.system.n_broken_bonds(), 1u);
}

// Sheared at zero overlap, a bonded contact holds ks x (tangential displacement) up to a_s, then
// breaks; with no normal force nothing is left. Pressed to an overlap afterwards, the contact only
// carries friction: the shear force caps at mu kn overlap (3.6 N/m here, against a_s = 30 N/m).
TEST(Bond, ShearFailureLeavesFriction)
{
  BondRig rig(1e-6);
  const double ks = 0.5 * kn, mu = std::tan(deg(20.0));
  rig.p().x[1] = 2.0 * radius; // back to exactly touching, still bonded
  rig.system.step();
  ASSERT_NEAR(rig.gap(), 0.0, 1e-15);
  ASSERT_EQ(rig.system.n_broken_bonds(), 0u);

  // 4.9 mm/s: increments of ks v dt = 0.0245 N/m, so that no step lands exactly on a_s.
  const double shear_speed = 0.98 * BondRig::speed;
  rig.move(Vec2(0.0, shear_speed));
  const double y0 = rig.p().y[1];
  double max_shear = 0.0;
  bool broke = false;
  for (int k = 0; k < 2000 && !broke; ++k)
    {
      rig.system.step();
      // Force on disc 1 along y: the spring drags it back, fy = -ks u with u its displacement.
      // The contact normal turns by u / 2r (< 3e-3 rad), which shortens u along the tangent by a
      // relative u^2 / (8 r^2) < 1e-5, and the tension kn u^2 / 4r < 0.1 N/m adds no y component
      // beyond 3e-3 of itself: 1e-3 N/m covers both (3e-5 of a_s).
      const double fy = rig.p().fy[1], u = rig.p().y[1] - y0;
      if (rig.system.n_broken_bonds() == 0)
        {
          EXPECT_NEAR(fy, -ks * u, 1e-3) << "step " << k;
          max_shear = std::max(max_shear, -fy);
        }
      else
        {
          broke = true;
          EXPECT_GT(ks * u, shear_strength - 1e-3);
          EXPECT_LT(ks * u, shear_strength + ks * shear_speed * BondRig::dt + 1e-3);
          EXPECT_NEAR(fy, 0.0, 1e-3); // zero friction at zero normal force (only the tiny tension)
          // The spring's whole energy, 1/2 ks u^2 (~9e-4 J/m), is released at the break and booked
          // as dissipated (nothing else dissipated before: no slip, no dashpot). The geometric
          // shortening of u along the turning tangent (< 1e-5 relative) bounds the error: 1e-4.
          const double released = 0.5 * ks * u * u;
          EXPECT_NEAR(rig.system.energy().friction_dissipated, released, 1e-4 * released);
        }
    }
  ASSERT_TRUE(broke);
  EXPECT_EQ(rig.system.n_broken_bonds(), 1u);
  // Peak within one step's increment ks v dt = 0.0245 N/m below a_s (plus the geometric 1e-3).
  EXPECT_LE(max_shear, shear_strength + 1e-3);
  EXPECT_GT(max_shear, shear_strength - ks * shear_speed * BondRig::dt - 1e-3);

  // Press to an overlap of 1e-5 m (kn overlap = 10 N/m), then shear again.
  rig.move(Vec2(-BondRig::speed, 0.0));
  while (rig.gap() > -1e-5)
    rig.system.step();
  rig.move(Vec2(0.0, shear_speed));
  double max_ratio = 0.0;
  bool slipped = false;
  for (int k = 0; k < 400; ++k) // 2e-5 m of shear; sliding starts after mu kn overlap / ks = 7e-6 m
    {
      rig.system.step();
      const ContactState &s = rig.system.pair_contacts().state[0];
      const double normal = -kn * rig.gap(); // compression from the positions
      ASSERT_GT(normal, 0.0);
      // |Ft| <= mu Fn at every step, equality once sliding (rounding only: 1e-9 relative).
      max_ratio = std::max(max_ratio, std::abs(s.tangential_force) / (mu * normal));
      if (std::abs(s.tangential_force) > (1.0 - 1e-9) * mu * normal)
        slipped = true;
    }
  EXPECT_TRUE(slipped);
  EXPECT_NEAR(max_ratio, 1.0, 1e-9);
  EXPECT_EQ(rig.system.n_broken_bonds(), 1u);
}
