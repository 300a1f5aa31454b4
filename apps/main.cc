// geohybrid: one executable, one subcommand per kind of run.
//
//   geohybrid dem FILE.prm                 a DEM scene (deposition, impacts, any walls)
//   geohybrid dem FILE.prm --resume        continue it from its last checkpoint
//   geohybrid biaxial FILE.prm             REDF samples in biaxial compression, friction angle, E
//   geohybrid calibrate FILE.prm           contact friction, kn, ks/kn fitted to target phi', E (nu)
//   geohybrid pullout FILE.prm             pull-out of a geosynthetic anchored in the INSA tank
//   geohybrid pullout FILE.prm --seeds N   the same on N fills (seeds s, s+1, ...), averaged
//   geohybrid pullout FILE.prm --print-parameters-hash   the input checked, its physics' hash printed
//   geohybrid sweep FILE.prm --print-parameters-hash     the same for each member of the sweep
//   mpirun -np N geohybrid pullout FILE.prm  the same with 'mode = fem' on N MPI ranks
//   ('mode = hybrid': particles round the sheet, the continuum elsewhere; one process)
//   geohybrid coupling-test FILE.prm       the coupling's patch, wave and energy benchmarks for one method
//   geohybrid compare DIR1 DIR2 ... [--output FILE.png]   pull-out curves of result directories in one PNG
//   geohybrid sweep FILE.prm               pull-outs over a list or grid of values, resumable, T_max and its spread
//   mpirun -np N geohybrid sweep FILE.prm  the same, the members dealt to the ranks
//   geohybrid design FILE.prm              the smallest B (or L) whose T_max reaches a target, by bisection over sweeps
//   geohybrid report DIR1 DIR2 ... [--output FILE.html]   one self-contained HTML page of results
//   geohybrid COMMAND --print-parameters   every parameter of COMMAND with default, unit, doc
//
// Input files are read with deal.II's ParameterHandler (.prm or .json). Errors in the input stop
// the run before anything is written, with a message naming the file and the parameter.
#include "apps/biaxial_command.h"
#include "apps/calibrate_command.h"
#include "apps/compare_command.h"
#include "apps/coupling_test_command.h"
#include "apps/design_command.h"
#include "apps/design_definition.h"
#include "apps/dem_command.h"
#include "apps/interrupt.h"
#include "apps/output_guard.h"
#include "apps/pullout_command.h"
#include "apps/pullout_seeds.h"
#include "apps/rank_error.h"
#include "apps/report_command.h"
#include "apps/sweep_command.h"
#include "apps/sweep_definition.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace
{
struct Command
{
  const char *summary;
  std::function<void(dealii::ParameterHandler &)> declare;
  std::function<int(const std::string &, bool)> run; ///< (input file, resume)
};

const std::map<std::string, Command> &commands()
{
  static const std::map<std::string, Command> table{
    {"dem", {"run a DEM scene: deposition of discs or clusters in a box, or particles from CSV",
             geohybrid::apps::declare_dem_parameters, geohybrid::apps::run_dem_command}},
    {"biaxial", {"biaxial compression of REDF samples at several confining stresses (calibration test)",
                 geohybrid::apps::declare_biaxial_parameters, geohybrid::apps::run_biaxial_command}},
    {"calibrate", {"fit contact friction, kn and ks/kn to a target friction angle, E (and nu) by biaxial runs",
                   geohybrid::apps::declare_calibrate_parameters, geohybrid::apps::run_calibrate_command}},
    {"pullout", {"pull-out test of a geosynthetic in the INSA tank: simple run-out or wrap-around (mode = dem, fem or hybrid)",
                 geohybrid::apps::declare_pullout_parameters,
                 [](const std::string &file, bool resume) { return geohybrid::apps::run_pullout_command(file, resume); }}},
    {"sweep", {"pull-outs of a base input over a list or grid of values, one directory each, resumable; sweep.csv and "
               "sweep.png of T_max and its spread over the seeds (under mpirun the members spread over the ranks)",
               geohybrid::apps::declare_sweep_parameters,
               [](const std::string &file, bool resume) { return geohybrid::apps::run_sweep_command(file, resume); }}},
    {"design", {"the smallest B (wrap-around) or L in a bracket whose mean - k std of T_max over the seeds reaches a "
                "target, by bisection over sweeps (resumable; under mpirun each sweep's runs spread over the ranks); "
                "design.csv, design.png, summary.json",
                geohybrid::apps::declare_design_parameters,
                [](const std::string &file, bool resume) { return geohybrid::apps::run_design_command(file, resume); }}},
    {"coupling-test", {"DEM-FEM coupling benchmarks for one method: ghost forces, reflected wave energy, energy drift",
                       geohybrid::apps::declare_coupling_test_parameters, geohybrid::apps::run_coupling_test_command}},
  };
  return table;
}

/// This invocation as a shell command (arguments quoted where needed), with --resume (and then
/// without --overwrite) or without (and then with --overwrite),
/// under `mpirun -np P` if it runs on P > 1 ranks.
std::string command_line(int argc, char **argv, bool resume)
{
  const auto quoted = [](const std::string &word) {
    if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%") ==
                           std::string::npos)
      return word;
    std::string text = "'";
    for (const char c : word)
      text += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return text + "'";
  };
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  std::string line = n_ranks > 1 ? "mpirun -np " + std::to_string(n_ranks) + " " : "";
  line += quoted(argv[0]);
  for (int k = 1; k < argc; ++k)
    if (std::strcmp(argv[k], "--resume") && (!resume || std::strcmp(argv[k], "--overwrite")))
      line += " " + quoted(argv[k]);
  // Run again from the start, the directory holds this run's files: --overwrite replaces them.
  const bool has_overwrite = std::find_if(argv + 1, argv + argc, [](const char *a) { return !std::strcmp(a, "--overwrite"); }) != argv + argc;
  return resume ? line + " --resume" : has_overwrite ? line : line + " --overwrite";
}

void print_usage(std::ostream &out)
{
  out << "geohybrid: 2D DEM of soil coupled with a deal.II continuum, for geosynthetic anchorages\n\n"
         "usage: geohybrid COMMAND FILE.prm|FILE.json [--resume | --overwrite]\n"
         "       geohybrid COMMAND --print-parameters   (every parameter, default, unit and meaning)\n"
         "       geohybrid pullout FILE.prm --seeds N [--resume]   (N fills, seeds s, s+1, ...; the averaged curve; under mpirun spread over the ranks)\n"
         "       geohybrid pullout FILE.prm --print-parameters-hash   (FILE checked as a run would, nothing\n"
         "                                              written; the hash its summary.json would hold)\n"
         "       geohybrid sweep FILE.prm --print-parameters-hash   (each member's name and hash, nothing written)\n"
         "       geohybrid compare DIR1 DIR2 ... [--output FILE.png]   (pull-out curves in one PNG)\n"
         "       geohybrid report DIR1 DIR2 ... [--output FILE.html]   (one self-contained HTML page of the results)\n"
         "       geohybrid --help\n\n"
         "--resume continues the run of FILE from its last checkpoint, OUTPUT/checkpoint.h5\n"
         "(written every 'Simulation/checkpoint interval' seconds, at the end, and when SIGINT or\n"
         "SIGTERM stops a dem or pullout run: Ctrl-C); the end time may have been raised meanwhile.\n"
         "With --seeds N it keeps the seeds that finished and continues the others. The input must be\n"
         "the checkpointed run's: only the run-control entries may change ('output directory',\n"
         "'threads', 'checkpoint interval', 'stop after steps'; for dem also 'Simulation/end time',\n"
         "'output interval' and 'snapshot interval'; while the pull has not started, as with\n"
         "filled_tank.h5 copied as checkpoint.h5, also 'Pull/rate', 'Pull/grain local damping' and\n"
         "'Pull/sheet local damping'); any other difference is refused, naming it.\n"
         "A run into an output directory that holds another run's files is refused; --overwrite\n"
         "removes those files first (only the files geohybrid writes: yours stay).\n\ncommands:\n";
  for (const auto &[name, command] : commands())
    out << "  " << name << std::string(15 - std::min<std::size_t>(14, name.size()), ' ') << command.summary << '\n';
}
} // namespace

int main(int argc, char **argv)
{
  // MPI (and PETSc) for the continuum, which runs on the ranks of mpirun; a plain start is one
  // rank. One thread per rank for deal.II's own tasks (the DEM's OpenMP threads are its own).
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))
    {
      print_usage(std::cout);
      return argc < 2 ? 1 : 0;
    }
  // compare and report read result directories, not an input file: their own arguments.
  if (!std::strcmp(argv[1], "compare") || !std::strcmp(argv[1], "report"))
    try
      {
        const std::vector<std::string> arguments(argv + 2, argv + argc);
        return !std::strcmp(argv[1], "compare") ? geohybrid::apps::run_compare_command(arguments)
                                                : geohybrid::apps::run_report_command(arguments);
      }
    catch (const std::exception &e)
      {
        std::cerr << "geohybrid: error: " << e.what() << '\n';
        return 1;
      }
  const auto found = commands().find(argv[1]);
  if (found == commands().end())
    {
      std::cerr << "geohybrid: unknown command '" << argv[1] << "'\n\n";
      print_usage(std::cerr);
      return 2;
    }
  // The arguments after the command: --print-parameters alone, or one input file and --resume.
  std::string input_file;
  bool resume = false, overwrite = false, print_parameters = false, print_hash = false;
  int n_seeds = 0; // pullout --seeds N
  for (int k = 2; k < argc; ++k)
    {
      const std::string argument = argv[k];
      if (argument == "--resume" && !resume)
        resume = true;
      else if (argument == "--overwrite" && !overwrite)
        overwrite = true;
      else if (argument == "--seeds" && !std::strcmp(argv[1], "pullout") && n_seeds == 0)
        {
          char *end = nullptr;
          const long n = k + 1 < argc ? std::strtol(argv[k + 1], &end, 10) : 0;
          if (k + 1 >= argc || *end != '\0' || n < 1 || n > 1000)
            {
              std::cerr << "geohybrid pullout: '--seeds' needs a number of seeds in [1, 1000]\n";
              return 2;
            }
          n_seeds = static_cast<int>(n);
          ++k;
        }
      else if (argument == "--print-parameters" && !print_parameters)
        print_parameters = true;
      else if (argument == "--print-parameters-hash" &&
               (!std::strcmp(argv[1], "pullout") || !std::strcmp(argv[1], "sweep")) && !print_hash)
        print_hash = true;
      else if (argument.rfind("--", 0) != 0 && input_file.empty())
        input_file = argument;
      else
        {
          std::cerr << "geohybrid " << argv[1] << ": unexpected argument '" << argument << "'\n\n";
          print_usage(std::cerr);
          return 2;
        }
    }
  if (print_parameters ? (resume || overwrite || n_seeds > 0 || print_hash || !input_file.empty())
                       : (input_file.empty() || (print_hash && (resume || overwrite || n_seeds > 0))))
    {
      std::cerr << "geohybrid " << argv[1] << ": expected one input file (optionally followed by --resume or "
                << "--overwrite, or for pullout by --seeds N, for pullout and sweep by --print-parameters-hash) or "
                   "--print-parameters\n";
      return 2;
    }
  if (resume && overwrite)
    {
      std::cerr << "geohybrid " << argv[1] << ": --resume continues the run in the output directory, --overwrite "
                << "removes it: give one of them\n";
      return 2;
    }
  geohybrid::apps::set_overwrite_output(overwrite);
  try
    {
      if (print_parameters)
        {
          dealii::ParameterHandler prm;
          found->second.declare(prm);
          prm.print_parameters(std::cout, dealii::ParameterHandler::OutputStyle::PRM);
          return 0;
        }
      if (print_hash && !std::strcmp(argv[1], "sweep"))
        {
          const auto hashes = geohybrid::apps::sweep_member_hashes(input_file);
          if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
            for (const auto &[member, hash] : hashes)
              std::cout << member << ' ' << hash << '\n';
          return 0;
        }
      if (print_hash)
        {
          const std::string hash = geohybrid::apps::check_pullout_input(input_file);
          if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
            std::cout << hash << std::endl;
          return 0;
        }
      // The commands whose loops stop cleanly on a signal (apps/interrupt.h); the others keep
      // the default action, which ends them at once.
      if (!std::strcmp(argv[1], "dem") || !std::strcmp(argv[1], "pullout") || !std::strcmp(argv[1], "sweep") ||
          !std::strcmp(argv[1], "design"))
        geohybrid::apps::install_interrupt_handlers();
      if (n_seeds > 0)
        return geohybrid::apps::run_pullout_seeds(input_file, n_seeds, MPI_COMM_WORLD, resume);
      return found->second.run(input_file, resume);
    }
  catch (const geohybrid::apps::Interrupted &e)
    {
      // One line (from rank 0 under mpirun, where every rank stops): where the run stopped, what
      // it saved, and the command that goes on from there.
      if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        std::cout << "geohybrid " << argv[1] << ": interrupted by " << geohybrid::apps::signal_name(e.signal()) << ' '
                  << e.what() << (e.resumable() ? "; continue with: " : "; run it again: ")
                  << command_line(argc, argv, e.resumable()) << std::endl;
      return e.exit_status();
    }
  catch (const std::exception &e)
    {
      // Under mpirun every rank stops at an error of the input: rank 0 says it, once; an error of
      // one rank alone (RankError) is said by that rank.
      const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
      if (rank == 0 || dynamic_cast<const geohybrid::apps::RankError *>(&e) != nullptr)
        std::cerr << "geohybrid " << argv[1] << (rank > 0 ? " (rank " + std::to_string(rank) + ")" : std::string())
                  << ": error: " << e.what() << '\n';
      return 1;
    }
}
