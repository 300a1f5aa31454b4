#pragma once
// `geohybrid design FILE.prm`: the smallest B (or L) in a bracket whose runs reach a target T_max
// with a margin over the seeds' spread, mean - k std >= target (apps/design_definition.h), found
// by bisection (apps/design_bisection.h). Each value tried is a sweep over the seeds
// (apps/sweep_command.h) in its own directory OUTPUT/B_<value>/, so that its runs are kept,
// resumed and spread over the ranks as a sweep's are: the same command run again replays the
// bisection over the runs it finds finished and makes only the missing ones.
//
// The bracket's ends are run first; if the criterion does not change from unmet to met between
// them, the design says so and stops rather than bisecting. Results: design.csv, design.png and
// summary.json (apps/design_results.h); design.prm, the resolved design input, and
// design_base.prm, the base input with the design's overrides, which every run starts from.
#include <mpi.h>

#include <string>

namespace geohybrid::apps
{
/// Runs the design of `input_file` on the ranks of `communicator` (collective). Returns 0 if an
/// answer was found; 1 if not (the bracket does not bracket the target, or a run failed: the
/// summary says which). `resume` changes nothing: a design always continues the one in its
/// directory. Throws std::runtime_error for a bad design file (before anything is written) and
/// Interrupted after a signal.
int run_design_command(const std::string &input_file, bool resume, MPI_Comm communicator = MPI_COMM_WORLD);
} // namespace geohybrid::apps
