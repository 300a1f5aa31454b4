#pragma once
// The sums of the coupling forces last applied to each side: Newton's third law for the
// coupling, checked by the diagnostics (the continuum's share is spread with shape functions that
// sum to one, so the two sums cancel to round-off).
#include "dem/conventions.h"

namespace geohybrid::coupling
{
struct CouplingForceSums
{
  dem::Vec2 on_particles = dem::Vec2::Zero();  ///< sum over the band particles [N/m]
  dem::Vec2 on_continuum = dem::Vec2::Zero();  ///< sum over the continuum's nodes [N/m]
};
} // namespace geohybrid::coupling
