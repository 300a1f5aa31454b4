// System-level checks of DemSystem: the energy balance (conservative, dissipative, with a moving
// wall), the stress servo of a wall, bit-for-bit reproducibility across thread counts, and the
// refusal of bad input.
#include "dem/dem_system.h"
#include "dem/laboratory/sample_preparation.h"
#include "dem/measurements.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace geohybrid::dem;

namespace
{
constexpr double density = 2650.0, r_max = 0.005, kn = 1.0e6;

ContactParameters law(double friction_deg, double restitution)
{
  ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = 0.5 * kn;
  c.friction_angle_deg = friction_deg;
  c.restitution = restitution;
  return c;
}

/// nx x ny discs of radii uniform in [r_low, 1] r_max on a square grid of pitch `pitch` r_max
/// (> 2: no overlaps), with velocity components uniform in [-v, v]. Every `cluster_every`-th body
/// is a two-disc cluster instead (0: discs only). Deterministic: fixed seed.
ParticleSet grid_sample(int nx, int ny, double v, int cluster_every = 0, unsigned seed = 42,
                        double pitch = 2.5, double r_low = 0.7)
{
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> radius(r_low * r_max, r_max), velocity(-v, v),
    angle(-pi, pi);
  pitch *= r_max;
  ParticleSet p;
  int k = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i, ++k)
      {
        const Vec2 centre((i + 0.5) * pitch, (j + 0.5) * pitch);
        std::size_t b;
        if (cluster_every > 0 && k % cluster_every == 0) // within 0.82 r_max of its centre
          b = p.add_two_disc_cluster(centre, 0.6 * r_max, 0.54 * r_max, 0.5 * r_max, angle(generator), density);
        else
          b = p.add_disc(centre, radius(generator), density);
        p.vx[b] = velocity(generator);
        p.vy[b] = velocity(generator);
      }
  return p;
}

/// A closed box [0, width] x [0, height] of four walls whose active sides face inwards; returns
/// the index of the first (the floor; then right, roof, left).
std::size_t add_box(DemSystem &system, double width, double height, const LinearContactLaw &wall_law)
{
  const std::size_t floor = system.add_wall(Wall("floor", Vec2(0.0, 0.0), Vec2(width, 0.0), wall_law));
  system.add_wall(Wall("right", Vec2(width, 0.0), Vec2(width, height), wall_law));
  system.add_wall(Wall("roof", Vec2(width, height), Vec2(0.0, height), wall_law));
  system.add_wall(Wall("left", Vec2(0.0, height), Vec2(0.0, 0.0), wall_law));
  return floor;
}

/// Mechanical energy stored now: kinetic + gravitational (zero at y = 0, the floor) + elastic.
double stored(const EnergyBudget &e) { return e.kinetic + e.gravitational + e.elastic; }
double dissipated(const EnergyBudget &e)
{
  return e.friction_dissipated + e.viscous_dissipated + e.local_damping_dissipated;
}

constexpr int nx = 20, ny = 15; // 300 discs
constexpr double box_width = nx * 2.5 * r_max, box_height = 1.2 * ny * 2.5 * r_max;

/// The 300-disc box under gravity used by the energy tests.
/// `safety` is the step as a fraction of the single-disc contact estimate sqrt(m / kn), in which
/// the energy tests' errors were measured: for these discs (ks = kn / 2) the critical step is
/// 2 / sqrt(12 kn / m) = sqrt(m / kn) / sqrt(3) (DemSystem::critical_time_step).
constexpr double per_contact_estimate = 1.7320508075688772; // sqrt(3): critical -> sqrt(m / kn)

DemSystem box_system(double friction_deg, double restitution, double local_damping, double safety)
{
  DemSettings s;
  s.local_damping = local_damping;
  s.time_step_safety = safety * per_contact_estimate;
  const LinearContactLaw contact(law(friction_deg, restitution));
  DemSystem system(grid_sample(nx, ny, 0.5), contact, s);
  add_box(system, box_width, box_height, contact);
  return system;
}
} // namespace

// Frictionless, perfectly elastic, undamped: nothing dissipates, so kinetic + gravitational +
// elastic energy is conserved by the dynamics and only the integrator's error remains. Leapfrog's
// energy error is O(dt^2) per contact (measured: 8e-5 of E0 over 3000 steps at dt = 0.1 x the
// single-contact step sqrt(m / kn), 2e-5 at half the step over the same time); 1e-3 of E0 allows a factor of ~10.
TEST(EnergyBalance, ConservedWithoutDissipation)
{
  DemSystem system = box_system(0.0, 1.0, 0.0, 0.1);
  system.step();
  const EnergyBudget e0 = system.energy();
  const double scale = stored(e0);
  double max_error = 0.0;
  for (int k = 0; k < 3000; ++k)
    {
      system.step();
      max_error = std::max(max_error, std::abs(system.energy().total() - e0.total()));
    }
  const EnergyBudget e = system.energy();
  // Nothing may have been booked as dissipated: friction 0 means no slip work at all, e = 1 no
  // dashpot, alpha = 0 no damping. Exactly zero.
  EXPECT_EQ(e.friction_dissipated, 0.0);
  EXPECT_EQ(e.viscous_dissipated, 0.0);
  EXPECT_EQ(e.local_damping_dissipated, 0.0);
  EXPECT_EQ(e.boundary_work, 0.0);
  // Something happened: the discs fell (over 10 % of the potential energy released) and collide.
  EXPECT_GT(system.n_touching_pairs() + system.n_touching_wall_contacts(), 10u);
  EXPECT_LT(e.gravitational, 0.9 * e0.gravitational);
  EXPECT_LT(max_error, 1e-3 * scale);
}

// Friction (20 deg), dashpots (e = 0.5) and local damping (0.7): the stored energy falls, and
// what is lost is booked in the three dissipation terms so that total() stays constant. The
// balance error is O(dt^2) like the integrator's (measured 3.0e-4, 8.8e-5, 2.8e-5 of E0 at 0.2,
// 0.1, 0.05 x sqrt(m / kn) over the same time). 1e-3 of E0, tighter than the 1 % asked
// for, leaves a factor 10 and catches a 10 % error in the dashpot term (~3 % of E0; verified by
// mutation); the dissipated energy is ~35 % of E0.
TEST(EnergyBalance, ClosesWithDissipation)
{
  DemSystem system = box_system(20.0, 0.5, 0.7, 0.1);
  system.step();
  const EnergyBudget e0 = system.energy();
  const double scale = stored(e0);
  double max_error = 0.0;
  for (int k = 0; k < 6000; ++k)
    {
      system.step();
      max_error = std::max(max_error, std::abs(system.energy().total() - e0.total()));
    }
  const EnergyBudget e = system.energy();
  EXPECT_GT(e.friction_dissipated, 0.0);
  EXPECT_GT(e.viscous_dissipated, 0.0);
  EXPECT_GT(e.local_damping_dissipated, 0.0);
  EXPECT_EQ(e.boundary_work, 0.0); // fixed walls do no work
  EXPECT_GT(dissipated(e), 0.25 * scale);
  EXPECT_LT(max_error, 1e-3 * scale);
}

// The booking turned on during a run (a tank filled without it, then pulled with it): from there
// the balance closes as in a run booked from the start.
TEST(EnergyBalance, ClosesFromWhereTheTrackingIsTurnedOn)
{
  DemSystem system = box_system(20.0, 0.5, 0.7, 0.1);
  system.set_energy_tracking(false);
  for (int k = 0; k < 1000; ++k)
    system.step();
  EXPECT_EQ(dissipated(system.energy()), 0.0);
  system.set_energy_tracking(true);
  const EnergyBudget e0 = system.energy();
  const double scale = stored(e0);
  double max_error = 0.0;
  for (int k = 0; k < 5000; ++k)
    {
      system.step();
      max_error = std::max(max_error, std::abs(system.energy().total() - e0.total()));
    }
  EXPECT_GT(dissipated(system.energy()), 0.1 * scale);
  EXPECT_LT(max_error, 1e-3 * scale);
}

// Bonds (a_n = a_s = 30 N/m on every new contact) that break during the fall: the spring energy
// a breaking bond releases is booked as dissipated, so the balance closes as well as without
// bonds (measured 3.6e-5 of E0; before that booking, 1.5e-3 of E0 went missing, independent of
// dt). 3e-4 of E0 is the tolerance: a factor 8 above the measure, a factor 5 below the gap.
TEST(EnergyBalance, ClosesWithBondBreakage)
{
  DemSettings s;
  s.local_damping = 0.7;
  s.time_step_safety = 0.1;
  ContactParameters c = law(20.0, 0.5);
  c.tensile_strength = 30.0;
  c.shear_strength = 30.0;
  c.bond_new_contacts = true; // cementing: contacts bond as they form
  const LinearContactLaw contact(c);
  DemSystem system(grid_sample(nx, ny, 0.5), contact, s);
  add_box(system, box_width, box_height, contact);
  system.step();
  const EnergyBudget e0 = system.energy();
  double max_error = 0.0;
  for (int k = 0; k < 6000; ++k)
    {
      system.step();
      max_error = std::max(max_error, std::abs(system.energy().total() - e0.total()));
    }
  EXPECT_GT(system.n_broken_bonds(), 50u);
  EXPECT_LT(max_error, 3e-4 * stored(e0));
}

// One collision, closed form: the dashpot's booked work equals the kinetic energy the collision
// removed, 1/2 m v^2 - 1/2 m v'^2 (disc on a wall; and two equal discs head-on, m/2 reduced mass),
// for several restitution coefficients. Booked with the trapezoidal rule, the error is O(dt^2):
// measured below 1e-4 relative at 0.02 x the critical step (booking each step's dashpot force
// with the half-step rate alone gave +0.1 % to +0.9 % here, and +20 % to +40 % at the default
// 0.5). 5e-4 is the tolerance.
TEST(EnergyBalance, DashpotWorkEqualsLostKineticEnergy)
{
  for (double e : {0.9, 0.5, 0.2})
    for (bool against_wall : {true, false})
      {
        ParticleSet p;
        const double v = 1.0;
        p.add_disc(Vec2(0.0, r_max + 1e-5), r_max, density);
        p.vy[0] = -v;
        if (!against_wall)
          {
            p.add_disc(Vec2(0.0, -r_max - 1e-5), r_max, density);
            p.vy[1] = v;
          }
        DemSettings s;
        s.gravity = Vec2::Zero();
        s.local_damping = 0.0;
        s.time_step_safety = 0.02;
        DemSystem system(p, LinearContactLaw(law(20.0, e)), s);
        if (against_wall)
          system.add_wall(Wall("floor", Vec2(-1.0, 0.0), Vec2(1.0, 0.0), LinearContactLaw(law(20.0, e))));
        const double kinetic0 = system.energy().kinetic;
        const ParticleSet &q = system.particles();
        int steps = 0;
        while (!(q.y[0] > r_max + 1e-5 && q.vy[0] > 0.0) && steps < 100000) // until it flies off
          {
            system.step();
            ++steps;
          }
        ASSERT_LT(steps, 100000);
        const EnergyBudget b = system.energy();
        const double lost = kinetic0 - b.kinetic;
        EXPECT_GT(lost, 0.1 * (1.0 - e * e) * kinetic0) << "e = " << e; // it did dissipate
        EXPECT_NEAR(b.viscous_dissipated, lost, 5e-4 * lost) << "e = " << e << (against_wall ? " wall" : " pair");
        EXPECT_EQ(b.elastic, 0.0); // apart again
      }
}

namespace
{
struct PistonRun
{
  double max_error = 0.0, boundary_work = 0.0, scale = 0.0, dissipated = 0.0;
};

/// The box with its right wall moving inwards at `speed` for 0.096 s.
PistonRun run_piston(double friction_deg, double restitution, double local_damping, const Vec2 &gravity,
                     double safety, double speed)
{
  DemSettings s;
  s.gravity = gravity;
  s.local_damping = local_damping;
  s.time_step_safety = safety * per_contact_estimate; // as box_system
  const LinearContactLaw contact(law(friction_deg, restitution));
  DemSystem system(grid_sample(nx, ny, 0.5), contact, s);
  const std::size_t right = add_box(system, box_width, box_height, contact) + 1;
  system.walls()[right].velocity = Vec2(-speed, 0.0);
  system.step();
  const EnergyBudget e0 = system.energy();
  PistonRun r;
  r.scale = stored(e0);
  const int steps = static_cast<int>(std::lround(300.0 / safety));
  for (int k = 0; k < steps; ++k)
    {
      system.step();
      r.max_error = std::max(r.max_error, std::abs(system.energy().total() - e0.total()));
    }
  // The wall moved at its prescribed speed (positions of O(0.1) m: 1e-12 is rounding).
  EXPECT_NEAR(system.walls()[right].start.x(), box_width - speed * system.time(), 1e-12);
  r.boundary_work = system.energy().boundary_work - e0.boundary_work;
  r.dissipated = dissipated(system.energy());
  return r;
}
} // namespace

// A piston compressing a frictionless elastic gas of discs (no gravity): the wall's work goes into
// kinetic and elastic energy and is booked as boundary_work, so total() stays constant. The wall
// force is integrated by the trapezoidal rule, second order like the integrator: the balance
// error is O(dt^2) (measured 1.4e-3, 4.5e-4, 1.0e-4 of the energy scale at 0.2, 0.1, 0.05 x the
// single-contact step sqrt(m / kn), the same as without the piston). At 0.05, 1e-3 of the scale leaves a factor 10,
// while the boundary work is 13 % of the scale: an unbooked or mis-signed wall work would show.
TEST(EnergyBalance, MovingWallWorkEntersBalance)
{
  const PistonRun r = run_piston(0.0, 1.0, 0.0, Vec2::Zero(), 0.05, 0.1); // 9.6 mm of 250 mm
  EXPECT_GT(r.boundary_work, 0.05 * r.scale); // the piston heats the gas
  EXPECT_LT(r.max_error, 1e-3 * r.scale);
}

// The same with gravity, friction, dashpots and local damping, the piston pushing through the
// settling sample at 0.5 m/s: the balance error (measured 3e-4 of the energy scale) stays within
// 3e-3 of it, while the boundary work is larger than the whole scale.
TEST(EnergyBalance, MovingWallWithDissipation)
{
  const PistonRun r = run_piston(20.0, 0.5, 0.7, Vec2(0.0, -9.81), 0.1, 0.5); // 48 mm of 250 mm
  EXPECT_GT(r.dissipated, 0.1 * r.scale);
  EXPECT_GT(r.boundary_work, 1.0 * r.scale); // far above the tolerance: its booking matters
  EXPECT_LT(r.max_error, 3e-3 * r.scale);
}

// A roof wall servo-controlled to 10 kPa compresses 100 discs (gravity on, local damping 0.7)
// against the fixed floor. The discs start on a grid with random velocities, so that they
// collapse into a disordered packing (the stacked columns of a grid at rest are unstable and
// would buckle later, at an arbitrary time). Once settled (measured: by ~2700 steps) the roof's
// normal stress is the target; with frictionless walls the floor carries the roof's force plus
// the weight of the discs (vertical equilibrium). Then the right wall pushes in at 5 mm/s and the
// servo roof must retreat: PFC's servo then lags by v N kn dt / (alpha L) ~ 30 Pa at the roof's
// speed v ~ 1 mm/s (measured 41 Pa, 0.41 %). 2 % is the tolerance asked for. The walls have
// dashpots (e = 0.5), which the servo's gain counts (DemSystem::move_walls): without them in it
// and with dashpots that never pull (contact_law.h), the roof locked into a two-step cycle at its
// speed cap, its stress jumping between 5.0 and 14.3 kPa.
TEST(ServoWall, HoldsTargetStress)
{
  constexpr int n_side = 10;
  const double width = n_side * 2.5 * r_max, target = 1.0e4;
  DemSettings s;
  s.local_damping = 0.7;
  const LinearContactLaw contact(law(20.0, 0.5)), wall_law(law(0.0, 0.5));
  DemSystem system(grid_sample(n_side, n_side, 0.5), contact, s);
  const std::size_t floor = add_box(system, width, width, wall_law), right = floor + 1, roof = floor + 2;
  Wall &servo = system.walls()[roof];
  servo.control = WallControl::servo_stress;
  servo.servo.target_stress = target;
  servo.servo.max_speed = 0.2;
  double weight = 0.0;
  for (double m : system.particles().mass)
    weight += m * 9.81;

  system.run_steps(3500);
  double max_deviation = 0.0, max_equilibrium_error = 0.0;
  for (int k = 0; k < 500; ++k)
    {
      system.step();
      const Wall &top = system.walls()[roof], &bottom = system.walls()[floor];
      max_deviation = std::max(max_deviation, std::abs(top.normal_stress() - target));
      const double roof_force = top.normal_stress() * top.length();
      max_equilibrium_error =
        std::max(max_equilibrium_error, std::abs(bottom.normal_stress() * bottom.length() - roof_force - weight));
    }
  EXPECT_LT(max_deviation, 0.02 * target);
  EXPECT_LT(max_equilibrium_error, 0.02 * (target * width + weight));
  // The roof really compressed the sample: it came down to about half the box.
  const double settled_height = system.walls()[roof].start.y();
  EXPECT_LT(settled_height, 0.6 * width);
  EXPECT_GT(system.walls()[roof].n_contacts, 2u);

  system.walls()[right].velocity = Vec2(-5e-3, 0.0);
  max_deviation = 0.0;
  for (int k = 0; k < 2000; ++k)
    {
      system.step();
      max_deviation = std::max(max_deviation, std::abs(system.walls()[roof].normal_stress() - target));
    }
  std::cout << "servo lag while the side wall pushes: " << max_deviation << " Pa" << std::endl;
  EXPECT_LT(max_deviation, 0.02 * target);
  // Squeezed sideways by 1.6 mm, the sample pushed the roof up (by a fraction of a millimetre).
  EXPECT_GT(system.walls()[roof].start.y(), settled_height + 1e-4);
}

namespace
{
/// 3000 bodies (every tenth a two-disc cluster) in a box under gravity, with friction, dashpots,
/// local damping and weak bonds, so that every code path of a step is exercised, including bond
/// breakage. They start near contact (radii 0.92-1 r_max on a 2.05 r_max grid: every grid
/// neighbour within the Verlet skin), so that the pair list holds more than 4096 pairs from the
/// first step and the deterministic sums run over several blocks, in parallel.
DemSystem deposition(int n_threads, int cluster_every = 10, double local_damping = 0.7, bool track_energy = true)
{
  constexpr int n_x = 60, n_y = 50;
  constexpr double pitch = 2.05;
  DemSettings s;
  s.n_threads = n_threads;
  s.local_damping = local_damping;
  s.track_energy = track_energy;
  ContactParameters c = law(20.0, 0.5);
  c.tensile_strength = 2.0;
  c.shear_strength = 2.0;
  c.bond_new_contacts = true; // cementing: contacts bond as they form
  const LinearContactLaw contact(c);
  DemSystem system(grid_sample(n_x, n_y, 0.1, cluster_every, 7, pitch, 0.92), contact, s);
  add_box(system, n_x * pitch * r_max, n_y * pitch * r_max, LinearContactLaw(law(20.0, 0.5)));
  return system;
}

void expect_identical(const DemSystem &one, const DemSystem &two)
{
  const ParticleSet &a = one.particles(), &b = two.particles();
  ASSERT_EQ(a.n_bodies(), b.n_bodies());
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.rotation, b.rotation);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vy, b.vy);
  EXPECT_EQ(a.omega, b.omega);
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.torque, b.torque);
  EXPECT_EQ(a.disc_x, b.disc_x);
  EXPECT_EQ(a.disc_y, b.disc_y);
  const EnergyBudget ea = one.energy(), eb = two.energy();
  EXPECT_EQ(ea.kinetic, eb.kinetic);
  EXPECT_EQ(ea.gravitational, eb.gravitational);
  EXPECT_EQ(ea.elastic, eb.elastic);
  EXPECT_EQ(ea.friction_dissipated, eb.friction_dissipated);
  EXPECT_EQ(ea.viscous_dissipated, eb.viscous_dissipated);
  EXPECT_EQ(ea.local_damping_dissipated, eb.local_damping_dissipated);
  EXPECT_EQ(ea.boundary_work, eb.boundary_work);
  EXPECT_EQ(one.n_broken_bonds(), two.n_broken_bonds());
  EXPECT_EQ(one.n_neighbour_rebuilds(), two.n_neighbour_rebuilds());
  EXPECT_EQ(one.pair_contacts().disc_i, two.pair_contacts().disc_i);
  EXPECT_EQ(one.pair_contacts().disc_j, two.pair_contacts().disc_j);
}
} // namespace

// The same deposition on 1 and 2 threads gives the same numbers, bit for bit: every loop writes
// each value from one thread and every sum is taken in one fixed order (dem_system.h). Exact
// equality is the only meaningful tolerance here. Only 300 steps: on a loaded 2-core machine each
// of the ~8 parallel regions of a step of the 2-thread run can spin for a scheduler slice while
// its second thread waits for a core (libgomp's default active wait; measured here: 1 s with
// OMP_WAIT_POLICY=passive, 55 s without, for 1000 steps). A differing rounding anywhere cannot
// vanish in a colliding packing, so 300 steps with ~25 list rebuilds and many bond breaks suffice.
//
// Three threads too: the pair loop runs one chunk of pairs per thread, and the bodies shared by
// two chunks are completed afterwards (PairContacts); an odd number of chunks on two cores
// checks that this too sums in the one-thread order.
TEST(Threads, OneAndTwoThreadsBitForBit)
{
  DemSystem one = deposition(1), two = deposition(2), three = deposition(3);
  one.step();
  two.step();
  three.step();
  EXPECT_GT(one.pair_contacts().size(), 4096u); // several blocks in deterministic_sum
  EXPECT_GT(two.pair_contacts().shared_body.size(), 0u);
  EXPECT_GT(three.pair_contacts().shared_body.size(), two.pair_contacts().shared_body.size());
  for (int k = 0; k < 299; ++k)
    {
      one.step();
      two.step();
      three.step();
    }
  expect_identical(one, two);
  expect_identical(one, three);
  // The run exercised what it claims to: contacts in more than one summation block, broken
  // bonds, dissipation, list rebuilds.
  EXPECT_GT(one.pair_contacts().size(), 4096u);
  EXPECT_GT(one.n_touching_pairs(), 300u);
  EXPECT_GT(one.n_broken_bonds(), 0u);
  EXPECT_GT(one.energy().viscous_dissipated, 0.0);
  EXPECT_GT(one.energy().friction_dissipated, 0.0);
  EXPECT_GT(one.n_neighbour_rebuilds(), 5u);
}

// A tank's settled lifts are fixed while the next one grows (lift_growth.cc). Skipping the
// contacts between two fixed bodies at rest (DemSystem::set_skip_contacts_between_fixed_bodies),
// and the placing of their discs, must change nothing that a free body sees: the same deposition
// with its lower half fixed, run with and without the skip, gives every free body the same bits,
// and every contact (the skipped ones' forces kept over list rebuilds) the same force, so that
// the unbalanced-force ratio REDF reads is the same too.
TEST(FixedBodies, SkippingTheirContactsChangesNoFreeBody)
{
  DemSystem plain = deposition(2), skipping = deposition(2);
  for (int k = 0; k < 200; ++k)
    {
      plain.step();
      skipping.step();
    }
  std::size_t n_fixed = 0;
  for (DemSystem *system : {&plain, &skipping})
    {
      ParticleSet &p = system->particles();
      n_fixed = 0;
      for (std::size_t b = 0; b < p.n_bodies(); ++b)
        if (p.y[b] < 0.5 * (*std::max_element(p.y.begin(), p.y.end())))
          {
            p.fix_body(b);
            ++n_fixed;
          }
    }
  skipping.set_skip_contacts_between_fixed_bodies(true);
  const std::uint64_t rebuilds_before = skipping.n_neighbour_rebuilds();
  for (int k = 0; k < 300; ++k)
    {
      plain.step();
      skipping.step();
    }
  const ParticleSet &a = plain.particles(), &b = skipping.particles();
  std::size_t n_free = 0;
  for (std::size_t k = 0; k < a.n_bodies(); ++k)
    if (a.inverse_mass[k] > 0.0)
      {
        ++n_free;
        ASSERT_EQ(a.x[k], b.x[k]) << k;
        ASSERT_EQ(a.y[k], b.y[k]) << k;
        ASSERT_EQ(a.rotation[k], b.rotation[k]) << k;
        ASSERT_EQ(a.vx[k], b.vx[k]) << k;
        ASSERT_EQ(a.omega[k], b.omega[k]) << k;
        ASSERT_EQ(a.fx[k], b.fx[k]) << k;
        ASSERT_EQ(a.fy[k], b.fy[k]) << k;
        ASSERT_EQ(a.torque[k], b.torque[k]) << k;
      }
  EXPECT_EQ(a.disc_x, b.disc_x);
  EXPECT_EQ(a.disc_y, b.disc_y);
  EXPECT_EQ(plain.pair_contacts().disc_i, skipping.pair_contacts().disc_i);
  EXPECT_EQ(plain.pair_contacts().force_x, skipping.pair_contacts().force_x);
  EXPECT_EQ(plain.pair_contacts().force_y, skipping.pair_contacts().force_y);
  EXPECT_EQ(plain.pair_contacts().elastic_normal_force, skipping.pair_contacts().elastic_normal_force);
  EXPECT_EQ(unbalanced_force_ratio(plain), unbalanced_force_ratio(skipping));
  EXPECT_EQ(plain.energy().friction_dissipated, skipping.energy().friction_dissipated);
  EXPECT_EQ(plain.energy().elastic, skipping.energy().elastic);
  // What the test claims was exercised: about half the bodies fixed and touching each other,
  // the other half still moving, contacts between fixed bodies, and list rebuilds while they
  // were skipped.
  EXPECT_GT(n_fixed, 1000u);
  EXPECT_GT(n_free, 1000u);
  std::size_t fixed_pairs_touching = 0;
  const PairContacts &c = skipping.pair_contacts();
  for (std::size_t q = 0; q < c.size(); ++q)
    fixed_pairs_touching += c.state[q].touching && b.inverse_mass[b.disc_body[c.disc_i[q]]] == 0.0 &&
                            b.inverse_mass[b.disc_body[c.disc_j[q]]] == 0.0;
  EXPECT_GT(fixed_pairs_touching, 100u); // 151 when written
  EXPECT_GT(skipping.n_neighbour_rebuilds(), rebuilds_before);
}

// Radius expansion of the bodies from one on (a lift over the settled ones): those below keep
// every bit of their sizes, masses and discs; the grown ones are what scaling them all gives.
TEST(FixedBodies, ScalingFromABodyOnLeavesTheOnesBelow)
{
  ParticleSet all = grid_sample(6, 5, 0.1, 3, 11);
  ParticleSet upper = all;
  const std::size_t first = 13;
  all.scale_sizes(1.07);
  ParticleSet before = upper;
  upper.scale_sizes(1.07, first);
  for (std::size_t b = 0; b < upper.n_bodies(); ++b)
    {
      const ParticleSet &expected = b < first ? before : all;
      EXPECT_EQ(upper.mass[b], expected.mass[b]) << b;
      EXPECT_EQ(upper.inertia[b], expected.inertia[b]) << b;
      EXPECT_EQ(upper.inverse_mass[b], expected.inverse_mass[b]) << b;
      for (std::uint32_t d = upper.first_disc[b]; d < upper.first_disc[b] + upper.n_discs[b]; ++d)
        {
          EXPECT_EQ(upper.disc_radius[d], expected.disc_radius[d]) << b;
          EXPECT_EQ(upper.disc_x[d], expected.disc_x[d]) << b;
          EXPECT_EQ(upper.disc_y[d], expected.disc_y[d]) << b;
        }
    }
  EXPECT_NE(upper.disc_radius[upper.first_disc[first]], before.disc_radius[before.first_disc[first]]);
}

// The same with single discs only, the case whose discs are placed in the bodies' first pass
// (ParticleSet::single_centred_discs), with and without local damping and energy bookkeeping
// (each a different body loop; without damping and bookkeeping, the benchmark's loops). On
// several threads each chunk of pairs checks body ownership only in its first pairs
// (PairContacts::chunk_checked_end), and adds the rest at once: the test checks that this part
// exists and is a small share of the pairs, and that the sums still come out the same.
TEST(Threads, SingleDiscsOneTwoThreeThreadsBitForBit)
{
  for (const bool damped : {true, false})
    {
      SCOPED_TRACE(damped ? "local damping, energy bookkeeping" : "no local damping, no energy bookkeeping");
      const double alpha = damped ? 0.7 : 0.0;
      DemSystem one = deposition(1, 0, alpha, damped), two = deposition(2, 0, alpha, damped),
                three = deposition(3, 0, alpha, damped);
      ASSERT_TRUE(one.particles().single_centred_discs());
      for (int k = 0; k < 300; ++k)
        {
          one.step();
          two.step();
          three.step();
        }
      expect_identical(one, two);
      expect_identical(one, three);
      for (const DemSystem *system : {&two, &three})
        {
          const PairContacts &c = system->pair_contacts();
          std::size_t checked = 0;
          for (std::size_t k = 0; k < c.n_chunks; ++k)
            checked += c.chunk_checked_end[k] - c.chunk_begin(k);
          EXPECT_GT(checked, 0u);
          EXPECT_LT(checked, c.size() / 5);
        }
      EXPECT_GT(one.n_touching_pairs(), 300u);
      EXPECT_GT(one.n_neighbour_rebuilds(), 5u);
      if (damped)
        {
          EXPECT_GT(one.energy().local_damping_dissipated, 0.0);
        }
    }
}

// Contact parameters are checked where they enter, with a message naming the parameter.
TEST(BadInput, ContactParametersRefused)
{
  const auto message_of = [](const ContactParameters &c) -> std::string {
    try
      {
        LinearContactLaw law_(c);
      }
    catch (const std::invalid_argument &e)
      {
        return e.what();
      }
    return "";
  };
  ContactParameters c = law(20.0, 0.5);
  EXPECT_NO_THROW(c.validate("test"));

  ContactParameters bad = c;
  bad.normal_stiffness = -1.0e6;
  EXPECT_THROW(bad.validate("test"), std::invalid_argument);
  EXPECT_NE(message_of(bad).find("normal stiffness"), std::string::npos) << message_of(bad);

  for (double angle : {90.0, 95.0, -1.0})
    {
      bad = c;
      bad.friction_angle_deg = angle;
      EXPECT_THROW(bad.validate("test"), std::invalid_argument) << angle;
      EXPECT_NE(message_of(bad).find("friction angle"), std::string::npos) << message_of(bad);
    }
  bad.friction_angle_deg = 89.9; // just below 90 is allowed
  EXPECT_NO_THROW(bad.validate("test"));

  for (double e : {0.0, -0.5, 1.01})
    {
      bad = c;
      bad.restitution = e;
      EXPECT_THROW(bad.validate("test"), std::invalid_argument) << e;
      EXPECT_NE(message_of(bad).find("restitution"), std::string::npos) << message_of(bad);
    }
  bad.restitution = 1.0; // the end of (0, 1] is allowed
  EXPECT_NO_THROW(bad.validate("test"));
  // validate names its caller.
  bad.normal_stiffness = 0.0;
  try
    {
      bad.validate("wall 'floor'");
      ADD_FAILURE() << "zero normal stiffness accepted";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("wall 'floor'"), std::string::npos) << e.what();
    }
}

// The critical step is a bound for the densest packing: a hexagonal packing of equal discs, all
// in contact (6 each), frictional, without damping, keeps its energy at dt = critical_time_step()
// over thousands of steps, for ks = kn (rotation limits) and ks = kn / 2. (Measured with the
// refusal disabled: the same packing blows up at 1.1 x this step, and at 0.7 sqrt(m / kn), the
// single-contact estimate used before.)
TEST(TimeStep, CriticalStepStableForAHexagonalPacking)
{
  for (const double shear_ratio : {1.0, 0.5})
    {
      ParticleSet p;
      const double spacing = 2.0 * r_max * (1.0 - 1e-3); // every neighbour pair overlaps a little
      for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 20; ++i)
          {
            const std::size_t b =
              p.add_disc(Vec2((i + 0.5 * (j % 2)) * spacing, j * spacing * std::sqrt(3.0) / 2.0), r_max, density);
            p.vx[b] = 1e-3 * std::sin(7.1 * i + 3.3 * j); // excite every mode
            p.vy[b] = 1e-3 * std::cos(1.7 * i + 5.3 * j);
          }
      DemSettings s;
      s.gravity = Vec2::Zero();
      s.local_damping = 0.0;
      s.time_step_safety = 1.0;
      ContactParameters c = law(60.0, 1.0);
      c.shear_stiffness = shear_ratio * kn;
      // Strong bonds hold the lattice together (the overlaps would otherwise push it apart), so
      // that every disc keeps its six contacts and the lattice vibrates about its rest state.
      c.tensile_strength = c.shear_strength = 0.1 * kn * r_max;
      c.bond_new_contacts = true;
      DemSystem system(p, LinearContactLaw(c), s);
      ASSERT_EQ(system.time_step(), system.critical_time_step());
      system.initialise_forces();
      ASSERT_GT(system.n_touching_pairs(), 1100u); // 20 x 20 hexagonal: 1123 neighbour pairs
      const double e0 = system.energy().total();
      system.run_steps(4000);
      EXPECT_NEAR(system.energy().total(), e0, 1e-2 * e0) << "ks / kn = " << shear_ratio;
      EXPECT_EQ(system.n_broken_bonds(), 0u);
    }
}

// Sand is a packing of two-disc clusters, whose rotational stiffness the critical step estimates
// from contacts spread evenly round each disc (not a strict bound): a dense REDF packing under
// 100 kPa, its walls fixed, undamped, every body kicked, keeps its stored energy at the critical
// step (friction may only take some away) and all its contacts, for ks = kn / 2 and ks = kn.
// (Measured on 400 clusters with the refusal disabled: stable at 1.6 x, blown up at 2 x.)
TEST(TimeStep, CriticalStepStableForAClusterPacking)
{
  for (const double shear_ratio : {0.5, 1.0})
    {
      RedfSpec spec;
      spec.width = 0.06;
      spec.height = 0.06;
      spec.n_particles = 100;
      spec.particle_contact = law(30.0, 1.0);
      spec.particle_contact.normal_stiffness = 7e7;
      spec.particle_contact.shear_stiffness = shear_ratio * 7e7;
      spec.wall_contact = spec.particle_contact;
      spec.wall_contact.friction_angle_deg = 0.0;
      spec.target_stress = 1e5;
      const RedfSample sample = make_redf_sample(spec);
      DemSettings s = sample.system.settings();
      s.local_damping = 0.0;
      s.gravity = Vec2::Zero();
      s.time_step_safety = 1.0;
      DemSystem system(sample.system.particles(), LinearContactLaw(spec.particle_contact), s);
      for (Wall wall : sample.system.walls())
        {
          wall.control = WallControl::prescribed_velocity;
          wall.velocity = Vec2::Zero();
          system.add_wall(wall);
        }
      ASSERT_EQ(system.time_step(), system.critical_time_step());
      ParticleSet &p = system.particles();
      for (std::size_t b = 0; b < p.n_bodies(); ++b)
        {
          p.vx[b] = 1e-3 * std::sin(7.1 * b);
          p.vy[b] = 1e-3 * std::cos(3.3 * b);
          p.omega[b] = 0.3 * std::sin(1.7 * b);
        }
      system.initialise_forces();
      const std::size_t touching = system.n_touching_pairs();
      ASSERT_GT(touching, 2 * p.n_bodies()); // dense: coordination above 4
      const auto stored_energy = [&] { return system.energy().kinetic + system.energy().elastic; };
      const double e0 = stored_energy();
      system.run_steps(3000);
      EXPECT_LT(stored_energy(), 1.001 * e0) << "ks / kn = " << shear_ratio;
      EXPECT_GT(stored_energy(), 0.9 * e0) << "ks / kn = " << shear_ratio;
      // Kicked grains may slide off a contact or two; a blow-up loses most (at 2 x: a third).
      EXPECT_GT(system.n_touching_pairs(), 0.9 * touching) << "ks / kn = " << shear_ratio;
    }
}

// A step above the critical one is refused, naming the stable limit (its value in the message);
// the critical step itself is accepted. A thread count of 0 is refused.
TEST(BadInput, TimeStepAndThreads)
{
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), r_max, density);
  p.add_disc(Vec2(3.0 * r_max, 0.0), 0.7 * r_max, density);
  DemSettings s;
  const LinearContactLaw contact(law(20.0, 0.5));
  DemSystem system(p, contact, s);
  // Independent value of the limit: the lighter disc, m = rho pi r^2, with 6 contacts: in
  // translation omega^2 = 6 (kn + ks) / m = 9 kn / m for ks = kn / 2, in rotation
  // omega^2 = 2 * 6 ks r^2 / (m r^2 / 2) = 12 kn / m, the higher; dt = 2 / omega.
  const double m = density * pi * 0.49 * r_max * r_max;
  const double dt_crit = 2.0 / std::sqrt(12.0 * kn / m);
  EXPECT_NEAR(system.critical_time_step(), dt_crit, 1e-12 * dt_crit);
  EXPECT_NO_THROW(system.set_time_step(system.critical_time_step()));
  EXPECT_EQ(system.time_step(), system.critical_time_step());
  try
    {
      system.set_time_step(1.01 * dt_crit);
      ADD_FAILURE() << "a step above the critical one was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      std::ostringstream limit;
      limit << system.critical_time_step();
      const std::string what = e.what();
      EXPECT_NE(what.find("stable limit"), std::string::npos) << what;
      EXPECT_NE(what.find(limit.str()), std::string::npos) << what << " (limit " << limit.str() << ")";
    }
  EXPECT_EQ(system.time_step(), system.critical_time_step()); // unchanged by the refusal
  EXPECT_THROW(system.set_time_step(0.0), std::invalid_argument);
  EXPECT_THROW(system.set_time_step(-1e-6), std::invalid_argument);

  s.time_step = 2.0 * dt_crit; // a user step in the settings is checked too
  EXPECT_THROW(DemSystem(p, contact, s), std::invalid_argument);

  DemSettings no_threads;
  no_threads.n_threads = 0;
  EXPECT_THROW(DemSystem(p, contact, no_threads), std::invalid_argument);
  no_threads.n_threads = -2;
  EXPECT_THROW(DemSystem(p, contact, no_threads), std::invalid_argument);
}

// One definition of the automatic step: the safety factor times the critical step of the system
// as it is, walls included. Walls twice as stiff as the grains lower the critical step by sqrt(2)
// (omega^2 scales with kn + ks); the step follows, to exactly the safety factor of the new limit.
// (Before, the step fixed with the grains alone was kept while it stayed below the new limit:
// 0.5 x the grains' critical step, 0.71 of the system's; the run printed one figure and a refused
// user step named the other.)
TEST(TimeStep, AutomaticStepIsTheSafetyFactorOfTheSystemWithItsWalls)
{
  DemSettings s;
  s.time_step_safety = 0.5;
  DemSystem system(grid_sample(6, 4, 0.1), LinearContactLaw(law(20.0, 1.0)), s);
  const double grains_only = system.critical_time_step();
  EXPECT_EQ(system.time_step(), 0.5 * grains_only);
  ContactParameters stiff = law(20.0, 1.0);
  stiff.normal_stiffness *= 2.0;
  stiff.shear_stiffness *= 2.0;
  add_box(system, 6 * 2.5 * r_max, 4 * 2.5 * r_max, LinearContactLaw(stiff));
  EXPECT_NEAR(system.critical_time_step(), grains_only / std::sqrt(2.0), 1e-12 * grains_only);
  EXPECT_EQ(system.time_step(), 0.5 * system.critical_time_step());
  // A step the user chooses between the two limits is refused, naming the walls' limit.
  s.time_step = 0.9 * grains_only;
  DemSystem chosen(grid_sample(6, 4, 0.1), LinearContactLaw(law(20.0, 1.0)), s);
  try
    {
      add_box(chosen, 6 * 2.5 * r_max, 4 * 2.5 * r_max, LinearContactLaw(stiff));
      ADD_FAILURE() << "a step above the walls' limit was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      std::ostringstream limit;
      limit << system.critical_time_step();
      EXPECT_NE(std::string(e.what()).find("stable limit " + limit.str()), std::string::npos) << e.what();
    }
}

// Renumbering bodies in Morton order keeps every body exactly (found by its id, with its discs),
// and brings neighbours close in memory: on a randomly numbered grid, the mean index distance
// between neighbours falls by more than 10 (measured: 543, about n/3, before; 34 after).
TEST(ParticleOrder, SpatialSortKeepsBodiesAndBringsNeighboursClose)
{
  constexpr int n_side = 40;
  ParticleSet grid = grid_sample(n_side, n_side, 0.1, 7, 3, 2.0);
  // Number the bodies at random.
  std::vector<std::size_t> order(grid.n_bodies());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  ParticleSet shuffled;
  for (std::size_t b : order)
    {
      const std::uint32_t d = grid.first_disc[b];
      const Vec2 c(grid.x[b], grid.y[b]);
      const std::size_t nb = grid.n_discs[b] == 1
                               ? shuffled.add_disc(c, grid.disc_radius[d], density, static_cast<std::int64_t>(b))
                               : shuffled.add_two_disc_cluster(c, grid.disc_radius[d], grid.disc_radius[d + 1],
                                                               0.5 * r_max, 0.3, density, static_cast<std::int64_t>(b));
      shuffled.vx[nb] = grid.vx[b];
    }
  const ParticleSet sorted = spatially_sorted(shuffled, 2.0 * r_max);
  ASSERT_EQ(sorted.n_bodies(), shuffled.n_bodies());
  ASSERT_EQ(sorted.n_discs_total(), shuffled.n_discs_total());
  std::vector<std::size_t> index_of_id(shuffled.n_bodies());
  for (std::size_t b = 0; b < shuffled.n_bodies(); ++b)
    index_of_id[static_cast<std::size_t>(shuffled.body_id[b])] = b;
  std::vector<bool> seen(sorted.n_bodies(), false);
  for (std::size_t b = 0; b < sorted.n_bodies(); ++b)
    {
      const std::size_t a = index_of_id[static_cast<std::size_t>(sorted.body_id[b])];
      ASSERT_FALSE(seen[a]);
      seen[a] = true;
      EXPECT_EQ(sorted.x[b], shuffled.x[a]);
      EXPECT_EQ(sorted.y[b], shuffled.y[a]);
      EXPECT_EQ(sorted.vx[b], shuffled.vx[a]);
      EXPECT_EQ(sorted.mass[b], shuffled.mass[a]);
      EXPECT_EQ(sorted.inertia[b], shuffled.inertia[a]);
      ASSERT_EQ(sorted.n_discs[b], shuffled.n_discs[a]);
      for (std::uint32_t k = 0; k < sorted.n_discs[b]; ++k)
        {
          const std::uint32_t d = sorted.first_disc[b] + k, e = shuffled.first_disc[a] + k;
          EXPECT_EQ(sorted.disc_body[d], b);
          EXPECT_EQ(sorted.disc_radius[d], shuffled.disc_radius[e]);
          EXPECT_EQ(sorted.disc_x[d], shuffled.disc_x[e]);
          EXPECT_EQ(sorted.disc_offset_y[d], shuffled.disc_offset_y[e]);
        }
    }
  // Mean index distance between bodies whose centres are within 1.5 grid pitches.
  const auto mean_neighbour_distance = [](const ParticleSet &p) {
    double sum = 0.0;
    std::size_t n = 0;
    const double reach = 1.5 * 2.0 * r_max;
    for (std::size_t a = 0; a < p.n_bodies(); ++a)
      for (std::size_t b = a + 1; b < p.n_bodies(); ++b)
        if (std::hypot(p.x[a] - p.x[b], p.y[a] - p.y[b]) < reach)
          {
            sum += static_cast<double>(b - a);
            ++n;
          }
    return sum / static_cast<double>(n);
  };
  const double before = mean_neighbour_distance(shuffled), after = mean_neighbour_distance(sorted);
  EXPECT_GT(before, 10.0 * after) << before << " -> " << after;
  EXPECT_THROW(spatially_sorted(shuffled, 0.0), std::invalid_argument);
}

// Coupling hooks (issue 6), attached to a system as a CouplingAttachment: energy weights scale a
// body's mass by its weight and a contact's force, stored energy and dissipation by the mean weight
// along its branch; the force hook adds forces before the second half kick.
TEST(EnergyWeights, ScaleMassesAndContactForcesByTheBranchMean)
{
  // Two discs 1 cm across overlapping by 1 um, the band (8 mm wide) starting between them.
  const double r = 0.005, overlap = 1e-6, kn = 1e7, width = 0.008;
  const auto make = [&] {
    ParticleSet p;
    p.add_disc(Vec2(0.0, 0.0), r, 2000.0);
    p.add_disc(Vec2(2 * r - overlap, 0.0), r, 2000.0);
    ContactParameters c;
    c.normal_stiffness = kn;
    c.shear_stiffness = 0.5 * kn;
    DemSettings s;
    s.gravity = Vec2(0.0, 0.0);
    s.local_damping = 0.0;
    return DemSystem(p, LinearContactLaw(c), s);
  };
  DemSystem plain = make(), weighted = make();
  EnergyWeights weights;
  weights.band_width = width;
  const double s0 = -0.004, s1 = s0 + 2 * r - overlap; // particle weights 1 and 1 - s1 / width
  weights.body_band_coordinate.resize(2);
  weights.body_band_coordinate[0] = s0;
  weights.body_band_coordinate[1] = s1;
  EnergyWeights past_the_band = weights;
  CouplingAttachment coupling;
  coupling.set_energy_weights(weighted.particles(), weights);
  EXPECT_THROW(coupling.set_energy_weights(weighted.particles(), weights), std::invalid_argument); // once
  weighted.attach(coupling);
  EXPECT_THROW(weighted.attach(coupling), std::logic_error);
  plain.initialise_forces();
  weighted.initialise_forces();
  // Mean of 1 - clamp(s / w) along the branch: 4 mm at 1, then s1 of the ramp at 1 - s1 / (2 w).
  const double branch_weight = (-s0 + s1 * (1.0 - s1 / (2.0 * width))) / (s1 - s0);
  EXPECT_NEAR(weights.contact_weight(0, 1), branch_weight, 1e-14);
  EXPECT_NEAR(plain.particles().fx[0], -kn * overlap, 1e-9 * kn * overlap);
  EXPECT_NEAR(weighted.particles().fx[0], branch_weight * plain.particles().fx[0], 1e-12 * kn * overlap);
  EXPECT_NEAR(weighted.particles().fx[1], -weighted.particles().fx[0], 1e-12 * kn * overlap);
  EXPECT_DOUBLE_EQ(weighted.particles().mass[0], plain.particles().mass[0]);
  EXPECT_NEAR(weighted.particles().mass[1], (1.0 - s1 / width) * plain.particles().mass[1], 1e-12 * plain.particles().mass[1]);
  EXPECT_NEAR(weighted.particles().inverse_mass[1] * weighted.particles().mass[1], 1.0, 1e-14);
  EXPECT_NEAR(weighted.energy().elastic, branch_weight * plain.energy().elastic, 1e-12 * plain.energy().elastic);
  EXPECT_LT(weighted.critical_time_step(), plain.critical_time_step()); // a lighter body, weighted springs
  // A free body with no weight left (past the band's continuum edge) is refused.
  past_the_band.body_band_coordinate[1] = width + 0.001;
  DemSystem past = make();
  CouplingAttachment refused;
  EXPECT_THROW(refused.set_energy_weights(past.particles(), past_the_band), std::invalid_argument);
  // Detached, the system runs its unweighted contacts again.
  weighted.detach();
  EXPECT_LT(weighted.critical_time_step(), plain.critical_time_step()); // the masses stay weighted
  EXPECT_NEAR(weighted.energy().elastic, plain.energy().elastic, 1e-12 * plain.energy().elastic);
}

// The band's density scaling (CouplingAttachment::scale_band_inertia): the light body's inertial
// mass is raised to its stiffest contact's weight, its weight (gravity) is not, and the critical
// step goes back to the unweighted pair's.
TEST(EnergyWeights, BandInertiaScalingKeepsTheWeightAndRestoresTheStep)
{
  const double r = 0.005, width = 0.008, g = 9.81;
  const auto make = [&] {
    ParticleSet p;
    p.add_disc(Vec2(0.0, 0.0), r, 2000.0);
    p.add_disc(Vec2(2 * r, 0.0), r, 2000.0);
    DemSettings s;
    s.gravity = Vec2(0.0, -g);
    s.local_damping = 0.0;
    return DemSystem(p, LinearContactLaw(), s);
  };
  DemSystem plain = make(), scaled = make();
  EnergyWeights weights;
  weights.band_width = width;
  weights.body_band_coordinate.resize(2);
  weights.body_band_coordinate[0] = -0.004;    // weight 1
  weights.body_band_coordinate[1] = 0.006;     // weight 1 - 0.006 / 0.008 = 0.25
  CouplingAttachment coupling, weights_only;
  EXPECT_THROW(coupling.scale_band_inertia(scaled.particles()), std::logic_error); // no weights yet
  coupling.set_energy_weights(scaled.particles(), weights);
  DemSystem weighted = make();
  weights_only.set_energy_weights(weighted.particles(), weights);
  weighted.attach(weights_only);
  const double weighted_step = weighted.critical_time_step();
  // Body 1's stiffest contact reaches 2 r = 10 mm towards the core: s = -0.004, weight 1.
  EXPECT_NEAR(coupling.scale_band_inertia(scaled.particles()), 4.0, 1e-12);
  EXPECT_THROW(coupling.scale_band_inertia(scaled.particles()), std::logic_error);
  scaled.attach(coupling);
  EXPECT_TRUE(coupling.band_inertia_scaled());
  // Attached, the masses stay those its time step was set for.
  EXPECT_THROW(weights_only.set_energy_weights(weighted.particles(), weights), std::logic_error);
  const ParticleSet &p = scaled.particles();
  const double m = plain.particles().mass[1];
  EXPECT_NEAR(p.mass[1], 0.25 * m, 1e-12 * m);                // the weight gravity acts on
  EXPECT_NEAR(1.0 / p.inverse_mass[1], m, 1e-12 * m);         // the inertial mass
  EXPECT_NEAR(1.0 / p.inverse_mass[0], m, 1e-12 * m);         // the core's body unchanged
  EXPECT_LT(weighted_step, 0.6 * plain.critical_time_step());
  EXPECT_NEAR(scaled.critical_time_step(), plain.critical_time_step(), 1e-12 * plain.critical_time_step());
  // Falling freely (the discs touch without overlap): body 1 accelerates at g / 4.
  scaled.run_steps(10);
  const double t = 10 * scaled.time_step();
  EXPECT_NEAR(scaled.particles().vy[1], -0.25 * g * t, 1e-9 * g * t);
  EXPECT_NEAR(scaled.particles().vy[0], -g * t, 1e-9 * g * t);
}

TEST(EnergyWeights, ForceHookActsBeforeTheSecondHalfKick)
{
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), 0.01, 1000.0);
  DemSettings s;
  s.gravity = Vec2(0.0, 0.0);
  s.local_damping = 0.0;
  DemSystem system(p, LinearContactLaw(), s);
  std::vector<double> impulse_times;
  const double force = 2.0; // N/m along x
  CouplingAttachment coupling;
  coupling.set_force_hook([&](ParticleSet &particles, double impulse_time) {
    particles.fx[0] += force;
    impulse_times.push_back(impulse_time);
  });
  system.attach(coupling);
  system.run_steps(10);
  // A constant force: v = F t / m after 10 steps, x = F t^2 / (2 m) (velocity Verlet is exact here).
  const double m = system.particles().mass[0], dt = system.time_step(), t = 10 * dt;
  EXPECT_NEAR(system.particles().vx[0], force * t / m, 1e-12 * force * t / m);
  EXPECT_NEAR(system.particles().x[0], 0.5 * force * t * t / m, 1e-12 * force * t * t / m);
  ASSERT_EQ(impulse_times.size(), 11u); // the evaluation at t = 0, then one per step
  EXPECT_DOUBLE_EQ(impulse_times[0], 0.5 * dt);
  EXPECT_DOUBLE_EQ(impulse_times[1], dt);
}

// Local damping leaves exempt bodies alone (a coupling's tied particles): two equal discs fall
// from rest under gravity with alpha = 0.7; the exempt one falls freely (velocity Verlet is exact
// for a constant force: v = g t), the other at (1 - alpha) g once it moves.
TEST(LocalDamping, ExemptBodiesFallFreely)
{
  ParticleSet p;
  p.add_disc(Vec2(0.0, 0.0), 0.01, 1000.0);
  p.add_disc(Vec2(1.0, 0.0), 0.01, 1000.0);
  DemSettings s;
  s.gravity = Vec2(0.0, -9.81);
  s.local_damping = 0.7;
  s.time_step = 1e-5;
  DemSystem system(p, LinearContactLaw(), s);
  CouplingAttachment coupling;
  coupling.set_constrained_bodies(system.particles(), {0});
  system.attach(coupling);
  system.initialise_forces();
  for (int n = 0; n < 100; ++n)
    system.step();
  const double t = 100 * 1e-5;
  EXPECT_NEAR(system.particles().vy[0], -9.81 * t, 1e-12);
  EXPECT_NEAR(system.particles().vy[1], -(1.0 - 0.7) * 9.81 * t, 0.02 * 9.81 * t);
  coupling.set_constrained_bodies(system.particles(), {}); // damped again (from the second half kick on:
  system.step();                                           // the first step's first half kick has none)
  const double v0 = system.particles().vy[0];
  system.step();
  EXPECT_NEAR(system.particles().vy[0] - v0, -(1.0 - 0.7) * 9.81 * 1e-5, 1e-12);
  EXPECT_THROW(coupling.set_constrained_bodies(system.particles(), {2}), std::invalid_argument);
}
