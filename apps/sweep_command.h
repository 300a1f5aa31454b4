#pragma once
// `geohybrid sweep FILE.prm`: one pull-out per member of a sweep (apps/sweep_definition.h), each a
// normal `geohybrid pullout` run of the base input with the member's values, in its own
// directory OUTPUT/<member>/ (the member's name: its entries and values, "B_0.25_seed_2"); then
// sweep.csv and sweep.png (apps/sweep_results.h), and sweep.prm, the sweep's resolved input.
//
// Resumable member by member: a sweep run again keeps each member whose summary.json holds the
// member's parameters_hash, resumes one with a checkpoint (dem and hybrid modes), starts again
// one that stopped without (its own files, of the same input, are replaced) and runs the others.
// A member whose directory holds another run's files (the sweep changed under it) fails, naming
// them, unless --overwrite is given: then every member not finished with its own hash is run
// afresh.
//
// Under mpirun the members are dealt to the ranks, member k to rank k mod P, each rank running
// its members one after the other on MPI_COMM_SELF (fem-mode members too); rank 0 writes the
// table once every rank is done. A member that fails is reported on the terminal at once and in
// sweep.csv; the others go on, and the exit status is then 1. A SIGINT or SIGTERM stops the
// running members as a pull-out stops (a checkpoint to resume from); no other member starts,
// sweep.csv lists what finished, and the same command continues the sweep.
#include "apps/sweep_definition.h"
#include "apps/sweep_results.h"

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace geohybrid::apps
{
/// Runs the sweep of `input_file` on the ranks of `communicator` (collective). Returns 0 if every
/// member finished, 1 if one failed. `resume` is accepted and changes nothing: a sweep always
/// continues the one in its directory. Throws std::runtime_error for a bad sweep file (before
/// anything is written) and Interrupted after a signal.
int run_sweep_command(const std::string &input_file, bool resume, MPI_Comm communicator = MPI_COMM_WORLD);

/// `geohybrid sweep FILE.prm --print-parameters-hash`: each member's name and the parameters_hash
/// its summary.json would hold, in the sweep's order, each member's input checked as its run
/// would check it (check_pullout_input); nothing written. Throws as run_sweep_command, or naming
/// the member whose input is refused.
std::vector<std::pair<std::string, std::string>> sweep_member_hashes(const std::string &input_file);

struct SweepRun
{
  int status = 0;                      ///< 0 if every member finished, 1 if one failed (every rank)
  std::vector<MemberOutcome> outcomes; ///< per member, in the sweep's order: on rank 0 only
};

/// The sweep of `sweep` (made by parse_sweep or make_sweep from `prm`, which is written as
/// sweep.prm) on the ranks of `communicator` (collective): what run_sweep_command does once its
/// file is read. `geohybrid design` runs each of its steps so.
SweepRun run_sweep(const SweepDefinition &sweep, const dealii::ParameterHandler &prm, MPI_Comm communicator);
} // namespace geohybrid::apps
