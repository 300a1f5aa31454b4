#include "sample_reuse.h"

#include "dem/measurements.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
std::uint64_t change_contact_laws(DemSystem &system, const RectangularBox &box, const ContactParameters &particle,
                                  const ContactParameters &wall, double stress, const EquilibriumCriteria &criteria)
{
  if (!(stress > 0.0))
    throw std::invalid_argument("change_contact_laws: the confining stress must be positive");
  particle.validate("change_contact_laws: particle contact");
  wall.validate("change_contact_laws: wall contact");
  // The current step may be unstable with stiffer laws, and set_particle_law refuses a law that
  // makes it so: shorten it first (any step below the current critical one is accepted), then
  // take the automatic step of the new laws.
  system.set_time_step(1e-3 * system.time_step());
  for (Wall &w : system.walls())
    w.law = LinearContactLaw(wall);
  system.set_particle_law(LinearContactLaw(particle));
  system.set_time_step(system.settings().time_step_safety * system.critical_time_step());

  box.servo_sides(system, stress, true, stress, true, 0.05);
  const std::uint64_t check_every = 200;
  for (std::uint64_t steps = 1;; ++steps)
    {
      box.update_loaded_lengths(system);
      system.step();
      if (steps % check_every != 0)
        continue;
      const double stress_error = std::max(std::abs(box.horizontal_stress(system) / stress - 1.0),
                                           std::abs(box.vertical_stress(system) / stress - 1.0));
      if (stress_error < criteria.stress_tolerance && unbalanced_force_ratio(system) < criteria.unbalanced_ratio)
        return steps;
      if (steps >= criteria.max_steps)
        {
          std::ostringstream message;
          message << "no equilibrium at " << stress << " Pa after changing the contact laws (" << steps
                  << " steps, stress error " << stress_error << ", unbalanced-force ratio "
                  << unbalanced_force_ratio(system) << ")";
          throw std::runtime_error(message.str());
        }
    }
}
} // namespace geohybrid::dem
