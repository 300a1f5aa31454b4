// `geohybrid design` (issue 24, section 4): the bisection's bookkeeping on functions whose root is
// known; a fem-mode design whose answer meets the criterion in its own run and fails it in a run
// a tolerance below; the bracket's ends that do not bracket the target, said and not bisected;
// a design run again keeping its runs; bad design files refused by name before anything is
// written. DesignOfAFemRunOut also runs on two ranks (test_app_pullout_fem_np2).
#include "apps/design_bisection.h"
#include "apps/design_command.h"
#include "apps/pullout_command.h"
#include "apps/run_directory.h"
#include "apps/summary.h"
#include "apps/sweep_results.h"
#include "sweep_test_inputs.h"
#include "text_file.h"
#include "tiny_pullout_input.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <vector>

namespace fs = std::filesystem;
using geohybrid::apps::DesignBisection;

namespace
{
/// A design file beside the fem base input (tests/sweep_test_inputs.h), into DIRECTORY/design.
std::string write_design_input(const fs::path &directory, const std::string &design_lines, const std::string &top = "",
                               const std::string &name = "design_input.prm")
{
  const fs::path file = directory / name;
  if (geohybrid::testing::is_rank_zero())
    std::ofstream(file) << "set base input = base.prm\n"
                        << "set output directory = " << (directory / "design").string() << "\n"
                        << top << "subsection Design\n" << design_lines << "end\n";
  MPI_Barrier(MPI_COMM_WORLD);
  return file.string();
}

std::string design_error_of(const std::string &file)
{
  try
    {
      geohybrid::apps::run_design_command(file, false);
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}

/// Runs the bisection on `met` (false below a root, true from it on) and returns it ended.
DesignBisection run_bisection(double minimum, double maximum, double tolerance, const std::function<bool(double)> &met)
{
  DesignBisection b(minimum, maximum, tolerance);
  for (int k = 0; k < 100 && b.outcome() == DesignBisection::Outcome::running; ++k)
    {
      const double x = b.next();
      b.record(x, met(x));
    }
  return b;
}
} // namespace

// x^3 >= r on [0.5, 3] for several r, and a few tolerances: the answer is a value tried and met,
// the highest value that failed is within the tolerance below it, the root lies between them, and
// the number of values tried is the two ends and ceil(log2(width / tolerance)) midpoints at most.
TEST(DesignBisection, FindsTheRootOfAMonotoneFunctionWithinTheTolerance)
{
  for (const double tolerance : {0.1, 0.01, 0.003})
    for (const double r : {0.2, 1.0, 2.0, 7.9, 26.0})
      {
        const double root = std::cbrt(r);
        const DesignBisection b = run_bisection(0.5, 3.0, tolerance, [&](double x) { return x * x * x >= r; });
        ASSERT_EQ(b.outcome(), DesignBisection::Outcome::found) << r;
        EXPECT_LE(b.highest_failing(), root);
        EXPECT_GE(b.answer(), root);
        EXPECT_LE(b.answer() - b.highest_failing(), tolerance);
        EXPECT_NEAR(b.answer(), root, tolerance);
        const auto &trials = b.trials();
        EXPECT_LE(trials.size(), 2u + static_cast<std::size_t>(std::ceil(std::log2(2.5 / tolerance))));
        bool answer_tried = false, failing_tried = false;
        for (const auto &t : trials)
          {
            EXPECT_EQ(t.met, t.value * t.value * t.value >= r);
            answer_tried |= t.value == b.answer() && t.met;
            failing_tried |= t.value == b.highest_failing() && !t.met;
            EXPECT_NEAR(t.value / b.grid(), std::round(t.value / b.grid()), 1e-6) << "a midpoint off its grid";
          }
        EXPECT_TRUE(answer_tried && failing_tried);
      }
}

// The ends tried first, and a criterion they do not bracket stops the search after them.
TEST(DesignBisection, EndsThatDoNotBracketStopAfterTwoValues)
{
  const auto ends = [](const std::function<bool(double)> &met) {
    const DesignBisection b = run_bisection(1.0, 2.0, 0.01, met);
    EXPECT_EQ(b.trials().size(), 2u);
    EXPECT_EQ(b.trials()[0].value, 1.0);
    EXPECT_EQ(b.trials()[1].value, 2.0);
    return b.outcome();
  };
  EXPECT_EQ(ends([](double) { return false; }), DesignBisection::Outcome::not_reached);
  EXPECT_EQ(ends([](double) { return true; }), DesignBisection::Outcome::met_at_minimum);
  EXPECT_EQ(ends([](double x) { return x < 1.5; }), DesignBisection::Outcome::decreasing);
  EXPECT_THROW(DesignBisection(1.0, 2.0, 1.0), std::invalid_argument);
  EXPECT_THROW(DesignBisection(1.0, 2.0, 0.0), std::invalid_argument);
}

// A bracket that is the tolerance in decimal stops the search, though its difference in binary is
// a little above: 0.06 and 0.14 by 0.02, the midpoints 0.1 and 0.08, then no 0.07.
TEST(DesignBisection, ABracketOfTheToleranceInDecimalStops)
{
  const DesignBisection b = run_bisection(0.06, 0.14, 0.02, [](double x) { return x >= 0.075; });
  ASSERT_EQ(b.outcome(), DesignBisection::Outcome::found);
  EXPECT_EQ(b.trials().size(), 4u);
  EXPECT_DOUBLE_EQ(b.answer(), 0.08);
  EXPECT_DOUBLE_EQ(b.highest_failing(), 0.06);
}

// The smallest run-out length L in [0.1, 0.5] m whose T_max reaches 3 kN/m, in the fem tank of the
// sweep tests (T_max grows with L as the interface's geostatic limit 2 gamma H tan(delta) L). The
// answer L* meets the criterion in its own run, the highest value that failed is within the
// tolerance below it, and a pull-out at L* - tolerance, run here, fails it. Then the same design
// again keeps every run, and designs whose target the bracket does not bracket say so after its
// two ends (both kept from the first design: no run is made again).
TEST(Design, DesignOfAFemRunOut)
{
  const fs::path d = geohybrid::testing::fresh_test_directory("design");
  if (geohybrid::testing::is_rank_zero())
    geohybrid::testing::write_fem_base_input(d);
  const double target = 3.0, tolerance = 0.05;
  const std::string input = write_design_input(d, "  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n"
                                                  "  set target T_max = 3\n  set tolerance = 0.05\n");
  const fs::path out = d / "design";
  ASSERT_EQ(geohybrid::apps::run_design_command(input, false), 0); // collective
  double answer = 0.0;
  std::map<std::string, fs::file_time_type> written;
  if (geohybrid::testing::is_rank_zero())
    {
      const nlohmann::json summary = geohybrid::apps::read_summary(out / "summary.json");
      ASSERT_EQ(summary.at("outcome"), "found") << summary.at("message");
      answer = summary.at("answer_m").get<double>();
      const double failing = summary.at("highest_failing_m").get<double>();
      EXPECT_GT(answer, failing);
      EXPECT_LE(answer - failing, tolerance);
      const auto rows = geohybrid::testing::csv_rows_by_name(out / "design.csv");
      ASSERT_EQ(rows.size(), summary.at("n_values_tried").get<std::size_t>());
      EXPECT_LE(rows.size(), 2u + 3u); // the ends, then ceil(log2(0.4 / 0.05)) midpoints
      EXPECT_EQ(rows[0].at("L_m"), "0.1");
      EXPECT_EQ(rows[1].at("L_m"), "0.5");
      bool answer_met = false, failing_failed = false;
      for (const auto &row : rows)
        {
          // Each row's mean is its run's T_max, its criterion the mean (fem: one run, std 0), its verdict
          // the criterion against the target.
          const double L = std::stod(row.at("L_m")), mean = std::stod(row.at("T_max_kN_per_m"));
          const fs::path run = out / row.at("directory") / row.at("directory");
          const double T_max = geohybrid::apps::read_summary(run / "summary.json").at("T_max_kN_per_m").get<double>();
          written[run.string()] = fs::last_write_time(run / "summary.json");
          EXPECT_NEAR(mean, T_max, 1e-10 * T_max) << row.at("directory");
          EXPECT_EQ(row.at("n_runs"), "1");
          EXPECT_EQ(std::stod(row.at("T_max_std_kN_per_m")), 0.0);
          EXPECT_EQ(std::stod(row.at("criterion_kN_per_m")), mean);
          EXPECT_EQ(row.at("met"), mean >= target ? "yes" : "no") << L;
          // T_max rises with L: met at and above the answer, not at and below the highest failing value.
          EXPECT_EQ(row.at("met") == "yes", L >= answer) << L;
          answer_met |= L == answer && row.at("met") == "yes";
          failing_failed |= L == failing && row.at("met") == "no";
        }
      EXPECT_TRUE(answer_met);
      EXPECT_TRUE(failing_failed);
      EXPECT_TRUE(summary.at("answer_m").is_number());
      EXPECT_EQ(summary.at("warnings").size(), 0u) << summary.at("warnings").dump();
      EXPECT_EQ(geohybrid::testing::read_text(out / "design.png").substr(1, 3), "PNG");
      // A pull-out a tolerance below the answer falls short of the target.
      const fs::path below = d / "below";
      const std::string L_below = geohybrid::apps::number(answer - tolerance, 10);
      ASSERT_EQ(geohybrid::apps::run_pullout_command((d / "base.prm").string(), false, MPI_COMM_SELF,
                                                     {{"Anchorage/L", L_below}, {"output directory", below.string()}}),
                0);
      const double T_below = geohybrid::apps::read_summary(below / "summary.json").at("T_max_kN_per_m").get<double>();
      EXPECT_LT(T_below, target) << "L = " << L_below;
    }
  MPI_Barrier(MPI_COMM_WORLD);

  // Again: the same answer, every run kept as it was.
  ASSERT_EQ(geohybrid::apps::run_design_command(input, false), 0);
  if (geohybrid::testing::is_rank_zero())
    {
      EXPECT_EQ(geohybrid::apps::read_summary(out / "summary.json").at("answer_m").get<double>(), answer);
      for (const auto &[run, time] : written)
        EXPECT_EQ(fs::last_write_time(fs::path(run) / "summary.json"), time) << run;
    }
  MPI_Barrier(MPI_COMM_WORLD);

  // Targets the bracket does not bracket: said after its two ends, not bisected, exit status 1.
  for (const auto &[target_text, outcome] : std::vector<std::pair<std::string, std::string>>{
         {"100", "not reached"}, {"0.5", "met at the minimum"}})
    {
      const std::string other = write_design_input(d, "  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n"
                                                      "  set target T_max = " + target_text + "\n  set tolerance = 0.05\n",
                                                   "", "design_" + target_text + ".prm");
      EXPECT_EQ(geohybrid::apps::run_design_command(other, false), 1);
      if (geohybrid::testing::is_rank_zero())
        {
          const nlohmann::json summary = geohybrid::apps::read_summary(out / "summary.json");
          EXPECT_EQ(summary.at("outcome"), outcome);
          EXPECT_TRUE(summary.at("answer_m").is_null());
          EXPECT_EQ(summary.at("n_values_tried").get<int>(), 2);
          EXPECT_NE(summary.at("message").get<std::string>().find("not bisected"), std::string::npos);
          EXPECT_EQ(geohybrid::testing::csv_rows_by_name(out / "design.csv").size(), 2u);
        }
      MPI_Barrier(MPI_COMM_WORLD);
    }
  for (const auto &[run, time] : written)
    EXPECT_EQ(fs::last_write_time(fs::path(run) / "summary.json"), time) << run;
  if (geohybrid::testing::is_rank_zero())
    fs::remove_all(d);
  MPI_Barrier(MPI_COMM_WORLD);
}

// dem mode on the tiny tank, two fills per value: each row's mean, std and criterion mean - k std
// are those of its two runs' T_max, read here from their summaries. The target (1 N/m) is met
// already at the minimum: said after the two ends, four runs in all.
TEST(Design, MeanAndSpreadOverDemSeeds)
{
  const fs::path d = geohybrid::testing::fresh_test_directory("design");
  if (!geohybrid::testing::is_rank_zero())
    return;
  geohybrid::testing::write_tiny_pullout_input(d);
  const fs::path file = d / "design_dem.prm";
  std::ofstream(file) << "set base input = tiny.prm\nset output directory = " << (d / "design").string() << "\n"
                      << "subsection Design\n  set entry = L\n  set minimum = 0.06\n  set maximum = 0.14\n"
                      << "  set target T_max = 0.001\n  set margin factor = 1.5\n  set tolerance = 0.02\n"
                      << "  set seeds = 3, 4\nend\n";
  EXPECT_EQ(geohybrid::apps::run_design_command(file.string(), false, MPI_COMM_SELF), 1);
  const fs::path out = d / "design";
  const nlohmann::json summary = geohybrid::apps::read_summary(out / "summary.json");
  EXPECT_EQ(summary.at("outcome"), "met at the minimum") << summary.at("message");
  EXPECT_EQ(summary.at("n_runs").get<int>(), 4);
  const auto rows = geohybrid::testing::csv_rows_by_name(out / "design.csv");
  ASSERT_EQ(rows.size(), 2u);
  for (const auto &row : rows)
    {
      std::vector<double> T;
      for (const std::string seed : {"3", "4"})
        {
          const fs::path run = out / row.at("directory") / (row.at("directory") + "_seed_" + seed);
          T.push_back(geohybrid::apps::read_summary(run / "summary.json").at("T_max_kN_per_m").get<double>());
        }
      EXPECT_GT(std::abs(T[0] - T[1]), 1e-6 * T[0]) << "two fills gave one T_max: no spread to check";
      const double mean = 0.5 * (T[0] + T[1]), std = std::abs(T[0] - T[1]) / std::sqrt(2.0);
      EXPECT_EQ(row.at("n_runs"), "2");
      EXPECT_NEAR(std::stod(row.at("T_max_kN_per_m")), mean, 1e-10 * mean);
      EXPECT_NEAR(std::stod(row.at("T_max_std_kN_per_m")), std, 1e-9 * mean);
      EXPECT_NEAR(std::stod(row.at("criterion_kN_per_m")), mean - 1.5 * std, 1e-9 * mean);
      EXPECT_EQ(row.at("met"), mean - 1.5 * std >= 0.001 ? "yes" : "no");
    }
  fs::remove_all(d);
}

// Refused before anything is written, naming the file and the entry.
TEST(Design, BadDesignFilesNameTheEntry)
{
  const fs::path d = geohybrid::testing::fresh_test_directory("design");
  if (!geohybrid::testing::is_rank_zero())
    return;
  geohybrid::testing::write_fem_base_input(d);
  const std::string good = "  set minimum = 0.1\n  set maximum = 0.5\n  set target T_max = 3\n  set tolerance = 0.05\n";
  struct Case
  {
    std::string lines, top, expected;
  };
  for (const Case &c :
       {Case{"  set entry = L\n  set minimun = 0.1\n", "", "minimun"},
        Case{"  set entry = H\n" + good, "", "'Design/entry' = 'H' is not one a design sizes"},
        Case{"  set entry = B\n" + good, "", "'Design/entry' = B sizes a wrap-around's upper part"},
        Case{"  set entry = L\n  set minimum = 0.1\n  set maximum = 0.7\n  set target T_max = 3\n  set tolerance = 0.05\n", "",
             "'Design/maximum' = 0.7 m does not fit the tank: L must be shorter than 'Tank/length' = 0.6 m"},
        Case{"  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n  set target T_max = -3\n  set tolerance = 0.05\n", "",
             "'Design/target T_max' = -3 kN/m must be positive"},
        Case{"  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n  set tolerance = 0.05\n", "",
             "'Design/target T_max' is not set"},
        Case{"  set entry = L\n  set minimum = 0.5\n  set maximum = 0.1\n  set target T_max = 3\n  set tolerance = 0.05\n", "",
             "'Design/maximum' = 0.1 m must be above 'Design/minimum' = 0.5 m"},
        Case{"  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n  set target T_max = 3\n  set tolerance = 0.5\n", "",
             "'Design/tolerance' = 0.5 m must be positive and below the bracket's width"},
        Case{"  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n  set target T_max = three\n  set tolerance = 0.05\n",
             "", "'Design/target T_max' = 'three' is not a number"},
        Case{"  set entry = L\n  set margin factor = -1\n" + good, "", "'Design/margin factor' = -1 must not be negative"},
        Case{"  set entry = L\n  set seeds = 1, x\n" + good, "", "'x' is not a seed"},
        Case{"  set entry = L\n" + good, "subsection Overrides\n  set mode = dem\nend\n",
             "'Design/margin factor' = 1 needs a spread over the seeds"},
        Case{"  set entry = L\n" + good, "subsection Overrides\n  subsection Anchorage\n    set L = 0.3\n  end\nend\n",
             "'Overrides/Anchorage/L' is set by the design"},
        Case{"  set entry = L\n" + good, "subsection Overrides\n  subsection Anchorage\n    set H = deep\n  end\nend\n",
             "'Overrides/Anchorage/H' = 'deep' is not a value that 'Anchorage/H' takes"},
        Case{"  set entry = L\n" + good, "subsection Overrides\n  subsection Anchorage\n    set H = 1.2\n  end\nend\n",
             "'Design/minimum' = 0.1: the base input with L = 0.1 is refused"}})
    {
      const std::string file = write_design_input(d, c.lines, c.top);
      const std::string message = design_error_of(file);
      EXPECT_NE(message.find(c.expected), std::string::npos) << c.lines << " -> " << message;
      EXPECT_NE(message.find(file), std::string::npos) << message;
      EXPECT_FALSE(fs::exists(d / "design")) << c.lines;
    }
  fs::remove_all(d);
}
