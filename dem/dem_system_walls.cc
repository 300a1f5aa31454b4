// Rigid walls in the system: adding one, moving them (prescribed velocity or PFC's stress servo),
// their disc contacts and the energy terms of those contacts.
#include "dem_system.h"

#include "contact_frame.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace geohybrid::dem
{
std::size_t DemSystem::add_wall(const Wall &wall)
{
  if ((wall.end - wall.start).norm() <= 0.0)
    throw std::invalid_argument("wall '" + wall.name + "': start and end points coincide");
  walls_.push_back(wall);
  wall_contacts_.emplace_back();
  wall_force_previous_.push_back(Vec2::Zero());
  wall_friction_work_.push_back(0.0);
  wall_viscous_work_.push_back(0.0);
  skin_ = std::max(skin_, 1.05 * wall.law.max_bonded_gap());
  rebuild_needed_ = true;
  // A stiffer wall lowers the stable step: the automatic step follows it, a step the user chose is
  // re-checked (throws if it is now unstable).
  update_time_step();
  return walls_.size() - 1;
}

void DemSystem::move_walls()
{
  const double dt = time_step_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    {
      Wall &wall = walls_[w];
      if (wall.control == WallControl::servo_stress)
        {
          // PFC's servo: retreat by the distance that would remove a fraction `relaxation` of the
          // stress error, given the contacts' stiffness: v = alpha (sigma - sigma_0) L / (N kn dt),
          // plus an integral term so that a steadily moving wall holds its stress without lag.
          WallServo &servo = wall.servo;
          const double error = wall.normal_stress() - servo.target_stress;
          const double n_contacts = std::max<double>(1.0, static_cast<double>(wall.n_contacts));
          const double kn = wall.law.normal_stiffness();
          double resistance = n_contacts * kn * dt; // the contacts' force change per unit speed over a step
          if (wall.law.has_dashpot() && wall.n_contacts > 0)
            {
              // A wall with dashpots also meets c = 2 zeta sqrt(kn m) per contact at once: left out,
              // the servo overshoots each step and, the dashpots never pulling (contact_law.h),
              // locks into a cycle at its speed cap, the stress jumping by +-50 % (ServoWall test).
              resistance = 0.0;
              const WallContacts &c = wall_contacts_[w];
              for (std::size_t q = 0; q < c.disc.size(); ++q)
                if (c.state[q].touching)
                  {
                    const double inverse_mass = particles_.inverse_mass[particles_.disc_body[c.disc[q]]];
                    resistance += kn * dt; // a fixed body's contact has no dashpot (contact_law.h)
                    if (inverse_mass > 0.0)
                      resistance += 2.0 * wall.law.damping_ratio() * std::sqrt(kn / inverse_mass);
                  }
            }
          const double gain = servo.relaxation * wall.stress_length() / resistance;
          double speed = gain * (error + servo.integral_gain * (servo.integral + error));
          if (std::abs(speed) < servo.max_speed && wall.n_contacts > 0)
            servo.integral += error; // no wind-up while capped or out of contact
          speed = std::clamp(speed, -servo.max_speed, servo.max_speed);
          wall.velocity = -speed * wall.normal();
        }
      wall.translate(dt * wall.velocity);
    }
}

void DemSystem::compute_wall_forces()
{
  ParticleSet &p = particles_;
  const double dt = time_step_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    {
      Wall &wall = walls_[w];
      WallContacts &c = wall_contacts_[w];
      Vec2 total = Vec2::Zero();
      std::size_t n_touching = 0;
      double friction = 0.0, viscous = 0.0;
      for (std::size_t q = 0; q < c.disc.size(); ++q)
        {
          const std::uint32_t d = c.disc[q];
          ContactState &state = c.state[q];
          const Vec2 centre(p.disc_x[d], p.disc_y[d]);
          Vec2 closest;
          const double distance = closest_point_on_segment(centre, wall.start, wall.end, closest);
          const double overlap = p.disc_radius[d] - distance;
          if (overlap <= 0.0 && !state.bonded && !state.touching)
            {
              c.force_x[q] = c.force_y[q] = c.elastic_normal_force[q] = 0.0;
              c.friction_work[q] = c.viscous_work[q] = 0.0;
              continue;
            }
          const std::uint32_t b = p.disc_body[d];
          const Vec2 normal =
            ContactFrame::normal_towards(centre, closest, distance, [&]() -> Vec2 { return -wall.normal(); });
          const ContactFrame contact = ContactFrame::of_disc(p, d, normal, overlap);
          const ContactForce f = wall.law.evaluate(contact.kinematics(wall.velocity, p.inverse_mass[b], dt), state);
          const Vec2 force = contact.force_on_i(f);
          c.force_x[q] = force.x();
          c.force_y[q] = force.y();
          c.elastic_normal_force[q] = state.touching ? f.elastic_normal : 0.0;
          c.friction_work[q] = f.friction_work;
          c.viscous_work[q] = f.viscous_work;
          friction += f.friction_work;
          viscous += f.viscous_work;
          n_broken_bonds_ += f.bond_broke;
          p.fx[b] += force.x();
          p.fy[b] += force.y();
          p.torque[b] += cross(contact.lever(), force);
          total -= force;
          n_touching += state.touching;
        }
      // Sheet nodes pressing on the wall (none without sheets): their force is part of the
      // wall's load; n_contacts keeps counting discs (it is the particles' coordination).
      for (std::size_t s = 0; s < sheets_.size(); ++s)
        {
          const SheetWallLoad load = evaluate_sheet_wall_contacts(sheets_[s], wall, sheet_contacts_[s].walls[w], dt);
          total += load.force_on_wall;
          friction += load.work.friction;
          viscous += load.work.viscous;
          n_broken_bonds_ += load.work.broken_bonds;
        }
      wall.force_from_particles = total;
      wall.n_contacts = n_touching;
      wall_friction_work_[w] = friction;
      wall_viscous_work_[w] = viscous;
    }
}

void DemSystem::book_wall_work()
{
  const double dt = time_step_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    {
      const Vec2 total = walls_[w].force_from_particles;
      if (settings_.track_energy && dt > 0.0)
        {
          accumulated_.friction_dissipated += wall_friction_work_[w];
          accumulated_.viscous_dissipated += wall_viscous_work_[w];
          // Work of the wall on the particles, trapezoidal in time.
          accumulated_.boundary_work -= 0.5 * (total + wall_force_previous_[w]).dot(walls_[w].velocity) * dt;
        }
      wall_force_previous_[w] = total;
    }
}

std::size_t DemSystem::n_touching_wall_contacts() const
{
  std::size_t n = 0;
  for (const Wall &w : walls_)
    n += w.n_contacts;
  return n;
}
} // namespace geohybrid::dem
