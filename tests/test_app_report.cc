// `geohybrid report` (issue 24, section 4): one self-contained HTML page of a run and a sweep,
// loaded in a real headless browser (Debian's chromium, scripts/setup_debian.sh), whose DOM must
// hold the figures as PNG data URIs, the tables, and the comparison with the paper's Tables 3 and
// 6 for a run of their case.
#include "apps/pullout_command.h"
#include "apps/run_directory.h"
#include "apps/summary.h"
#include "apps/sweep_command.h"
#include "sweep_test_inputs.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace
{
std::size_t occurrences(const std::string &text, const std::string &what)
{
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size()))
    ++n;
  return n;
}

/// A finished run's directory as a fem pull-out writes it, made here: the input of Table 3's GT230
/// wrap-around, D1 = 0.2 m, H = 0.4 m, B = 0.25 m in sand 1, T_max 12.78 kN/m, its curve without
/// its PNG (the report plots it), one warning with characters HTML must escape.
void write_table3_run(const fs::path &run)
{
  fs::create_directories(run);
  dealii::ParameterHandler prm;
  geohybrid::apps::declare_pullout_parameters(prm);
  for (const auto &[path, value] : std::vector<std::pair<std::string, std::string>>{
         {"mode", "fem"}, {"Anchorage/type", "wrap-around"}, {"Anchorage/H", "0.4"}, {"Anchorage/D1", "0.2"},
         {"Anchorage/D2", "0.2"}, {"Anchorage/B", "0.25"}, {"Sheet/axial stiffness", "2.104e6"}, {"Soil/unit weight", "15.2e3"}})
    geohybrid::apps::set_parameter(prm, path, value);
  geohybrid::apps::write_resolved_parameters(prm, run);
  geohybrid::apps::Summary summary;
  summary.set("command", "pullout");
  summary.set("mode", "fem");
  summary.set("anchorage", "wrap-around");
  summary.set("T_max_kN_per_m", 12.78);
  summary.set("warnings", std::vector<std::string>{"a <warning> & more"});
  summary.write(run / "summary.json");
  std::ofstream(run / "pullout_curve.csv") << "head_displacement_m,head_tension_kN_per_m\n0,0\n0.01,9.5\n0.02,12.78\n0.03,12.1\n";
}
} // namespace

// About 3 s: two fem members and one headless browser.
TEST(Report, PageOfARunAndASweepLoadsInABrowser)
{
  const char *const chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium))
    GTEST_SKIP() << chromium << " is not installed (scripts/setup_debian.sh installs it)";
  geohybrid::testing::TemporaryDirectory d("report");
  const fs::path run = d.path / "gt230_h040_b025";
  write_table3_run(run);
  geohybrid::testing::write_fem_base_input(d.path);
  const std::string sweep_input = geohybrid::testing::write_sweep_input(
    d.path, "base.prm", "  subsection Anchorage\n    set L = 0.3, 0.55\n  end\n");
  ASSERT_EQ(geohybrid::apps::run_sweep_command(sweep_input, false, MPI_COMM_SELF), 0);

  // The command itself, as a user runs it.
  const fs::path page = d.path / "report.html";
  const std::string report = std::string(GEOHYBRID_EXECUTABLE) + " report '" + run.string() + "' '" +
                             (d.path / "sweep").string() + "' --output '" + page.string() + "' > '" +
                             (d.path / "report.log").string() + "' 2>&1";
  ASSERT_EQ(std::system(report.c_str()), 0) << geohybrid::testing::read_text(d.path / "report.log");

  // The page as the browser reads it: its DOM once loaded.
  const fs::path dom_file = d.path / "dom.html";
  const std::string browse = "timeout 120 " + std::string(chromium) + " --headless --no-sandbox --disable-gpu --user-data-dir='" +
                             (d.path / "chromium").string() + "' --dump-dom 'file://" + page.string() + "' > '" +
                             dom_file.string() + "' 2> '" + (d.path / "chromium.log").string() + "'";
  ASSERT_EQ(std::system(browse.c_str()), 0) << geohybrid::testing::read_text(d.path / "chromium.log");
  const std::string dom = geohybrid::testing::read_text(dom_file);
  // Two figures, each a PNG ("iVBORw0KGgo" is its signature in base64): the run's curve, plotted
  // by the report, and sweep.png. Six tables: the run's comparison, summary and input; the
  // sweep's values, members and input.
  EXPECT_EQ(occurrences(dom, "<img src=\"data:image/png;base64,iVBORw0KGgo"), 2u) << dom.substr(0, 2000);
  EXPECT_EQ(occurrences(dom, "<img"), 2u);
  EXPECT_EQ(occurrences(dom, "<table"), 6u);
  // 12.78 kN/m against Table 3's 14.2 (-10.0 %) and Table 6's 16.4 (-22.1 %).
  EXPECT_NE(dom.find("<td>Table 3, experiment</td><td>GT230 wrap-around in sand 1, D1 = 0.2 m, H = 0.4 m, B = 0.25 m</td>"
                     "<td>14.2</td><td>12.78</td><td>-10.0 %</td>"),
            std::string::npos);
  EXPECT_NE(dom.find("<td>Table 6, the paper's PFC2D</td><td>GT230 wrap-around in sand 1, D1 = 0.2 m, H = 0.4 m, "
                     "B = 0.25 m</td><td>16.4</td><td>12.78</td><td>-22.1 %</td>"),
            std::string::npos);
  EXPECT_EQ(occurrences(dom, "<td>Table "), 2u); // no other case of the paper
  EXPECT_NE(dom.find("a &lt;warning&gt; &amp; more"), std::string::npos);
  // The sweep's members, each finished, in its table.
  for (const char *member : {"<td>L_0.3</td>", "<td>L_0.55</td>"})
    EXPECT_NE(dom.find(member), std::string::npos) << member;
  EXPECT_EQ(occurrences(dom, "<td>finished</td>"), 2u);
}
