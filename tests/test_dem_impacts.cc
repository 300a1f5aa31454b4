// Closed-form checks of the linear contact law in collisions: contact duration, maximum overlap,
// restitution, and the sliding and sticking regimes of an oblique impact.
#include "dem/dem_system.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace geohybrid::dem;

namespace
{
constexpr double density = 2650.0, radius = 0.01, kn = 1.0e6;

DemSettings dynamics_settings()
{
  DemSettings s;
  s.gravity = Vec2::Zero();
  s.local_damping = 0.0;
  s.time_step_safety = 0.01; // resolve the contact in about 300 steps
  return s;
}

ContactParameters law(double restitution, double friction_deg = 0.0, double ks = 0.5 * kn)
{
  ContactParameters c;
  c.normal_stiffness = kn;
  c.shear_stiffness = ks;
  c.friction_angle_deg = friction_deg;
  c.restitution = restitution;
  return c;
}

struct ImpactRecord
{
  double duration = 0.0, max_overlap = 0.0;
};

/// Runs until the contact has closed and opened again, timing it.
ImpactRecord run_pair_until_separated(DemSystem &system)
{
  ImpactRecord r;
  bool started = false;
  for (int k = 0; k < 200000; ++k)
    {
      system.step();
      const ParticleSet &p = system.particles();
      const double overlap = p.disc_radius[0] + p.disc_radius[1] - std::hypot(p.x[1] - p.x[0], p.y[1] - p.y[0]);
      if (overlap > 0.0)
        {
          started = true;
          r.duration += system.time_step();
          r.max_overlap = std::max(r.max_overlap, overlap);
        }
      else if (started)
        break;
    }
  return r;
}
} // namespace

// Two equal discs meet head-on at relative speed 2 v. Without a dashpot the contact is half a
// period of the oscillator of mass m* = m/2: duration pi sqrt(m*/kn), peak overlap
// v_rel sqrt(m*/kn), and the velocities are exactly reversed.
TEST(Impact, TwoDiscNormalElastic)
{
  ParticleSet p;
  const double v = 0.5;
  p.add_disc(Vec2(0.0, 0.0), radius, density);
  p.add_disc(Vec2(2.0 * radius + 1e-4, 0.0), radius, density);
  p.vx[0] = v;
  p.vx[1] = -v;
  DemSystem system(p, LinearContactLaw(law(1.0)), dynamics_settings());
  const ImpactRecord r = run_pair_until_separated(system);
  const double m_eff = 0.5 * system.particles().mass[0];
  EXPECT_NEAR(r.duration, M_PI * std::sqrt(m_eff / kn), 0.01 * M_PI * std::sqrt(m_eff / kn));
  EXPECT_NEAR(r.max_overlap, 2.0 * v * std::sqrt(m_eff / kn), 1e-3 * 2.0 * v * std::sqrt(m_eff / kn));
  EXPECT_NEAR(system.particles().vx[0], -v, 1e-3 * v);
  EXPECT_NEAR(system.particles().vx[1], v, 1e-3 * v);
}

// The no-tension Kelvin-Voigt contact (dem/contact_law.h): the oscillator of damping ratio zeta
// and frequency omega, delta = (v / omega_d) exp(-zeta omega t) sin(omega_d t), until its force
// kn delta + c d(delta)/dt falls to zero, at omega_d t* = pi - 2 asin(zeta) (a linear contact
// would pull from there on); the discs then part at the speed they have, e exp(2 zeta asin(zeta)
// / sqrt(1 - zeta^2)) times the approach speed, and the overlap closes in a further 2 zeta / omega.
struct NoTensionRebound
{
  double restitution;  ///< rebound speed / approach speed [-]
  double overlap_time; ///< time with overlap > 0 [s]
};

NoTensionRebound no_tension_rebound(double e, double zeta, double omega)
{
  const double root = std::sqrt(1.0 - zeta * zeta);
  return {e * std::exp(2.0 * zeta * std::asin(zeta) / root),
          (M_PI - 2.0 * std::asin(zeta)) / (omega * root) + 2.0 * zeta / omega};
}

// With a dashpot set from e the contact is the no-tension Kelvin-Voigt one above: the rebound is a
// little faster than e (0.902, 0.550 and 0.325 of the approach for e = 0.9, 0.5 and 0.2), and the
// overlap lasts a little less than the linear pi / (omega sqrt(1 - zeta^2)) (4.3 % less at 0.2).
// The dashpot sees the half-step velocity (as in LAMMPS and PFC), a first-order lag: at 1 % of
// the critical step both are within 1 %.
TEST(Impact, TwoDiscNormalRestitution)
{
  for (double e : {0.9, 0.5, 0.2})
    {
      ParticleSet p;
      const double v = 0.5;
      p.add_disc(Vec2(0.0, 0.0), radius, density);
      p.add_disc(Vec2(2.0 * radius + 1e-4, 0.0), radius, density);
      p.vx[0] = v;
      p.vx[1] = -v;
      DemSystem system(p, LinearContactLaw(law(e)), dynamics_settings());
      const ImpactRecord r = run_pair_until_separated(system);
      const double zeta = system.particle_law().damping_ratio();
      const double omega = std::sqrt(kn / (0.5 * system.particles().mass[0]));
      const NoTensionRebound expected = no_tension_rebound(e, zeta, omega);
      const double rebound = 2.0 * v * expected.restitution;
      EXPECT_NEAR(system.particles().vx[1] - system.particles().vx[0], rebound, 1e-2 * rebound) << "e = " << e;
      EXPECT_NEAR(r.duration, expected.overlap_time, 0.01 * expected.overlap_time) << "e = " << e;
    }
}

// A disc thrown at a rigid wall: the wall acts as infinite mass, so m* = m; the no-tension
// rebound of TwoDiscNormalRestitution (0.718 and 0.397 of the approach for e = 0.7 and 0.3).
TEST(Impact, DiscWallRestitution)
{
  for (double e : {1.0, 0.7, 0.3})
    {
      ParticleSet p;
      const double v = 1.0;
      p.add_disc(Vec2(0.0, radius + 1e-4), radius, density);
      p.vy[0] = -v;
      DemSystem system(p, LinearContactLaw(law(1.0)), dynamics_settings());
      system.add_wall(Wall("floor", Vec2(-1.0, 0.0), Vec2(1.0, 0.0), LinearContactLaw(law(e))));
      double duration = 0.0;
      bool started = false;
      for (int k = 0; k < 100000; ++k)
        {
          system.step();
          const bool touching = system.particles().y[0] < radius;
          if (touching)
            {
              started = true;
              duration += system.time_step();
            }
          else if (started)
            break;
        }
      const double m = system.particles().mass[0];
      const double zeta = system.walls()[0].law.damping_ratio();
      const NoTensionRebound expected = no_tension_rebound(e, zeta, std::sqrt(kn / m));
      EXPECT_NEAR(system.particles().vy[0], expected.restitution * v, 5e-3 * expected.restitution * v) << "e = " << e;
      EXPECT_NEAR(duration, expected.overlap_time, 0.01 * expected.overlap_time) << "e = " << e;
    }
}

// Without a bond the soil has no tension: in a disc-wall impact at e = 0.5 the total normal force
// (spring and dashpot) is never negative, at any step (unclipped, a linear contact's dashpot pulls
// the disc back as the overlap closes, with c e v = 2 zeta sqrt(kn m) e v = 197 N/m here against
// a peak of 744 N/m). The
// dashpot's booked work is that of the force applied: the energy balance closes to 1e-3 of the
// impact's energy (EnergyBalance.ClosesWithDissipation's tolerance) and the energy dissipated is
// (1 - e'^2) of it, e' the no-tension restitution (0.550), to 1 %.
TEST(Impact, DampedContactNeverPulls)
{
  const double v = 1.0, e = 0.5;
  ParticleSet p;
  p.add_disc(Vec2(0.0, radius + 1e-4), radius, density);
  p.vy[0] = -v;
  DemSystem system(p, LinearContactLaw(law(1.0)), dynamics_settings());
  const std::size_t floor = system.add_wall(Wall("floor", Vec2(-1.0, 0.0), Vec2(1.0, 0.0), LinearContactLaw(law(e))));
  system.initialise_forces();
  const EnergyBudget start = system.energy();
  double smallest = 0.0, largest = 0.0, worst_balance = 0.0;
  bool started = false;
  for (int k = 0; k < 100000; ++k)
    {
      system.step();
      const Wall &w = system.walls()[floor];
      const double normal_force = -w.force_from_particles.dot(w.normal()); // compression positive
      smallest = std::min(smallest, normal_force);
      largest = std::max(largest, normal_force);
      worst_balance = std::max(worst_balance, std::abs(system.energy().total() - start.total()));
      const bool touching = system.particles().y[0] < radius;
      started = started || touching;
      if (started && !touching)
        break;
    }
  ASSERT_GT(system.particles().vy[0], 0.0); // rebounded
  std::cout << "normal force from " << smallest << " to " << largest << " N/m; rebound " << system.particles().vy[0] / v
            << " of the approach; balance " << worst_balance / start.kinetic << " of the impact's energy; dissipated "
            << system.energy().viscous_dissipated / start.kinetic << " of it" << std::endl;
  EXPECT_GE(smallest, 0.0);
  EXPECT_GT(largest, 0.8 * v * std::sqrt(kn * system.particles().mass[0])); // the impact happened
  EXPECT_LT(worst_balance, 1e-3 * start.kinetic);
  const double zeta = system.walls()[floor].law.damping_ratio();
  const double rebound = no_tension_rebound(e, zeta, std::sqrt(kn / system.particles().mass[0])).restitution;
  const double dissipated = (1.0 - rebound * rebound) * start.kinetic;
  EXPECT_NEAR(system.energy().viscous_dissipated, dissipated, 0.01 * dissipated);
}

// Oblique impact of a non-spinning disc on a wall. Sliding throughout (large tangential speed):
// the Coulomb impulse gives  dv_t = -mu (1 + e) v_n  and  omega = mu (1 + e) v_n m r / I.
// The contact point sits at mid-overlap, so the lever arm is r - overlap/2: the approach speed is
// kept low so that the peak overlap is 0.05 % of r and the closed form (lever r) applies.
TEST(Impact, ObliqueSlidingRegime)
{
  const double mu_deg = 20.0, mu = std::tan(mu_deg * M_PI / 180.0), vn = 0.05, vt = 0.3;
  ParticleSet p;
  p.add_disc(Vec2(0.0, radius + 1e-4), radius, density);
  p.vx[0] = vt;
  p.vy[0] = -vn;
  DemSystem system(p, LinearContactLaw(law(1.0)), dynamics_settings());
  system.add_wall(Wall("floor", Vec2(-10.0, 0.0), Vec2(10.0, 0.0), LinearContactLaw(law(1.0, mu_deg))));
  system.run_steps(6000);
  ASSERT_GT(system.particles().y[0], radius); // rebounded
  const ParticleSet &q = system.particles();
  EXPECT_NEAR(q.vy[0], vn, 1e-3 * vn);
  EXPECT_NEAR(q.vx[0], vt - mu * 2.0 * vn, 2e-3 * vt);
  // Friction at the bottom pushes -x, so the disc spins clockwise (negative omega).
  const double expected_omega = -mu * 2.0 * vn * q.mass[0] * radius / q.inertia[0];
  EXPECT_NEAR(q.omega[0], expected_omega, 5e-3 * std::abs(expected_omega));
}

// Sticking throughout: with ks = kn / 3 a disc (I = m r^2 / 2, tangential effective mass m/3)
// has equal normal and tangential frequencies, so the tangential spring makes exactly half an
// oscillation during the contact and the contact-point tangential velocity is reversed.
TEST(Impact, ObliqueStickingRegime)
{
  const double vn = 0.05, vt = 0.005;
  ParticleSet p;
  p.add_disc(Vec2(0.0, radius + 1e-4), radius, density);
  p.vx[0] = vt;
  p.vy[0] = -vn;
  DemSystem system(p, LinearContactLaw(law(1.0)), dynamics_settings());
  system.add_wall(Wall("floor", Vec2(-10.0, 0.0), Vec2(10.0, 0.0), LinearContactLaw(law(1.0, 89.0, kn / 3.0))));
  system.run_steps(6000);
  const ParticleSet &q = system.particles();
  ASSERT_GT(q.y[0], radius);
  const double contact_point_velocity = q.vx[0] + q.omega[0] * radius; // v + omega x (0, -r)
  EXPECT_NEAR(contact_point_velocity, -vt, 0.02 * vt);
}
