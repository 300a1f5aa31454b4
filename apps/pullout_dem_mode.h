#pragma once
// `geohybrid pullout FILE.prm` with 'set mode = dem' (the default): the tank filled in layers
// with particles, the sheet laid at its depth on the lift below it (dem/laboratory/pullout_tank.h);
// then the clamp, outside the front wall, pulls the sheet horizontally at a set rate and the run
// records the head tension (the clamp's reaction) against the head displacement.
//
// Before pulling, the run measures the normal stress the soil applies to the sheet (on its top
// and bottom faces, and Love-Weber in a band of soil above it) and reports it against gamma H:
// side-wall friction carries part of the weight, and the sheet lies a little above its nominal
// level (on the grains of the lift below), so sigma_v < gamma H is expected.
//
// Besides the files every mode writes, the soil's fields at 'Output/field outputs at'
// (pullout_field_output.h) and the head tension's parts (pullout_forces_output.h).
//
// Long runs: checkpoint.h5 holds the whole run (the system, the tank's description, the pull's
// progress, every row recorded, the field outputs' schedule and reference); it is written when
// the tank is full (and copied to filled_tank.h5), every 'checkpoint interval' s of wall time and
// at the end. `geohybrid pullout FILE --resume` continues from it, bit for bit; without one (the
// run stopped while filling) it fills the tank again and says so.
#include "apps/pullout_input.h"

#include <deal.II/base/parameter_handler.h>

#include <mpi.h>

#include <string>

namespace geohybrid::apps
{
/// mode = dem: the tank filled with particles, then pulled. With `resume`, the tank and the pull
/// continue from OUTPUT/checkpoint.h5: the result files are those of a run that never stopped,
/// bit for bit. With `check_only`, returns before the first file is written. Refuses a
/// `communicator` of several ranks (the particles run in one process, on its threads).
int run_pullout_dem_mode(dealii::ParameterHandler &prm, const PullOutInput &in, const std::string &where, bool resume,
                         MPI_Comm communicator, bool check_only);
} // namespace geohybrid::apps
