#include "hybrid_box_settling.h"

#include "dem/measurements.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::coupling
{
double highest_grain_top(const dem::ParticleSet &p)
{
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    top = std::max(top, p.disc_y[d] + p.disc_radius[d]);
  return top;
}

std::uint64_t step_particles_until(dem::DemSystem &particles, const std::function<bool()> &at_rest,
                                   std::uint64_t max_steps, const std::function<std::string()> &failure)
{
  std::uint64_t steps = 0;
  do
    {
      if (steps >= max_steps)
        throw std::runtime_error(failure());
      for (int k = 0; k < 200; ++k)
        particles.step();
      steps += 200;
    }
  while (!at_rest());
  return steps;
}

OverburdenSettling settle_under_overburden(dem::DemSystem &particles, std::size_t lid_index, double stress,
                                           double target, std::uint64_t max_steps, const std::string &where)
{
  const dem::ParticleSet &p = particles.particles();
  const double top = highest_grain_top(p);
  dem::Wall &lid = particles.walls()[lid_index];
  const double parked_at = lid.start.y();
  const dem::LinearContactLaw law_while_filling = lid.law;
  dem::ContactParameters frictionless = lid.law.parameters();
  frictionless.friction_angle_deg = 0.0; // a surcharge, as an air bag, carries no shear
  lid.law = dem::LinearContactLaw(frictionless);
  lid.translate(dem::Vec2(0.0, top - lid.start.y()));
  lid.control = dem::WallControl::servo_stress;
  lid.servo = dem::WallServo{};
  lid.servo.target_stress = stress;
  // The speed a lid may approach at: a hundredth of a grain's radius per step at most.
  lid.servo.max_speed = 0.01 * *std::min_element(p.disc_radius.begin(), p.disc_radius.end()) / particles.time_step();
  particles.request_neighbour_rebuild();
  const auto lid_stress = [&] { return particles.walls()[lid_index].normal_stress(); };
  const std::uint64_t steps = step_particles_until(
    particles,
    [&] { return std::abs(lid_stress() - stress) < 0.01 * stress && dem::unbalanced_force_ratio(particles) < target; },
    max_steps,
    [&] {
      std::ostringstream message;
      message << where << ": the particle box did not settle under its overburden of " << stress << " Pa in "
              << max_steps << " steps (the lid at " << lid_stress() << " Pa, unbalanced-force ratio "
              << dem::unbalanced_force_ratio(particles) << ", target " << target << ")";
      return message.str();
    });
  const double reached = lid_stress();
  dem::Wall &done = particles.walls()[lid_index];
  const double surface = done.start.y();
  done.control = dem::WallControl::prescribed_velocity;
  done.velocity = dem::Vec2::Zero();
  done.law = law_while_filling;
  done.translate(dem::Vec2(0.0, parked_at - done.start.y()));
  particles.request_neighbour_rebuild();
  return {steps, reached, surface};
}
} // namespace geohybrid::coupling
