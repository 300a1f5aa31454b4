#include "pullout_seeds.h"

#include "compare_command.h"
#include "interrupt.h"
#include "plot.h"
#include "pullout_command.h"
#include "pullout_input.h"
#include "rank_error.h"
#include "run_directory.h"
#include "spread.h"

#include "dem/io/checked_output.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace geohybrid::apps
{
int run_pullout_seeds(const std::string &input_file, int n_seeds, MPI_Comm communicator, bool resume)
{
  const bool with_mpi = dealii::Utilities::MPI::job_supports_mpi();
  const unsigned int rank = with_mpi ? dealii::Utilities::MPI::this_mpi_process(communicator) : 0;
  const unsigned int n_ranks = with_mpi ? dealii::Utilities::MPI::n_mpi_processes(communicator) : 1;
  const auto barrier = [&] {
    if (with_mpi)
      MPI_Barrier(communicator);
  };
  if (n_seeds < 1)
    throw std::invalid_argument("geohybrid pullout: '--seeds' = " + std::to_string(n_seeds) +
                                " must be at least 1");
  const auto start_time = std::chrono::steady_clock::now();
  // The input as the single runs read it: its output directory and first seed.
  dealii::ParameterHandler prm;
  declare_pullout_parameters(prm);
  parse_input_file(prm, input_file);
  prm.enter_subsection("Filling");
  const long first_seed = prm.get_integer("seed");
  const long n_particles = prm.get_integer("number of particles");
  prm.leave_subsection();
  const std::string mode = prm.get("mode");
  // Bad input (geometry that does not fit the tank, a bad entry) is refused before the parent
  // directory is written, as a single run refuses it before its own.
  parse_pullout(prm, input_file, mode != "fem");
  const std::filesystem::path out(prm.get("output directory"));
  // Rank 0 prepares the directory; its refusal (another run's files there) stops every rank.
  on_rank_zero(communicator, [&] {
    prepare_output_directory(out.string(), resume);
    write_resolved_parameters(prm, out);
  });

  // This rank's seeds, each on MPI_COMM_SELF; a failure or a signal (interrupt.h: mpirun passes
  // it to every rank) is kept until every rank is done, so that no rank waits for one that has
  // stopped. A resumed ensemble keeps the seeds that finished (their summary.json) and resumes
  // the others from their checkpoints.
  std::string failure, seeds, stopped;
  int signal = 0;
  bool resumable = true;
  for (int k = 0; k < n_seeds; ++k)
    {
      const std::string seed = std::to_string(first_seed + k);
      seeds += (k ? ", " : "") + seed;
      if (static_cast<unsigned int>(k) % n_ranks != rank || !failure.empty() || signal != 0)
        continue;
      const std::filesystem::path directory = out / ("seed_" + seed);
      if (resume && std::filesystem::exists(directory / "summary.json"))
        continue;
      if ((signal = interrupt_signal()) != 0) // came between two seeds: start no other
        continue;
      std::cout << "geohybrid pullout: seed " << seed << " (" << k + 1 << " of " << n_seeds << ") in "
                << directory.string() << (n_ranks > 1 ? " on rank " + std::to_string(rank) : std::string()) << std::endl;
      try
        {
          run_pullout_command(input_file, resume, with_mpi ? MPI_COMM_SELF : communicator,
                              {{"output directory", directory.string()}, {"Filling/seed", seed}});
        }
      catch (const Interrupted &e)
        {
          signal = e.signal();
          resumable = e.resumable();
          stopped = "seed " + seed + " stopped " + e.what() + "; ";
        }
      catch (const std::exception &e)
        {
          failure = "seed " + seed + ": " + e.what();
        }
    }
  const unsigned int n_failed =
    with_mpi ? dealii::Utilities::MPI::sum(failure.empty() ? 0u : 1u, communicator) : (failure.empty() ? 0u : 1u);
  if (with_mpi)
    {
      signal = dealii::Utilities::MPI::max(signal, communicator);
      resumable = dealii::Utilities::MPI::min(resumable ? 1u : 0u, communicator) == 1u;
    }
  if (signal != 0 && n_failed == 0)
    throw Interrupted(signal,
                      "before the ensemble's end: " + stopped + "the seeds that finished are kept in " +
                        out.string() + ", no summary.json there",
                      resumable);
  if (!failure.empty())
    throw RankError("geohybrid pullout --seeds: " + failure); // this rank's own: it prints it
  if (n_failed > 0)
    throw std::runtime_error("geohybrid pullout --seeds: the run of a seed on another rank failed (" +
                             std::to_string(n_failed) + " rank(s)); see its message");
  barrier();
  if (rank != 0)
    return 0;
  std::vector<PulloutRunRecord> runs;
  for (int k = 0; k < n_seeds; ++k)
    runs.push_back(read_pullout_run(out / ("seed_" + std::to_string(first_seed + k))));

  // The curves, row by row.
  const std::size_t n_rows = runs.front().curve.size();
  for (const PulloutRunRecord &run : runs)
    if (run.curve.size() != n_rows)
      throw std::runtime_error("geohybrid pullout --seeds: " + (run.directory / "pullout_curve.csv").string() + " has " +
                               std::to_string(run.curve.size()) + " rows, " +
                               (runs.front().directory / "pullout_curve.csv").string() + " " +
                               std::to_string(n_rows));
  std::ofstream curve(out / "pullout_curve.csv");
  curve << "head_displacement_m,head_tension_kN_per_m,head_tension_min_kN_per_m,head_tension_max_kN_per_m,"
           "head_tension_std_kN_per_m\n";
  for (std::size_t r = 0; r < n_rows; ++r)
    {
      // Each run records at the first step past the same displacement: they differ by less than
      // one step's travel, so the row's displacement is their mean.
      std::vector<double> u, T;
      for (const PulloutRunRecord &run : runs)
        {
          u.push_back(run.curve[r][0]);
          T.push_back(run.curve[r][1]);
        }
      const Spread s = spread_of(T);
      curve << std::setprecision(10) << spread_of(u).mean << ',' << s.mean << ',' << s.min << ',' << s.max << ','
            << s.std << '\n';
    }
  dem::close_checked(curve, out / "pullout_curve.csv");

  std::vector<PlotSeries> series{{out / "pullout_curve.csv", 1, 3, "min - max over the seeds", 1e3, 1.0,
                                  "filledcurves fs transparent solid 0.25 noborder", {4}},
                                 {out / "pullout_curve.csv", 1, 2, "mean", 1e3, 1.0, "lines lw 3", {}}};
  for (const PulloutRunRecord &run : runs)
    series.push_back({run.directory / "pullout_curve.csv", 1, 2, "seed " + run.directory.filename().string().substr(5), 1e3, 1.0,
                      "lines lw 1 dt 2", {}});
  plot_png(out / "pullout_curve.png", "Pull-out, head tension over " + std::to_string(n_seeds) + " seeds",
           {{"head displacement [mm]", "head tension [kN/m]", series, ""}});

  std::vector<double> T_max;
  for (const PulloutRunRecord &run : runs)
    T_max.push_back(run.max_head_tension_kN);
  const Spread t = spread_of(T_max);
  Summary summary;
  summary.set("command", "pullout --seeds");
  summary.set("mode", mode);
  summary.set("T_max_kN_per_m", t.mean);
  summary.set("T_max_std_kN_per_m", t.std);
  summary.set("T_max_min_kN_per_m", t.min);
  summary.set("T_max_max_kN_per_m", t.max);
  summary.set("seeds", seeds);
  summary.set("n_seeds", static_cast<double>(n_seeds));
  summary.set("n_particles", static_cast<double>(n_particles));
  summary.set("n_ranks", static_cast<double>(n_ranks));
  summary.set("wall_time_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count());
  std::vector<std::string> warnings; // each seed's, as its run printed them
  for (const PulloutRunRecord &run : runs)
    for (const std::string &w : run.warnings)
      warnings.push_back(run.directory.filename().string() + ": " + w);
  summary.set("warnings", warnings);
  summary.write(out / "summary.json");
  std::cout << "geohybrid pullout: T_max = " << t.mean << " +/- " << t.std << " kN/m over seeds " << seeds
            << "\nresults in " << out.string() << '\n';
  return 0;
}
} // namespace geohybrid::apps
