#pragma once
// `geohybrid pullout FILE.prm` with 'set mode = fem': the pull-out test with the soil as a deal.II
// continuum (geostatic K0 soil, tension-only truss sheet with its Mohr-Coulomb interface, the
// clamp pulled), from the same input file as the DEM run, with either solver ('Continuum/solver'):
// explicit (fem/pullout_problem.h: central differences, the clamp at 'Pull/rate') or implicit
// (fem/quasi_static_pullout.h: quasi-static load steps, Newton, every curve point converged; the
// straight run-out only). A run the implicit solver cannot finish keeps its curve up to the last
// converged point and writes no summary.json.
//
// What the two modes share keeps its meaning: Tank/length and fill height are the soil's extent,
// Anchorage (simple run-out: L, H; wrap-around: L, D1, D2, B) the sheet, Sheet/J, areal mass and Interface/friction angle the
// truss and its interface, Soil/unit weight the density, Pull (rate, ramp, final displacement,
// record interval, tension profiles) the clamp's programme and the curve's points,
// Output/experimental T_max the plot's line. What only the continuum needs is in subsection
// Continuum (mesh, the sheet's node spacing, element degree, soil model with E, nu, phi, c, psi,
// K0, damping, the interface's stiffnesses and cohesion). DEM-only entries (Filling, Soil/Particle
// contact, wall friction, clamp offset, thickness, segment length, the sheet's contact
// stiffnesses) are read but unused; their doc strings say so. A wrap-around's two corners are
// laid as arcs of twice the node spacing inside the sharp corners (fem/pullout_problem.h).
//
// Runs on any number of MPI ranks (mpirun -np N geohybrid pullout FILE.prm); rank 0 writes every
// file, through the same PulloutOutput as the DEM mode.
#include "apps/pullout_input.h"

#include "fem/constitutive/soil_model.h"

#include <deal.II/base/parameter_handler.h>

#include <mpi.h>

#include <string>

namespace geohybrid::apps
{
/// Declares subsection Continuum (fem mode; its soil entries also hybrid mode), with the defaults
/// for sand 1.
void declare_continuum_parameters(dealii::ParameterHandler &prm);

/// The continuum's soil as subsection Continuum gives it, the part fem and hybrid modes share.
struct ContinuumSoilInput
{
  fem::SoilParameters soil; ///< 'soil model', E, nu, phi, c, psi
  double k0 = 0.0;          ///< 'K0'; 0 = the soil's default [-]
  double local_damping = 0.3; ///< 'local damping' [-]
};
/// Reads the soil entries of subsection Continuum (from the top level of `prm`).
ContinuumSoilInput parse_continuum_soil(dealii::ParameterHandler &prm);

/// Runs the continuum pull-out of `in` (parsed from `prm`, the file named by `where`) on the ranks
/// of `communicator`. Collective; bad input throws std::invalid_argument naming the file and the
/// entry on every rank before anything is written. With `check_only`, returns 0 there instead of
/// running (--print-parameters-hash).
int run_pullout_fem_mode(dealii::ParameterHandler &prm, const PullOutInput &in, const std::string &where,
                         MPI_Comm communicator, bool check_only = false);
} // namespace geohybrid::apps
