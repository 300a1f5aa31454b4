#pragma once
// What a tie is given and gives back at each evaluation of the coupling forces: when the forces
// act (TieTiming), and the sums of the forces applied to each side: Newton's third law for the
// coupling, checked by the diagnostics (the continuum's share is spread with shape functions that
// sum to one, so the two sums cancel to round-off).
#include "dem/conventions.h"

namespace geohybrid::coupling
{
/// When the coupling forces are evaluated: in the particles' force hook, both sides at t_{n+1}.
struct TieTiming
{
  /// How long the forces act before the next drift: dt, or dt / 2 at the first evaluation [s].
  double impulse_time = 0.0;
  /// How long the velocities have just moved both sides: dt, or 0 at the first evaluation (no
  /// drift yet) [s].
  double drift_time = 0.0;
};

struct CouplingForceSums
{
  dem::Vec2 on_particles = dem::Vec2::Zero();  ///< sum over the band particles [N/m]
  dem::Vec2 on_continuum = dem::Vec2::Zero();  ///< sum over the continuum's nodes [N/m]
};
} // namespace geohybrid::coupling
