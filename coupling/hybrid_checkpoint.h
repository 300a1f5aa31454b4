#pragma once
// Checkpoints of a hybrid pull-out: the continuum's state (fem::ExplicitSolverState, its sheet's
// included) as named arrays of a dem::CommandState, which the DEM checkpoint file stores beside
// the particles' state (dem/io/checkpoint.h). Keys start with "continuum_"; doubles round-trip
// exactly, so a resumed run continues bit for bit.
#include "coupling/coupled_stepper.h"
#include "dem/io/checkpoint.h"
#include "fem/explicit_solver.h"

namespace geohybrid::coupling
{
void store_continuum_state(const fem::ExplicitSolverState &state, dem::CommandState &command);
/// The state stored by store_continuum_state. Throws std::runtime_error naming the key if one is
/// missing or of the wrong size.
fem::ExplicitSolverState restore_continuum_state(const dem::CommandState &command);

/// A multi-rate stepper's window phase (key "coupled_window_phase"); nothing in lockstep, whose
/// window is always empty.
void store_window_phase(const CoupledStepper &stepper, dem::CommandState &command);
/// Gives `stepper` the phase stored by store_window_phase, if any. Throws std::invalid_argument
/// if it does not fit the stepper.
void restore_window_phase(const dem::CommandState &command, CoupledStepper &stepper);
} // namespace geohybrid::coupling
