#pragma once
// Step 1 of a lift (tank_filling.h): its grains placed at random, at their starting sizes,
// between the lift's bottom level and its lid, clear of the grains already there and off the
// sheets laid so far. A sheet standing across the lift (a wrap-around's held return) walls it
// into compartments no grain passes between; each gets the share of the grains that fills it at
// the lift's target porosity, placed in it.
#include "dem/particles.h"
#include "dem/spar_sheet.h"
#include "sample_preparation.h"
#include "tank_filling.h"

#include <string>
#include <vector>

namespace geohybrid::dem
{
/// Adds the grains of `radii` (the lift's starting sizes) to `particles` in the
/// space [0, spec.width] x [layer.bottom, lid_level], by REDF's random placement with `redf`'s
/// seed, each compartment the `laid` sheets wall off getting its share, then moves those a sheet
/// would cut off it. A placement REDF refuses throws std::invalid_argument prefixed with `where`.
void place_lift_grains(const TankFillingSpec &spec, const RedfSpec &redf, const std::vector<double> &radii,
                       const std::vector<SparSheet> &laid, const TankLayer &layer, double lid_level,
                       const std::string &where, ParticleSet &particles);
} // namespace geohybrid::dem
