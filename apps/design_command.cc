#include "design_command.h"

#include "design_bisection.h"
#include "design_definition.h"
#include "design_results.h"
#include "interrupt.h"
#include "output_guard.h"
#include "rank_error.h"
#include "run_directory.h"
#include "sweep_command.h"

#include "dem/io/checked_output.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <locale>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
namespace fs = std::filesystem;

/// The base input every run starts from, in the design's directory.
const char *const base_file_name = "design_base.prm";

/// `text` (design_value_text) read back: the value as the run reads it.
double value_of(const std::string &text)
{
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  double value = 0.0;
  in >> value;
  return value;
}

/// Rank 0 prepares the design's directory (a directory of another kind of run is refused, as a
/// run into it would be), writes design.prm and design_base.prm; its refusal stops every rank.
void prepare_directory(const DesignDefinition &design, const dealii::ParameterHandler &prm, bool writer,
                       MPI_Comm communicator, bool with_mpi)
{
  const fs::path out = design.output_directory;
  std::string refused;
  if (writer)
    try
      {
        if (overwrite_output() || (!run_files(out).empty() && !fs::exists(out / "design.prm")))
          claim_output_directory(out, false); // --overwrite: removes geohybrid's files there, the design's too
        fs::remove(out / "summary.json");   // this design's, from before: written again at the end
        fs::create_directories(out);
        std::ofstream resolved(out / "design.prm");
        prm.print_parameters(resolved, dealii::ParameterHandler::OutputStyle::ShortPRM);
        dem::close_checked(resolved, out / "design.prm");
        dealii::ParameterHandler base;
        read_design_base(design, base);
        std::ofstream base_file(out / base_file_name);
        base.print_parameters(base_file, dealii::ParameterHandler::OutputStyle::ShortPRM);
        dem::close_checked(base_file, out / base_file_name);
      }
    catch (const std::exception &e)
      {
        refused = e.what();
      }
  if (with_mpi)
    refused = dealii::Utilities::MPI::broadcast(communicator, refused, 0);
  if (!refused.empty())
    throw std::runtime_error(refused);
}

/// The sweep over the seeds at one value, run; on rank 0 `step` gets its figures.
void run_step(const DesignDefinition &design, DesignStep &step, MPI_Comm communicator)
{
  const fs::path out = design.output_directory;
  dealii::ParameterHandler prm;
  declare_sweep_parameters(prm);
  set_parameter(prm, "base input", fs::absolute(out / base_file_name).lexically_normal().string());
  set_parameter(prm, "output directory", (out / step.directory).string());
  set_parameter(prm, "Sweep/" + design.entry, step.text);
  std::string seeds;
  for (const std::string &seed : design.seeds)
    seeds += (seeds.empty() ? "" : ", ") + seed;
  if (!seeds.empty())
    set_parameter(prm, "Sweep/Filling/seed", seeds);
  const SweepDefinition sweep = make_sweep(design.input_file, prm);
  SweepRun run;
  try
    {
      run = run_sweep(sweep, prm, communicator);
    }
  catch (const Interrupted &e)
    {
      throw Interrupted(e.signal(),
                        "during the design's runs at " + design.entry_name + " = " + step.text +
                          " m: the runs that finished are kept in " + out.string() +
                          "; the same command continues the design",
                        true);
    }
  step.n_runs = sweep.members.size();
  for (std::size_t m = 0; m < run.outcomes.size(); ++m)
    if (run.outcomes[m].T_max_kN)
      step.T_max_kN.push_back(*run.outcomes[m].T_max_kN);
    else
      step.message += (step.message.empty() ? "" : "; ") + sweep.members[m].name + " " + run.outcomes[m].status +
                      (run.outcomes[m].message.empty() ? "" : ": " + run.outcomes[m].message);
}

/// What the bisection's end means, in words.
DesignAnswer answer_of(const DesignDefinition &design, const DesignBisection &bisection,
                       const std::vector<DesignStep> &steps)
{
  DesignAnswer a;
  const std::string &B = design.entry_name;
  const std::string bracket = "[" + number(design.minimum) + ", " + number(design.maximum) + "] m";
  // One run per value (fem mode, or one seed) has no spread: its criterion is its T_max.
  const std::string criterion = design.seeds.size() < 2     ? std::string("T_max")
                                : design.margin_factor > 0.0 ? "mean - " + number(design.margin_factor) + " std of T_max"
                                                             : std::string("the mean T_max");
  const std::string target = number(design.target_kN, 4) + " kN/m";
  const auto at = [&](std::size_t k) {
    return B + " = " + steps[k].text + " m (" + number(steps[k].criterion_kN(design.margin_factor), 4) + " kN/m)";
  };
  switch (bisection.outcome())
    {
      case DesignBisection::Outcome::found:
        a.outcome = "found";
        a.answer = bisection.answer();
        a.highest_failing = bisection.highest_failing();
        a.message = B + "* = " + number(*a.answer) + " m: the smallest " + B + " in " + bracket + " whose " + criterion +
                    " reaches " + target + ", to " + number(design.tolerance) + " m (" + B + " = " +
                    number(*a.highest_failing) + " m does not)";
        break;
      case DesignBisection::Outcome::not_reached:
        a.outcome = "not reached";
        a.message = "no " + B + " in " + bracket + " reaches the target: " + criterion + " stays below " + target +
                    " at both ends, " + at(0) + " and " + at(1) + "; not bisected. Raise 'Design/maximum' (within the "
                    "tank) or lower the target";
        break;
      case DesignBisection::Outcome::met_at_minimum:
        a.outcome = "met at the minimum";
        a.message = "the bracket " + bracket + " does not bracket the target: " + criterion + " reaches " + target +
                    " already at the minimum, " + at(0) + " (and at the maximum, " + at(1) + "), so the smallest " +
                    B + " is at or below the minimum; not bisected. Lower 'Design/minimum'";
        break;
      case DesignBisection::Outcome::decreasing:
        a.outcome = "decreasing";
        a.message = "the bracket " + bracket + " does not bracket the target as the design assumes: " + criterion +
                    " reaches " + target + " at the minimum, " + at(0) + ", but not at the maximum, " + at(1) +
                    ": it falls as " + B + " grows; not bisected";
        break;
      case DesignBisection::Outcome::running:
        a.outcome = "runs failed";
        a.message = "a run at " + B + " = " + steps.back().text + " m did not finish (" + steps.back().message +
                    "), so the criterion cannot be judged there; the design stopped. Fix the cause and run the same "
                    "command again: the runs that finished are kept";
        break;
    }
  a.warnings = monotonicity_warnings(design, steps);
  return a;
}
} // namespace

int run_design_command(const std::string &input_file, bool /*resume*/, MPI_Comm communicator)
{
  const bool with_mpi = dealii::Utilities::MPI::job_supports_mpi();
  const bool writer = !with_mpi || dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
  const auto start_time = std::chrono::steady_clock::now();
  dealii::ParameterHandler prm;
  declare_design_parameters(prm);
  const DesignDefinition design = parse_design(input_file, prm);
  prepare_directory(design, prm, writer, communicator, with_mpi);
  const fs::path out = design.output_directory;
  if (writer)
    {
      std::cout << "geohybrid design: the smallest " << design.entry << " in [" << number(design.minimum) << ", "
                << number(design.maximum) << "] m with "
                << (design.seeds.size() < 2     ? std::string("T_max")
                    : design.margin_factor > 0.0 ? "mean - " + number(design.margin_factor) + " std of T_max"
                                                 : std::string("the mean T_max"))
                << " >= " << number(design.target_kN) << " kN/m, to " << number(design.tolerance)
                << " m; mode = " << design.mode << ", "
                << (design.seeds.empty() ? std::string("one run per value") : std::to_string(design.seeds.size()) + " seeds per value")
                << ", in " << out.string() << std::endl;
      for (const std::string &note : design.notes)
        std::cout << "geohybrid design: note: " << note << std::endl;
    }

  DesignBisection bisection(design.minimum, design.maximum, design.tolerance);
  std::vector<DesignStep> steps; // complete on rank 0; the other ranks know the values only
  while (bisection.outcome() == DesignBisection::Outcome::running)
    {
      DesignStep step;
      step.text = design_value_text(bisection.next());
      step.value = value_of(step.text);
      step.directory = design.entry_name + "_" + step.text;
      run_step(design, step, communicator);
      int complete = step.complete() ? 1 : 0, met = meets_criterion(design, step) ? 1 : 0;
      if (with_mpi)
        {
          complete = dealii::Utilities::MPI::broadcast(communicator, complete, 0);
          met = dealii::Utilities::MPI::broadcast(communicator, met, 0);
        }
      steps.push_back(step);
      // Rank 0 writes the table; its failure (a full disk) stops every rank, not only the writer.
      on_rank_zero(communicator, [&] {
        write_design_table(design, steps, out / "design.csv");
        std::cout << "geohybrid design: " << design.entry_name << " = " << step.text << " m: ";
        if (complete)
          std::cout << "T_max " << number(step.spread().mean, 5) << " kN/m (std " << number(step.spread().std, 3)
                    << " over " << step.T_max_kN.size() << " run(s)), criterion " << number(step.criterion_kN(design.margin_factor), 5)
                    << " kN/m: " << (met ? "met" : "not met") << std::endl;
        else
          std::cout << "a run did not finish: " << step.message << std::endl;
      });
      if (!complete)
        break;
      bisection.record(step.value, met != 0);
    }

  if (writer)
    {
      const DesignAnswer answer = answer_of(design, bisection, steps);
      write_design_table(design, steps, out / "design.csv");
      plot_design(design, answer, !design.seeds.empty(), out / "design.csv", out / "design.png");
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
      write_design_summary(design, steps, answer, seconds, out / "summary.json");
      for (const std::string &warning : answer.warnings)
        std::cout << "geohybrid design: warning: " << warning << std::endl;
      std::cout << "geohybrid design: " << answer.message << "; " << steps.size() << " value(s) tried in "
                << number(seconds, 4) << " s; results in " << (out / "design.csv").string() << std::endl;
    }
  return bisection.outcome() == DesignBisection::Outcome::found ? 0 : 1;
}
} // namespace geohybrid::apps
