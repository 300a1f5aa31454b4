#pragma once
// `geohybrid pullout FILE.prm` with 'set mode = hybrid' (issue 6): the pull-out of mode = dem with
// particles only in a box round the anchorage and the rest of the tank a deal.II continuum, tied
// across an overlap band (coupling/hybrid_pullout.h).
//
// The input is dem mode's (Tank, Anchorage, Sheet, Soil, Filling, Pull, Output: 'Filling/number
// of particles' is what the whole tank would hold; the box gets its share by area, grains of the
// same size) plus subsection Hybrid (the box, the band, the coupling method) and the soil entries
// of subsection Continuum (soil model, E, nu, phi, c, psi, K0, local damping), read as fem mode
// reads them (parse_continuum_soil).
//
// The outputs are dem mode's curve files through PulloutOutput (pullout_curve.csv, the per-sheet
// curve, sheet_displacements.csv, sheet_tension.csv in the tank's frame, pullout_curve.png),
// parameters.prm, and summary.json last, with mode = hybrid, the box, the band, the coupling
// method and the steps; coupling_diagnostics.csv. Checkpoints as dem mode's ('checkpoint
// interval', 'stop after steps', --resume): filled_box.h5 once the box is full, then checkpoint.h5
// with the continuum's state too; a resumed run repeats the coupled set-up from the filled box and
// continues bit for bit. Not written (yet): dem mode's field outputs ('Output/field outputs at').
// One MPI rank, as dem mode.
#include "apps/pullout_input.h"

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace geohybrid::apps
{
/// Declares subsection Hybrid.
void declare_hybrid_parameters(dealii::ParameterHandler &prm);

/// Runs the hybrid pull-out of `in` (parsed from `prm`, the file named by `where`). Bad input
/// throws std::invalid_argument naming the file and the entry before anything is written.
/// One process: `communicator` must have one rank (MPI_COMM_SELF for an ensemble member). With
/// `check_only`, returns 0 before the first file is written (--print-parameters-hash).
int run_pullout_hybrid_mode(dealii::ParameterHandler &prm, const PullOutInput &in, const std::string &where,
                            bool resume, MPI_Comm communicator, bool check_only = false);
} // namespace geohybrid::apps
