// `geohybrid coupling-test` end to end (issue 6): for each coupling method, the summary's figures
// are those of the library's benchmarks (coupling/coupling_benchmarks.h) for the same input, and
// within what coupling/README.md documents; the histories are written; bad input is refused
// naming the entry and the file, with no output directory left behind.
#include "apps/coupling_test_command.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
namespace bench = geohybrid::coupling::benchmarks;

namespace coupling_app_test
{
/// The input of examples/coupling_test.prm (the defaults; a second on one core): the patch of 12
/// rows, band 4 spacings, cells of 2; a strip of 40 spacings on each side of the band, the pulse 4
/// spacings wide; 10,000 undamped steps.
fs::path write_input(const fs::path &directory, const std::string &method, const std::string &extra = "")
{
  const fs::path file = directory / "coupling_test.prm";
  std::ofstream(file) << "set output directory = " << (directory / "out").string() << "\n"
                      << "set method = " << method << "\n"
                      << extra;
  return file;
}

std::string error_of(const fs::path &file)
{
  try
    {
      geohybrid::apps::run_coupling_test_command(file.string(), false);
    }
  catch (const std::exception &e)
    {
      return e.what();
    }
  return "";
}

double summary_number(const fs::path &file, const std::string &key)
{
  const std::string s = geohybrid::testing::read_text(file);
  const auto at = s.find("\"" + key + "\": ");
  if (at == std::string::npos)
    return std::nan("");
  return std::stod(s.substr(at + key.size() + 4));
}

std::vector<std::vector<double>> csv_rows(const fs::path &file)
{
  std::vector<std::vector<double>> rows;
  const std::vector<std::string> lines = geohybrid::testing::lines_of(file);
  for (std::size_t k = 1; k < lines.size(); ++k)
    {
      std::vector<double> row;
      std::istringstream in(lines[k]);
      for (std::string field; std::getline(in, field, ',');)
        row.push_back(std::stod(field));
      rows.push_back(row);
    }
  return rows;
}

/// The figures the library gives for the input `file` (read by the command's own parser).
struct LibraryFigures
{
  bench::PatchTestResult patch;
  bench::WaveRecord wave;
  bench::EnergyRecord energy;
};
LibraryFigures library_figures(const fs::path &file)
{
  dealii::ParameterHandler prm;
  geohybrid::apps::declare_coupling_test_parameters(prm);
  prm.parse_input(file.string());
  const geohybrid::apps::CouplingTestInput in = geohybrid::apps::parse_coupling_test(prm, file.string());
  return {bench::patch_test(in.method, in.strain, in.patch), bench::strip_crossing(in.method, in.strip, in.patch),
          bench::energy_record(in.method, in.n_energy_steps, 0.0, in.patch)};
}

/// Runs the command for `method` and checks its files against the library; returns the summary.
fs::path run_and_compare(const fs::path &directory, const std::string &method)
{
  const fs::path input = write_input(directory, method);
  EXPECT_EQ(error_of(input), "");
  const fs::path out = directory / "out", summary = out / "summary.json";
  EXPECT_TRUE(fs::exists(summary));
  EXPECT_NE(geohybrid::testing::read_text(summary).find("\"method\": \"" + method + "\""), std::string::npos);
  EXPECT_NE(geohybrid::testing::read_text(out / "parameters.prm").find("set method"), std::string::npos);

  // The same code on the same input: equal to the 12 digits the summary keeps.
  const LibraryFigures library = library_figures(input);
  const auto same = [&](const std::string &key, double expected) {
    EXPECT_NEAR(summary_number(summary, key), expected, 1e-10 * std::abs(expected)) << key;
  };
  same("max_ghost_force_relative", library.patch.ghost.largest());
  same("reflected_energy_fraction", library.wave.reflected);
  same("energy_drift_relative", library.energy.drift);
  EXPECT_EQ(summary_number(summary, "n_particles"), static_cast<double>(library.patch.n_particles));
  EXPECT_EQ(summary_number(summary, "n_cells"), 4.0 * 5.0); // 8 x 10.4 spacings in cells of ~2
  EXPECT_GT(summary_number(summary, "wall_time_s"), 0.0);

  // The histories: the energy every 10 steps from t = 0, the wave's ~200 samples ending at the figure.
  const auto energy = csv_rows(out / "energy_history.csv");
  EXPECT_EQ(energy.size(), 10000u / 10u + 1u);
  EXPECT_EQ(energy.front()[1], 0.0);
  EXPECT_NEAR(energy.back()[0], 10000 * library.energy.time_step, 1e-9 * energy.back()[0]);
  const auto wave = csv_rows(out / "wave_reflection.csv");
  EXPECT_GE(wave.size(), 100u);
  EXPECT_NEAR(wave.back()[1], library.wave.reflected, 1e-10 * library.wave.reflected);
  EXPECT_LT(wave.front()[1], 1e-20); // nothing reflected before the pulse moves
  return summary;
}

// coupling/README.md, measured on the same patch: ghost forces 1.86e-2 at the continuum's nodes
// (both methods: the penalty springs are slack under a uniform strain), 4.5e-7 on the untied
// discs; a long wave (pulse 4 spacings wide) reflected at 1.5e-4 with the multipliers, 4.7e-3 with
// penalty; the targets: reflection below 1e-2, drift below 1e-4 over 10,000 steps
// (measured: 2.0e-6, penalty -4.4e-6).
TEST(CouplingTestCommand, LagrangeMultipliersFiguresAreTheLibrarys)
{
  const geohybrid::testing::TemporaryDirectory d("coupling_test_lagrange");
  const fs::path summary = run_and_compare(d.path, "Lagrange multipliers");
  EXPECT_NEAR(summary_number(summary, "max_ghost_force_relative"), 1.86e-2, 0.05 * 1.86e-2);
  EXPECT_LT(summary_number(summary, "ghost_force_untied_discs_relative"), 1e-6);
  EXPECT_LT(summary_number(summary, "reflected_energy_fraction"), 1e-3); // 1.5e-4
  EXPECT_GT(summary_number(summary, "wave_energy_in_continuum_fraction"), 0.9); // the pulse did cross
  EXPECT_LT(std::abs(summary_number(summary, "energy_drift_relative")), 1e-5);  // 2.0e-6
  EXPECT_GT(summary_number(summary, "energy_continuum_share_max"), 0.5);
}

TEST(CouplingTestCommand, PenaltyFiguresAreTheLibrarys)
{
  const geohybrid::testing::TemporaryDirectory d("coupling_test_penalty");
  const fs::path summary = run_and_compare(d.path, "penalty");
  EXPECT_NEAR(summary_number(summary, "max_ghost_force_relative"), 1.86e-2, 0.05 * 1.86e-2);
  EXPECT_LT(summary_number(summary, "reflected_energy_fraction"), 1e-2);        // 4.7e-3
  EXPECT_GT(summary_number(summary, "wave_energy_in_continuum_fraction"), 0.9);
  EXPECT_LT(std::abs(summary_number(summary, "energy_drift_relative")), 1e-5);  // -4.4e-6
}

// The example is the defaults (what the tests above run), with its own output directory.
TEST(CouplingTestCommand, ExampleIsTheDefaults)
{
  const fs::path example = fs::path(GEOHYBRID_MESH_DIR) / ".." / "examples" / "coupling_test.prm";
  dealii::ParameterHandler defaults, read;
  geohybrid::apps::declare_coupling_test_parameters(defaults);
  geohybrid::apps::declare_coupling_test_parameters(read);
  read.parse_input(example.string());
  EXPECT_EQ(read.get("output directory"), "output/coupling_test_lagrange");
  EXPECT_EQ(read.get("method"), defaults.get("method"));
  const std::vector<std::pair<std::string, std::vector<std::string>>> numbers{
    {"Particles", {"normal stiffness", "shear stiffness", "disc radius", "density"}},
    {"Band", {"width", "cell size"}},
    {"Penalty", {"factor"}},
    {"Patch test", {"strain xx", "strain yy", "strain xy"}},
    {"Wave", {"pulse width", "strip length", "cell size"}},
    {"Energy", {"number of undamped steps"}}};
  for (const auto &[subsection, entries] : numbers)
    {
      read.enter_subsection(subsection);
      defaults.enter_subsection(subsection);
      for (const std::string &entry : entries)
        EXPECT_EQ(read.get_double(entry), defaults.get_double(entry)) << subsection << "/" << entry;
      read.leave_subsection();
      defaults.leave_subsection();
    }
}

TEST(CouplingTestCommand, BadInputIsRefusedByNameWithNoOutput)
{
  const geohybrid::testing::TemporaryDirectory d("coupling_test_bad");
  struct Case
  {
    std::string method, extra, named;
  };
  const std::vector<Case> cases{
    {"penalty", "set band width = 4\n", "band width"},                                   // unknown parameter
    {"penalty", "subsection Particles\n  set normal stiffness = -1e8\nend\n", "normal stiffness"},
    {"penalty", "subsection Band\n  set width = 1.5\nend\n", "width"},                   // narrower than 2 spacings
    {"springs", "", "method"},                                                           // unknown method
    {"penalty", "subsection Penalty\n  set factor = 0\nend\n", "factor"},
    {"penalty", "subsection Wave\n  set pulse width = 8\nend\n", "strip length"},        // the pulse does not fit
    {"penalty", "subsection Patch test\n  set strain xx = 0\n  set strain yy = 0\n  set strain xy = 0\nend\n", "strain"},
  };
  for (const Case &c : cases)
    {
      const fs::path input = write_input(d.path, c.method, c.extra);
      const std::string message = error_of(input);
      EXPECT_NE(message.find(c.named), std::string::npos) << c.named << ": " << message;
      EXPECT_NE(message.find(input.string()), std::string::npos) << message;
      EXPECT_FALSE(fs::exists(d.path / "out")) << c.named;
    }
  // No checkpoint to resume from.
  EXPECT_THROW(geohybrid::apps::run_coupling_test_command(write_input(d.path, "penalty").string(), true),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(d.path / "out"));
}
} // namespace coupling_app_test
