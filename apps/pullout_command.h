#pragma once
// `geohybrid pullout FILE.prm`: a pull-out test of a geosynthetic anchored in the INSA tank
// (reference paper, sections 2.2 and 4.3): simple run-out or wrap-around, head tension against
// head displacement. 'mode = dem' runs the discrete model (dem/laboratory/pullout_tank.h,
// apps/pullout_dem_mode.h), 'mode = fem' the continuum (fem/pullout_problem.h,
// apps/pullout_fem_mode.h) from the same file, also under mpirun; 'mode = hybrid' the two coupled
// (coupling/hybrid_pullout.h, apps/pullout_hybrid_mode.h), in one process. The input is read in
// apps/pullout_input.h.
#include <deal.II/base/parameter_handler.h>

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace geohybrid::apps
{
/// Declares every entry of the input, with its default, bounds and unit (pullout_input.cc).
void declare_pullout_parameters(dealii::ParameterHandler &prm);
/// Entries set after the input file is read, as (path, value): ("Filling/seed", "4").
using ParameterOverrides = std::vector<std::pair<std::string, std::string>>;
int run_pullout_command(const std::string &input_file, bool resume, const ParameterOverrides &overrides = {});
/// The same on the ranks of `communicator` (the other form takes MPI_COMM_WORLD): mode = fem
/// distributes its continuum over them; dem and hybrid modes run in one process and refuse a
/// communicator of several ranks (an ensemble member runs on MPI_COMM_SELF: pullout_seeds.h).
int run_pullout_command(const std::string &input_file, bool resume, MPI_Comm communicator,
                        const ParameterOverrides &overrides = {});
/// `geohybrid pullout FILE --print-parameters-hash`: reads and checks FILE as a run of it would,
/// refusing what the run refuses before its first file, writes nothing, and returns the
/// parameters_hash its summary.json would hold (apps/parameters_hash.h). Throws as the run would.
/// With `overrides`, the input as a run with them reads it (`geohybrid design` checks its ends so).
std::string check_pullout_input(const std::string &input_file, MPI_Comm communicator = MPI_COMM_WORLD,
                                const ParameterOverrides &overrides = {});
} // namespace geohybrid::apps
