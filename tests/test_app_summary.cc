// summary.json through nlohmann-json (apps/summary.h): numbers that read back to the same double,
// counts as integers, non-finite values as null, a nested list of warnings, and each top-level
// scalar on one `"key": value` line, which the validation campaign's shell reader
// (bench/validation_campaign.sh's summary_value, run here as it is) depends on.
#include "apps/summary.h"
#include "temporary_directory.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

namespace fs = std::filesystem;
using geohybrid::apps::read_summary;
using geohybrid::apps::Summary;
using geohybrid::testing::TemporaryDirectory;

namespace
{
/// What bench/validation_campaign.sh's summary_value prints for `key` in `file`.
std::string shell_summary_value(const fs::path &file, const std::string &key)
{
  const std::string command = "bash -c 'eval \"$(sed -n \"/^summary_value() {/,/^}/p\" " GEOHYBRID_SOURCE_DIR
                              "/bench/validation_campaign.sh)\"; summary_value \"$0\" \"$1\"' '" +
                              file.string() + "' '" + key + "'";
  std::unique_ptr<FILE, int (*)(FILE *)> pipe(popen(command.c_str(), "r"), pclose);
  std::string text;
  std::array<char, 256> buffer;
  while (pipe && fgets(buffer.data(), buffer.size(), pipe.get()))
    text += buffer.data();
  while (!text.empty() && text.back() == '\n')
    text.pop_back();
  return text;
}
} // namespace

TEST(SummaryJson, RoundTripsNumbersAndNestsWarnings)
{
  TemporaryDirectory d("summary_json");
  const double third = 1.0 / 3.0, tiny = 1.2345678901234567e-300;
  Summary summary;
  summary.set("T_max_kN_per_m", 9.36300142855123);
  summary.set("third", third);
  summary.set("tiny", tiny);
  summary.set("n_particles", 25000.0);
  summary.set("resumed_at_head_displacement_m", std::nan(""));
  summary.set("mode", "dem");
  summary.set("parameters_hash", "13c233d25deaf851");
  summary.set("DEM_region", std::vector<double>{0.0, -0.1, 1.5, std::numeric_limits<double>::infinity()});
  summary.set("warnings", std::vector<std::string>{"kinetic energy 7 % of the work", "say \"why\""});
  const fs::path file = d.path / "summary.json";
  summary.write(file);
  EXPECT_FALSE(fs::exists(d.path / "summary.json.tmp"));

  const nlohmann::json json = read_summary(file);
  EXPECT_EQ(json["third"].get<double>(), third); // every digit: the same double
  EXPECT_EQ(json["tiny"].get<double>(), tiny);
  EXPECT_EQ(json["T_max_kN_per_m"].get<double>(), 9.36300142855123);
  EXPECT_TRUE(json["n_particles"].is_number_integer());
  EXPECT_TRUE(json["resumed_at_head_displacement_m"].is_null());
  EXPECT_TRUE(json["DEM_region"][3].is_null());
  EXPECT_EQ(json["DEM_region"][1].get<double>(), -0.1);
  ASSERT_EQ(json["warnings"].size(), 2u);
  EXPECT_EQ(json["warnings"][1].get<std::string>(), "say \"why\"");

  // The shell reader of the campaign finds the top-level scalars as the old writer wrote them.
  EXPECT_EQ(shell_summary_value(file, "n_particles"), "25000");
  EXPECT_EQ(shell_summary_value(file, "parameters_hash"), "13c233d25deaf851");
  EXPECT_EQ(shell_summary_value(file, "mode"), "dem");
  EXPECT_EQ(std::stod(shell_summary_value(file, "T_max_kN_per_m")), 9.36300142855123);
  EXPECT_EQ(shell_summary_value(file, "resumed_at_head_displacement_m"), "null");

  // Sorted keys, two spaces: the text starts as the hand-made writer's did.
  std::ifstream in(file);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first, "{");
  EXPECT_EQ(second, "  \"DEM_region\": [");
}

TEST(SummaryJson, ReadRefusesWhatIsNotJsonNamingTheFile)
{
  TemporaryDirectory d("summary_json_bad");
  const fs::path file = d.path / "summary.json";
  std::ofstream(file) << "{\n  \"mode\": \"dem\",\n";
  try
    {
      read_summary(file);
      FAIL() << "a cut summary was read";
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
  EXPECT_THROW(read_summary(d.path / "none.json"), std::runtime_error);
}
