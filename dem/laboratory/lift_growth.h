#pragma once
// Step 2 of a lift (tank_filling.h): without gravity, under a temporary lid, the lift's grains
// grow by REDF until the slab between the lift's two levels is at its target porosity, the
// growth friction lowered while the lift is jammed (the lid's stress above the growth stress).
// The grains below the slab are fixed meanwhile; the sheets laid so far stay where they lie.
#include "dem/contact_law.h"
#include "dem/dem_system.h"
#include "dem/particles.h"
#include "dem/spar_sheet.h"
#include "sample_preparation.h"
#include "tank_filling.h"

#include <functional>
#include <string>
#include <vector>

namespace geohybrid::dem
{
/// Where a lift grows: its lid and the front wall's slot cut so far (none: slot_top == slot_bottom).
struct LiftLevels
{
  double lid = 0.0, slot_bottom = 0.0, slot_top = 0.0; ///< [m]
};

/// Grows the grains [layer.first_body, layer.first_body + layer.n_bodies) of `particles` (placed
/// by place_lift_grains) under the lid, the `laid` sheets in place, with `growth_settings` (those
/// of the fill without gravity). Records the layer's porosity_grown, growth_friction_deg and
/// n_growth_steps. Returns the grown system's state with the material friction restored and the
/// lid parked above the fill, ready to settle (lift_settling.h). `progress` (may be empty) gets
/// the growth's fraction done; a growth that fails throws std::runtime_error prefixed with `where`.
DemSystemState grow_lift(ParticleSet particles, const TankFillingSpec &spec, const RedfSpec &redf,
                         const LinearContactLaw &material, const DemSettings &growth_settings,
                         const std::vector<SparSheet> &laid, const LiftLevels &levels, const std::string &where,
                         const std::function<void(double)> &progress, TankLayer &layer);
} // namespace geohybrid::dem
