#pragma once
// The hybrid pull-out's particle box (hybrid_pullout.h): where in the tank the particles are, and
// the lifts the box is filled in.
//
// The box reaches `margin` below the sheet (or down to the base) in whole lifts, and from the
// sheet up to `margin` above its highest part rounded up to whole lifts (or to the surface). As
// in dem mode (dem/laboratory/pullout_tank.h), the sheet lies on a lift boundary, and so does a
// wrap-around's upper part, laid on the lift whose top is at its level. REDF refuses a lift
// thinner than five times its largest grain (dem/laboratory/tank_filling.h), and the grains' size
// is set by the whole tank's particles per area ('Filling/number of particles'), not by the box.
// - Given lifts (HybridRegionSpec::lift_thickness > 0): at most that thick, the margin below the
//   sheet divided evenly, as always; checked against the grains.
// - Automatic lifts (0): the given rule at the former default, 0.05 m, when the fill takes its
//   grains, so that an input that ran keeps its numbers; otherwise the thinnest aligned lifts at
//   least automatic_lift_room x 5 largest grains thick: the margin below divided into fewer lifts;
//   failing that, lifts of their own thickness in each part of the box (the margin below, a
//   wrap-around's rise, the margin above: the margin exactly); failing that, whole lifts reaching
//   past the margin, the box then further down (the margin is a least distance).
#include "dem/laboratory/pullout_tank.h"

#include <cstddef>
#include <string>

namespace geohybrid::coupling
{
struct HybridPullOutSpec;

/// The particle box in the tank's frame, and which of its sides the continuum shares [m].
struct ParticleBox
{
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  bool left_shared = false, bottom_shared = false, top_shared = false;
  std::size_t n_lifts = 0;
  double lift_thickness = 0.0; ///< of its lifts, the thinnest if they differ (box_tank.filling.layer_tops) [m]
  std::size_t n_particles = 0; ///< the whole tank's number in proportion to the box's area
  /// The largest grain its fill will make (dem::largest_particle_extent), at most a fifth of a lift [m].
  double largest_grain = 0.0;
  /// The DEM tank spec of the box, in the box's frame (its origin at (x0, y0)).
  dem::PullOutTankSpec box_tank;
};

/// Automatic lifts are at least this many times five largest grains of the box's draw: each
/// lift's own draw scatters round the box's by about 1 / (2 sqrt(its particles)), 2 % at 100
/// particles a lift, and the 5 % covers that.
inline constexpr double automatic_lift_room = 1.05;
/// The lifts the automatic choice tries first, the former default: at most this thick [m].
inline constexpr double automatic_lift_cap = 0.05;

/// Throws std::invalid_argument naming 'DEM region margin' if the box would hold the whole tank
/// (use mode = dem) or leave a sliver of continuum thinner than the band, as
/// HybridPullOutSpec::validate; naming 'Hybrid/lift thickness' and 'Filling/number of particles',
/// with values that would work, if its lifts are thinner than five of its largest grains.
ParticleBox particle_box(const HybridPullOutSpec &spec, const std::string &where);
} // namespace geohybrid::coupling
