// System-level checks of DemSystem: bit-for-bit reproducibility across thread counts, fixed bodies
// (their contacts skipped, the bodies above them grown), the particles' spatial order, the coupling's
// energy weights and force hook, and local damping of exempt bodies.
#include "dem/dem_system.h"
#include "dem/measurements.h"
#include "dem_system_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

using namespace geohybrid::dem;
using namespace geohybrid::testing::dem_system_scenes;

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
