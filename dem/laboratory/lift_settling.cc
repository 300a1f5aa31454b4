#include "lift_settling.h"

#include "dem/measurements.h"
#include "tank_walls.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace geohybrid::dem
{
SettledFill fill_system_from_state(DemSystemState state, const TankFillingSpec &t, const LinearContactLaw &material,
                                   const DemSettings &settling_settings, const LiftLevels &levels)
{
  SettledFill fill;
  fill.system = std::make_unique<DemSystem>(state.particles, material, settling_settings);
  fill.walls = add_tank_walls(*fill.system, t, levels.lid, levels.slot_bottom, levels.slot_top);
  fill.system->restore_state(std::move(state));
  return fill;
}

SettledFill settle_lift(DemSystemState grown, const TankFillingSpec &t, const LinearContactLaw &material,
                        const DemSettings &settling_settings, const LiftLevels &levels, const std::string &where,
                        const std::function<void(double)> &progress, TankLayer &layer)
{
  // The same state (contacts and their history) in a system with gravity, the layers below free again.
  for (std::size_t b = 0; b < layer.first_body; ++b)
    if (grown.particles.inverse_mass[b] == 0.0)
      {
        grown.particles.inverse_mass[b] = 1.0 / grown.particles.mass[b];
        grown.particles.inverse_inertia[b] = 1.0 / grown.particles.inertia[b];
      }
  SettledFill fill = fill_system_from_state(std::move(grown), t, material, settling_settings, levels);
  DemSystem &settled = *fill.system;
  // The growth's last forces had no gravity and, with its contacts between fixed bodies skipped,
  // left those out of the lower lifts' resultants: the settling starts from forces evaluated afresh.
  settled.initialise_forces_at_next_step();
  // The growth ran at the step its grains' starting sizes allowed (a fraction of their final
  // ones, so a lighter body and a shorter critical step); grown, they allow a longer one. Without
  // this the settling and the pull-out after the fill ran at 0.61 of the critical step instead of
  // 0.8 (measured on the 6,000-cluster tank: dt 1.006e-5 s, critical 1.655e-5 s), 31 % more steps
  // than needed.
  settled.set_time_step(settling_settings.time_step_safety * settled.critical_time_step());
  settled.request_neighbour_rebuild();
  const std::uint64_t check_every = 200;
  for (;;)
    {
      settled.step();
      if (++layer.n_settling_steps % check_every != 0)
        continue;
      const double unbalanced = unbalanced_force_ratio(settled);
      if (unbalanced < t.equilibrium_unbalanced_ratio)
        break;
      if (layer.n_growth_steps + layer.n_settling_steps > t.max_steps_per_layer)
        {
          std::ostringstream message;
          message << where << "the fill has not settled under gravity after " << t.max_steps_per_layer
                  << " steps (unbalanced-force ratio " << unbalanced << ", asked below "
                  << t.equilibrium_unbalanced_ratio << ")";
          throw std::runtime_error(message.str());
        }
      if (progress)
        progress(std::min(1.0, static_cast<double>(layer.n_settling_steps) / 50000.0));
    }
  return fill;
}
} // namespace geohybrid::dem
