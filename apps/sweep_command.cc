#include "sweep_command.h"

#include "interrupt.h"
#include "output_guard.h"
#include "parameters_hash.h"
#include "pullout_command.h"
#include "rank_error.h"
#include "resume_check.h"
#include "run_directory.h"
#include "summary.h"
#include "sweep_definition.h"
#include "sweep_results.h"

#include "dem/io/checked_output.h"

#include <deal.II/base/mpi.h>

#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <chrono>
#include <fstream>
#include <iostream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
namespace fs = std::filesystem;

/// "B = 0.25, seed = 2": a member's values for the terminal.
std::string describe(const SweepMember &member)
{
  std::string text;
  for (const auto &[path, value] : member.values)
    text += (text.empty() ? "" : ", ") + path + " = " + value;
  return text;
}

/// The parameters_hash in `directory`'s summary.json, empty if none can be read.
std::string finished_hash(const fs::path &directory)
{
  if (!fs::exists(directory / "summary.json"))
    return "";
  try
    {
      const nlohmann::json json = read_summary(directory / "summary.json");
      const auto hash = json.find("parameters_hash");
      return hash != json.end() && hash->is_string() ? hash->get<std::string>() : "";
    }
  catch (const std::exception &)
    {
      return ""; // unreadable: not a finished run of this member
    }
}

/// Runs one member on `communicator` (its rank alone), or keeps it if it finished before. A
/// signal is passed on as Interrupted; any other failure is the outcome's message.
MemberOutcome run_member(const SweepDefinition &sweep, const SweepMember &member, MPI_Comm communicator,
                         const std::string &on_rank)
{
  const fs::path directory = sweep.output_directory / member.name;
  const std::string where = "member " + member.name + " (" + describe(member) + ")";
  MemberOutcome outcome;
  try
    {
      dealii::ParameterHandler prm;
      read_member_input(sweep, member, prm);
      if (finished_hash(directory) == pullout_parameters_hash(prm))
        {
          outcome.status = "kept";
          return outcome;
        }
      // What a member left in its own directory (same physics: parameters.prm's hash) is continued:
      // from its checkpoint in dem and hybrid modes; fem mode has none and starts again over its files.
      bool resume = false;
      if (!overwrite_output() && (fs::exists(directory / "checkpoint.h5") || holds_same_pullout_run(directory, prm)))
        {
          if (prm.get("mode") != "fem")
            resume = true;
          else
            {
              set_overwrite_output(true);
              claim_output_directory(directory, false); // removes geohybrid's files only
              set_overwrite_output(false);
            }
        }
      std::cout << "geohybrid sweep: " << where << ", " << member.index + 1 << " of " << sweep.members.size()
                << (resume ? ", continued" : "") << ", in " << directory.string() << on_rank << std::endl;
      run_pullout_command(sweep.base_input, resume, communicator, member_overrides(sweep, member));
      outcome.status = "finished";
    }
  catch (const Interrupted &)
    {
      throw;
    }
  catch (const std::exception &e)
    {
      outcome.status = "failed";
      outcome.message = e.what();
      std::cerr << "geohybrid sweep: " << where << " failed" << on_rank << ": " << e.what() << std::endl;
    }
  return outcome;
}
} // namespace

int run_sweep_command(const std::string &input_file, bool /*resume*/, MPI_Comm communicator)
{
  dealii::ParameterHandler prm;
  declare_sweep_parameters(prm);
  const SweepDefinition sweep = parse_sweep(input_file, prm);
  return run_sweep(sweep, prm, communicator).status;
}

std::vector<std::pair<std::string, std::string>> sweep_member_hashes(const std::string &input_file)
{
  dealii::ParameterHandler prm;
  declare_sweep_parameters(prm);
  const SweepDefinition sweep = parse_sweep(input_file, prm);
  std::vector<std::pair<std::string, std::string>> hashes;
  for (const SweepMember &member : sweep.members)
    {
      try
        {
          hashes.emplace_back(member.name,
                              check_pullout_input(sweep.base_input, MPI_COMM_SELF, member_overrides(sweep, member)));
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error(input_file + ": member " + member.name + " (" + describe(member) + "): " + e.what());
        }
    }
  return hashes;
}

SweepRun run_sweep(const SweepDefinition &sweep, const dealii::ParameterHandler &prm, MPI_Comm communicator)
{
  const bool with_mpi = dealii::Utilities::MPI::job_supports_mpi();
  const unsigned int rank = with_mpi ? dealii::Utilities::MPI::this_mpi_process(communicator) : 0;
  const unsigned int n_ranks = with_mpi ? dealii::Utilities::MPI::n_mpi_processes(communicator) : 1;
  const auto start_time = std::chrono::steady_clock::now();
  const fs::path out = sweep.output_directory;

  // Rank 0 prepares the directory; its refusal stops every rank. A single run's directory is not
  // a sweep's: refused as a run into it is, or cleared with --overwrite.
  on_rank_zero(communicator, [&] {
    if (fs::exists(out / "summary.json") || fs::exists(out / "pullout_curve.csv") || fs::exists(out / "checkpoint.h5"))
      claim_output_directory(out, false);
    fs::create_directories(out);
    std::ofstream resolved(out / "sweep.prm");
    prm.print_parameters(resolved, dealii::ParameterHandler::OutputStyle::ShortPRM);
    dem::close_checked(resolved, out / "sweep.prm");
  });
  if (rank == 0)
    std::cout << "geohybrid sweep: " << sweep.members.size() << " members of " << sweep.base_input
              << (n_ranks > 1 ? " over " + std::to_string(n_ranks) + " ranks" : std::string()) << ", in " << out.string()
              << std::endl;

  // This rank's members, one after the other; each outcome as "index<TAB>status<TAB>message".
  const MPI_Comm member_communicator = with_mpi ? MPI_COMM_SELF : communicator;
  const std::string on_rank = n_ranks > 1 ? " (rank " + std::to_string(rank) + ")" : "";
  std::vector<std::string> records;
  int signal = 0;
  for (const SweepMember &member : sweep.members)
    {
      if (member.index % n_ranks != rank)
        continue;
      if (signal == 0)
        signal = interrupt_signal(); // came between two members: start no other
      MemberOutcome outcome;
      if (signal == 0)
        try
          {
            outcome = run_member(sweep, member, member_communicator, on_rank);
          }
        catch (const Interrupted &e)
          {
            signal = e.signal();
            outcome.status = "stopped";
            outcome.message = "stopped by " + signal_name(e.signal()) + " " + e.what();
          }
      records.push_back(std::to_string(member.index) + '\t' + outcome.status + '\t' + outcome.message);
    }
  std::vector<std::vector<std::string>> gathered{records};
  if (with_mpi)
    {
      gathered = dealii::Utilities::MPI::gather(communicator, records, 0);
      signal = dealii::Utilities::MPI::max(signal, communicator);
    }

  unsigned int n_failed = 0;
  SweepRun run;
  // Rank 0 writes the table; its failure (a full disk) stops every rank, not only the writer.
  on_rank_zero(communicator, [&] {
    std::vector<MemberOutcome> &outcomes = run.outcomes;
    outcomes.resize(sweep.members.size());
    for (const std::vector<std::string> &from_rank : gathered)
      for (const std::string &record : from_rank)
        {
          const std::size_t tab = record.find('\t'), second = record.find('\t', tab + 1);
          MemberOutcome &o = outcomes.at(std::stoul(record.substr(0, tab)));
          o.status = record.substr(tab + 1, second - tab - 1);
          o.message = record.substr(second + 1);
        }
    std::size_t n_finished = 0, n_kept = 0;
    for (std::size_t m = 0; m < outcomes.size(); ++m)
      {
        MemberOutcome &o = outcomes[m];
        if (o.status == "finished" || o.status == "kept")
          try
            {
              const nlohmann::json json = read_summary(out / sweep.members[m].name / "summary.json");
              o.T_max_kN = json.at("T_max_kN_per_m").get<double>();
              (o.status == "kept" ? n_kept : n_finished) += 1;
            }
          catch (const std::exception &e)
            {
              o.status = "failed";
              o.message = std::string("no T_max_kN_per_m in its summary.json: ") + e.what();
            }
        n_failed += o.status == "failed" ? 1 : 0;
      }
    write_sweep_table(sweep, outcomes, out / "sweep.csv");
    plot_sweep(sweep, out / "sweep.csv", out / "sweep.png");
    std::cout << "geohybrid sweep: " << n_finished << " member(s) run, " << n_kept << " kept from before, " << n_failed
              << " failed, " << outcomes.size() - n_finished - n_kept - n_failed << " not finished, in "
              << number(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count(), 4)
              << " s; results in " << (out / "sweep.csv").string() << std::endl;
    for (std::size_t m = 0; m < outcomes.size(); ++m)
      if (outcomes[m].status == "failed")
        std::cerr << "geohybrid sweep: failed: " << sweep.members[m].name << ": " << outcomes[m].message << '\n';
  });
  if (with_mpi)
    n_failed = dealii::Utilities::MPI::broadcast(communicator, n_failed, 0);
  if (signal != 0) // the same command continues a sweep, whatever its members had saved
    throw Interrupted(signal,
                      "before the sweep's end: the members that finished are kept in " + out.string() +
                        " (sweep.csv lists them); the same command continues the others",
                      true);
  run.status = n_failed > 0 ? 1 : 0;
  return run;
}
} // namespace geohybrid::apps
