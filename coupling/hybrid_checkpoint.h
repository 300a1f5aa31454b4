#pragma once
// Checkpoints of a hybrid pull-out: the continuum's state (fem::ExplicitSolverState, its sheet's
// included) as named arrays of a dem::CommandState, which the DEM checkpoint file stores beside
// the particles' state (dem/io/checkpoint.h). Keys start with "continuum_"; doubles round-trip
// exactly, so a resumed run continues bit for bit.
#include "dem/io/checkpoint.h"
#include "fem/explicit_solver.h"

namespace geohybrid::coupling
{
void store_continuum_state(const fem::ExplicitSolverState &state, dem::CommandState &command);
/// The state stored by store_continuum_state. Throws std::runtime_error naming the key if one is
/// missing or of the wrong size.
fem::ExplicitSolverState restore_continuum_state(const dem::CommandState &command);
} // namespace geohybrid::coupling
