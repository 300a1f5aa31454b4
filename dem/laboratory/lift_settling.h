#pragma once
// Step 3 of a lift (tank_filling.h): the grown lift and every grain below it freed, the whole
// fill settles under gravity, walls fixed, with local damping, until the unbalanced-force ratio
// falls below the spec's equilibrium ratio.
#include "dem/contact_law.h"
#include "dem/dem_system.h"
#include "lift_growth.h"
#include "tank_filling.h"

#include <functional>
#include <memory>
#include <string>

namespace geohybrid::dem
{
/// The fill as a system under gravity (`settling_settings`), with the tank's walls.
struct SettledFill
{
  std::unique_ptr<DemSystem> system;
  TankWalls walls;
};

/// The system of a fill's `state` (a grown lift's, or a settled one's from the lift cache): the
/// same construction, the tank's walls added, the state restored. Nothing is stepped.
SettledFill fill_system_from_state(DemSystemState state, const TankFillingSpec &spec, const LinearContactLaw &material,
                                   const DemSettings &settling_settings, const LiftLevels &levels);

/// Settles the `grown` state of a lift (grow_lift) under gravity, the grains of the lifts below
/// it free again, until equilibrium; counts the layer's n_settling_steps. `progress` (may be
/// empty) gets a fraction in [0, 1] that rises with the steps. Throws std::runtime_error prefixed
/// with `where` if the layer's growth and settling together exceed spec.max_steps_per_layer.
SettledFill settle_lift(DemSystemState grown, const TankFillingSpec &spec, const LinearContactLaw &material,
                        const DemSettings &settling_settings, const LiftLevels &levels, const std::string &where,
                        const std::function<void(double)> &progress, TankLayer &layer);
} // namespace geohybrid::dem
