#pragma once
// `geohybrid pullout FILE.prm --seeds N`: the same pull-out test on N random fills, as the paper
// averages three samples (section 4.3). Run k (k = 0 .. N-1) uses the seed s + k, s being
// 'Filling/seed' of the input, and writes its full output contract in OUTPUT/seed_<s + k>/.
// The output directory then holds the curve averaged over the runs, row by row (every run records
// at the same head displacements: 'Pull/record interval'):
//
//   pullout_curve.csv   head_displacement_m,head_tension_kN_per_m (the mean over the seeds),
//                       head_tension_min_kN_per_m, head_tension_max_kN_per_m,
//                       head_tension_std_kN_per_m (sample standard deviation, n - 1; 0 for one seed)
//   pullout_curve.png   the mean curve, the band between min and max, and each seed's curve
//   parameters.prm, summary.json (written last): T_max_kN_per_m (the mean of the seeds' T_max),
//                       T_max_std_kN_per_m, T_max_min/max_kN_per_m, seeds, n_seeds, n_particles,
//                       wall_time_s, mode, n_ranks
//
// Under mpirun the seeds are spread over the ranks (an ensemble, the brief's "runs spread over
// ranks"): rank r runs the seeds k = r, r + P, ... on MPI_COMM_SELF (dem and hybrid runs are one
// process each; a fem run then keeps to its rank), and rank 0 averages once all are done. Every
// seed's files are those of the serial run, bit for bit: a run does not depend on where it ran.
//
// A SIGINT or SIGTERM (apps/interrupt.h; mpirun passes it to every rank) stops each rank's seed
// as a single run stops, and no other seed starts; every rank then throws Interrupted. `--seeds N
// --resume` continues: the seeds with a summary.json are kept, the others resumed (or started).
#include <mpi.h>

#include <string>

namespace geohybrid::apps
{
/// Runs the N seeds, one after the other on each rank of `communicator`, and writes the averaged
/// results (rank 0). Throws std::invalid_argument for n_seeds < 1 (before anything is written)
/// and what the single runs throw (on every rank: a rank whose run failed gives its message, the
/// others name the failed seeds); std::runtime_error if the runs' curves do not have the same rows;
/// Interrupted after a signal. With `resume`, as above. Collective.
int run_pullout_seeds(const std::string &input_file, int n_seeds, MPI_Comm communicator = MPI_COMM_WORLD,
                      bool resume = false);
} // namespace geohybrid::apps
