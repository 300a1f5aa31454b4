// `geohybrid sweep` (issue 24, section 4): the members of a grid, each a pull-out of the base input
// with its values; sweep.csv's rows per member and per value with the mean and spread over the
// seeds; a failed member reported while the others finish; a sweep run again keeping its finished
// members and running again only the one whose summary is gone; bad sweep files refused by name.
// SweepOfFemMembers also runs on two ranks (test_app_pullout_fem_np2), the members dealt to them.
#include "apps/parameters_hash.h"
#include "apps/pullout_command.h"
#include "apps/run_directory.h"
#include "apps/sweep_command.h"
#include "apps/sweep_definition.h"
#include "apps/sweep_results.h"
#include "apps/summary.h"
#include "sweep_test_inputs.h"
#include "text_file.h"
#include "tiny_pullout_input.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

namespace fs = std::filesystem;
using geohybrid::testing::lines_of;

namespace
{
double member_summary_number(const fs::path &directory, const std::string &key)
{
  return geohybrid::apps::read_summary(directory / "summary.json").at(key).get<double>();
}

std::string sweep_error_of(const std::string &file)
{
  try
    {
      geohybrid::apps::run_sweep_command(file, false);
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

// L = 0.3, 0.55 and 0.7 m (longer than the 0.6 m tank: refused) on seeds 1 and 2: six members,
// four finish, two fail and say why, and the sweep's status is 1. The continuum has no fill, so
// its two seeds give one T_max: the spread over them is 0, exactly. The value reaches the run: the
// interface's geostatic limit 2 gamma H tan(delta) L grows as L.
TEST(Sweep, SweepOfFemMembers)
{
  const fs::path d = geohybrid::testing::fresh_test_directory("sweep");
  std::string input;
  if (geohybrid::testing::is_rank_zero())
    {
      geohybrid::testing::write_fem_base_input(d);
      input = geohybrid::testing::write_sweep_input(d, "base.prm",
                                                    "  subsection Anchorage\n    set L = 0.3, 0.55, 0.7\n  end\n"
                                                    "  subsection Filling\n    set seed = 1, 2\n  end\n");
    }
  MPI_Barrier(MPI_COMM_WORLD);
  input = (d / "sweep_input.prm").string();
  const fs::path out = d / "sweep";
  EXPECT_EQ(geohybrid::apps::run_sweep_command(input, false), 1); // collective
  std::map<std::string, fs::file_time_type> written;
  if (geohybrid::testing::is_rank_zero())
    {
      const auto rows = geohybrid::testing::csv_rows_by_name(out / "sweep.csv");
      ASSERT_EQ(rows.size(), 6u + 3u);
      const std::vector<std::string> names{"L_0.3_seed_1", "L_0.3_seed_2", "L_0.55_seed_1",
                                           "L_0.55_seed_2", "L_0.7_seed_1", "L_0.7_seed_2"};
      for (std::size_t m = 0; m < 6; ++m)
        {
          const auto &row = rows[m];
          EXPECT_EQ(row.at("row"), "member");
          EXPECT_EQ(row.at("member"), names[m]);
          if (m < 4)
            {
              ASSERT_EQ(row.at("status"), "finished") << row.at("message");
              const double T_max = member_summary_number(out / names[m], "T_max_kN_per_m");
              EXPECT_NEAR(std::stod(row.at("T_max_kN_per_m")), T_max, 1e-10 * T_max);
              written[names[m]] = fs::last_write_time(out / names[m] / "summary.json");
            }
          else
            {
              EXPECT_EQ(row.at("status"), "failed");
              EXPECT_NE(row.at("message").find("'Anchorage/L'"), std::string::npos) << row.at("message");
              EXPECT_FALSE(fs::exists(out / names[m] / "summary.json"));
            }
        }
      for (std::size_t v = 0; v < 2; ++v)
        {
          const auto &row = rows[6 + v];
          EXPECT_EQ(row.at("row"), "over seeds");
          EXPECT_EQ(row.at("status"), "all 2 seeds");
          EXPECT_EQ(row.at("Filling/seed"), "1 2");
          const double a = std::stod(rows[2 * v].at("T_max_kN_per_m")), b = std::stod(rows[2 * v + 1].at("T_max_kN_per_m"));
          EXPECT_EQ(a, b); // the continuum does not see the seed
          EXPECT_NEAR(std::stod(row.at("T_max_kN_per_m")), a, 1e-10 * a);
          EXPECT_EQ(std::stod(row.at("T_max_std_kN_per_m")), 0.0);
        }
      EXPECT_EQ(rows[8].at("status"), "no result");
      EXPECT_EQ(rows[8].at("message"), "failed: L_0.7_seed_1, L_0.7_seed_2");
      const double limit_short = member_summary_number(out / "L_0.3_seed_1", "geostatic_interface_limit_kN_per_m"),
                   limit_long = member_summary_number(out / "L_0.55_seed_1", "geostatic_interface_limit_kN_per_m");
      EXPECT_NEAR(limit_long / limit_short, 0.55 / 0.3, 1e-3 * 0.55 / 0.3);
      EXPECT_EQ(geohybrid::testing::read_text(out / "sweep.png").substr(1, 3), "PNG");
      // What a member's directory holds is its base input's run with its values.
      dealii::ParameterHandler member;
      geohybrid::apps::declare_pullout_parameters(member);
      geohybrid::apps::parse_input_file(member, (out / "L_0.55_seed_2" / "parameters.prm").string());
      EXPECT_EQ(geohybrid::apps::get_parameter(member, "Anchorage/L"), "0.55");
      EXPECT_EQ(geohybrid::apps::get_parameter(member, "Filling/seed"), "2");
      fs::remove(out / "L_0.55_seed_2" / "summary.json");
    }
  MPI_Barrier(MPI_COMM_WORLD);
  // Again: the finished members kept as they are, the one without a summary run again, the same.
  EXPECT_EQ(geohybrid::apps::run_sweep_command(input, false), 1);
  if (geohybrid::testing::is_rank_zero())
    {
      const auto rows = geohybrid::testing::csv_rows_by_name(out / "sweep.csv");
      ASSERT_EQ(rows.size(), 9u);
      for (const std::string name : {"L_0.3_seed_1", "L_0.3_seed_2", "L_0.55_seed_1"})
        EXPECT_EQ(fs::last_write_time(out / name / "summary.json"), written[name]) << name;
      EXPECT_EQ(rows[0].at("status"), "kept");
      EXPECT_EQ(rows[2].at("status"), "kept");
      EXPECT_EQ(rows[3].at("status"), "finished");
      EXPECT_EQ(rows[3].at("T_max_kN_per_m"), rows[2].at("T_max_kN_per_m"));
      fs::remove_all(d);
    }
  MPI_Barrier(MPI_COMM_WORLD);
}

// Two fills of the tiny DEM tank: the row over the seeds holds the mean, the extremes and the
// sample standard deviation of the members' T_max, as computed here from their summaries.
TEST(Sweep, MeanAndSpreadOverDemSeeds)
{
  const fs::path d = geohybrid::testing::fresh_test_directory("sweep");
  geohybrid::testing::write_tiny_pullout_input(d);
  const std::string input = geohybrid::testing::write_sweep_input(
    d, "tiny.prm", "  subsection Pull\n    set final displacement = 0.001\n  end\n"
                   "  subsection Filling\n    set seed = 3, 4\n  end\n");
  ASSERT_EQ(geohybrid::apps::run_sweep_command(input, false, MPI_COMM_SELF), 0);
  const fs::path out = d / "sweep";
  const auto rows = geohybrid::testing::csv_rows_by_name(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 3u);
  const double a = member_summary_number(out / "final-displacement_0.001_seed_3", "T_max_kN_per_m"),
               b = member_summary_number(out / "final-displacement_0.001_seed_4", "T_max_kN_per_m");
  EXPECT_GT(std::abs(a - b), 1e-6 * a) << "two fills gave one T_max: no spread to check";
  const auto &over = rows[2];
  EXPECT_EQ(over.at("status"), "all 2 seeds");
  EXPECT_NEAR(std::stod(over.at("T_max_kN_per_m")), 0.5 * (a + b), 1e-10 * a);
  EXPECT_NEAR(std::stod(over.at("T_max_min_kN_per_m")), std::min(a, b), 1e-10 * a);
  EXPECT_NEAR(std::stod(over.at("T_max_max_kN_per_m")), std::max(a, b), 1e-10 * a);
  EXPECT_NEAR(std::stod(over.at("T_max_std_kN_per_m")), std::abs(a - b) / std::sqrt(2.0), 1e-9 * a);
  // The member's summary holds the hash of the base input with its values: what a later sweep keeps.
  dealii::ParameterHandler prm;
  dealii::ParameterHandler sweep_prm;
  geohybrid::apps::declare_sweep_parameters(sweep_prm);
  const auto sweep = geohybrid::apps::parse_sweep(input, sweep_prm);
  geohybrid::apps::read_member_input(sweep, sweep.members[1], prm);
  EXPECT_EQ(geohybrid::apps::read_summary(out / sweep.members[1].name / "summary.json").at("parameters_hash"),
            geohybrid::apps::pullout_parameters_hash(prm));
  EXPECT_EQ(geohybrid::testing::read_text(out / "sweep.png").substr(1, 3), "PNG");
  // --print-parameters-hash: each member's name and the hash its run's summary holds.
  const auto hashes = geohybrid::apps::sweep_member_hashes(input);
  ASSERT_EQ(hashes.size(), 2u);
  for (const auto &[name, hash] : hashes)
    EXPECT_EQ(geohybrid::apps::read_summary(out / name / "summary.json").at("parameters_hash"), hash) << name;
  fs::remove_all(d);
}

// A list may repeat one entry's value where the members differ (the validation campaign's B =
// 0.25 m at two depths): two members, in the list's order, each with its pair.
TEST(Sweep, AListMayRepeatAValueOfOneEntry)
{
  const fs::path d = geohybrid::testing::fresh_test_directory("sweep");
  if (!geohybrid::testing::is_rank_zero())
    return;
  geohybrid::testing::write_fem_base_input(d);
  const std::string input = geohybrid::testing::write_sweep_input(
    d, "base.prm", "  subsection Anchorage\n    set L = 0.3, 0.3\n    set H = 0.5, 0.6\n  end\n", "set combination = list\n");
  dealii::ParameterHandler sweep_prm;
  geohybrid::apps::declare_sweep_parameters(sweep_prm);
  const auto sweep = geohybrid::apps::parse_sweep(input, sweep_prm);
  ASSERT_EQ(sweep.members.size(), 2u);
  const auto &second = sweep.members[1].values;
  ASSERT_EQ(second.size(), 2u);
  for (const auto &[path, value] : second)
    EXPECT_EQ(value, path == "Anchorage/L" ? "0.3" : "0.6") << path;
  fs::remove_all(d);
}

// Refused before anything is written, naming the entry: a value its entry does not take, lists of
// other lengths, a sweep of nothing, a base input that does not exist.
TEST(Sweep, BadSweepFilesNameTheEntry)
{
  const fs::path d = geohybrid::testing::fresh_test_directory("sweep");
  if (!geohybrid::testing::is_rank_zero())
    return;
  geohybrid::testing::write_fem_base_input(d);
  struct Case
  {
    std::string base, lines, top, expected;
  };
  for (const Case &c : {Case{"base.prm", "  subsection Anchorage\n    set L = 0.3, long\n  end\n", "", "'Sweep/Anchorage/L': the value 'long'"},
                        Case{"base.prm", "  subsection Anchorage\n    set type = simple run-out, wrap around\n  end\n", "",
                             "the value 'wrap around'"},
                        Case{"base.prm", "  subsection Anchorage\n    set L = 0.3, 0.4\n    set H = 0.5\n  end\n",
                             "set combination = list\n", "as many values of each entry"},
                        Case{"base.prm", "  subsection Anchorage\n    set L = 0.3, 0.3\n  end\n", "", "repeats a value"},
                        // A list may repeat one entry's value, not a whole member.
                        Case{"base.prm", "  subsection Anchorage\n    set L = 0.3, 0.3\n    set H = 0.5, 0.5\n  end\n",
                             "set combination = list\n", "values 1 and 2 of every entry are the same"},
                        Case{"base.prm", "  subsection Filling\n    set seed = 1, 1\n  end\n", "set combination = list\n",
                             "repeats a value"},
                        Case{"base.prm", "", "", "gives no values"},
                        Case{"missing.prm", "  subsection Anchorage\n    set L = 0.3\n  end\n", "", "'missing.prm' does not exist"},
                        Case{"base.prm", "  subsection Anchorage\n    set Q = 0.3\n  end\n", "", "Q"}})
    {
      const std::string message = sweep_error_of(geohybrid::testing::write_sweep_input(d, c.base, c.lines, c.top));
      EXPECT_NE(message.find(c.expected), std::string::npos) << c.lines << " -> " << message;
      EXPECT_FALSE(fs::exists(d / "sweep"));
    }
  fs::remove_all(d);
}
