// `geohybrid report` (issue 24, section 4): one self-contained HTML page of a run and a sweep,
// loaded in a real headless browser (Debian's chromium, scripts/setup_debian.sh), whose DOM must
// hold the figures as PNG data URIs, the tables, and the comparison with the paper's Tables 3 and
// 6 for a run of their case; the page of a small fem design (its answer, design.png, its table's
// numbers, each value's sweep) and of a design stopped by a failed run; a directory of no kind
// the report knows refused by name.
#include "apps/design_command.h"
#include "apps/design_results.h"
#include "apps/pullout_command.h"
#include "apps/report_command.h"
#include "apps/report_html.h"
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
#include <map>

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

const char *const chromium = "/usr/bin/chromium";

/// `page` as the browser reads it: its DOM once loaded (chromium's profile and log in `scratch`);
/// empty, with a failure, if the browser fails.
std::string dom_of(const fs::path &page, const fs::path &scratch)
{
  const fs::path dom_file = scratch / "dom.html";
  const std::string browse = "timeout 120 " + std::string(chromium) + " --headless --no-sandbox --disable-gpu --user-data-dir='" +
                             (scratch / "chromium").string() + "' --dump-dom 'file://" + page.string() + "' > '" +
                             dom_file.string() + "' 2> '" + (scratch / "chromium.log").string() + "'";
  if (std::system(browse.c_str()) != 0)
    {
      ADD_FAILURE() << geohybrid::testing::read_text(scratch / "chromium.log");
      return "";
    }
  return geohybrid::testing::read_text(dom_file);
}

/// Runs `geohybrid report ARGUMENTS` as a user does, its output in `log`; returns its exit status.
int run_report(const std::string &arguments, const fs::path &log)
{
  const std::string command = std::string(GEOHYBRID_EXECUTABLE) + " report " + arguments + " > '" + log.string() + "' 2>&1";
  return std::system(command.c_str());
}

/// The text from `open` to the next `close` after it in `text`; empty if either is missing.
std::string between(const std::string &text, const std::string &open, const std::string &close)
{
  const std::size_t from = text.find(open);
  const std::size_t to = from == std::string::npos ? std::string::npos : text.find(close, from);
  return to == std::string::npos ? std::string() : text.substr(from, to - from);
}

/// A number of a results CSV as the page shows it (4 digits); an empty cell stays empty.
std::string four_digits(const std::string &cell) { return cell.empty() ? cell : geohybrid::apps::number(std::stod(cell), 4); }

/// The row the design's table must show for a row of design.csv (by column name; `value` is the
/// value's column, B_m or L_m).
std::string expected_design_row(const std::map<std::string, std::string> &row, const std::string &value)
{
  std::string expected = "<tr><td>" + row.at("step") + "</td><td>" + row.at(value) + "</td>";
  for (const char *name : {"T_max_kN_per_m", "T_max_std_kN_per_m", "T_max_min_kN_per_m", "T_max_max_kN_per_m"})
    expected += "<td>" + four_digits(row.at(name)) + "</td>";
  return expected + "<td>" + row.at("n_runs") + "</td><td>" + four_digits(row.at("criterion_kN_per_m")) + "</td><td>" +
         four_digits(row.at("target_kN_per_m")) + "</td><td>" + row.at("met") + "</td><td>" + row.at("directory") +
         "</td><td>" + geohybrid::apps::html::escaped(row.at("message")) + "</td></tr>";
}
} // namespace

// About 3 s: two fem members and one headless browser.
TEST(Report, PageOfARunAndASweepLoadsInABrowser)
{
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
  ASSERT_EQ(run_report("'" + run.string() + "' '" + (d.path / "sweep").string() + "' --output '" + page.string() + "'",
                       d.path / "report.log"),
            0)
    << geohybrid::testing::read_text(d.path / "report.log");

  // The page as the browser reads it: its DOM once loaded.
  const std::string dom = dom_of(page, d.path);
  ASSERT_FALSE(dom.empty());
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

// A small fem design (the design tests' tank: four values of L, about 5 s) and its section: the
// outcome and the answer of its summary.json, design.png inlined byte for byte, design.csv's rows
// with their numbers, a warning escaped, design.prm, and each value's sweep under an anchor of its
// own, whose member's T_max is the row's mean.
TEST(Report, PageOfADesign)
{
  geohybrid::testing::TemporaryDirectory d("report_design");
  geohybrid::testing::write_fem_base_input(d.path);
  const fs::path design = d.path / "design", input = d.path / "design_input.prm";
  std::ofstream(input) << "set base input = base.prm\nset output directory = " << design.string() << "\n"
                       << "subsection Design\n  set entry = L\n  set minimum = 0.1\n  set maximum = 0.5\n"
                       << "  set target T_max = 3\n  set tolerance = 0.1\nend\n";
  ASSERT_EQ(geohybrid::apps::run_design_command(input.string(), false, MPI_COMM_SELF), 0);
  // T_max rises with L here, so the design has no warning of its own: one added, to be escaped.
  nlohmann::json summary = geohybrid::apps::read_summary(design / "summary.json");
  summary["warnings"].push_back("T_max <falls> & rises");
  std::ofstream(design / "summary.json") << summary.dump(2) << '\n';

  const fs::path page_file = d.path / "report.html";
  ASSERT_EQ(run_report("'" + design.string() + "' --output '" + page_file.string() + "'", d.path / "report.log"), 0)
    << geohybrid::testing::read_text(d.path / "report.log");
  const std::string page = geohybrid::testing::read_text(page_file);

  const std::string answer = geohybrid::apps::number(summary.at("answer_m").get<double>(), 10);
  EXPECT_NE(page.find("<b>outcome</b>: found &nbsp; <b>answer</b>: L* = " + answer + " m"), std::string::npos)
    << page.substr(0, 4000);
  EXPECT_NE(page.find(geohybrid::apps::html::escaped(summary.at("message").get<std::string>())), std::string::npos);
  EXPECT_NE(page.find("<li>T_max &lt;falls&gt; &amp; rises</li>"), std::string::npos);
  EXPECT_NE(page.find("<img src=\"data:image/png;base64," +
                      geohybrid::apps::html::base64(geohybrid::testing::read_text(design / "design.png")) +
                      "\" alt=\"design.png\">"),
            std::string::npos);
  EXPECT_NE(page.find(geohybrid::apps::html::escaped(geohybrid::testing::read_text(design / "design.prm"))),
            std::string::npos);

  // The table: one row per row of design.csv (the ends 0.1 and 0.5, then two midpoints), its numbers.
  const auto rows = geohybrid::testing::csv_rows_by_name(design / "design.csv");
  ASSERT_EQ(rows.size(), 4u);
  const std::string table = between(page, "<table class=\"design-values\">", "</table>");
  EXPECT_EQ(occurrences(table, "<tr>"), rows.size() + 1); // the header's and one per value
  std::size_t sweep_pngs = 0;
  for (const auto &row : rows)
    {
      EXPECT_NE(table.find(expected_design_row(row, "L_m")), std::string::npos) << expected_design_row(row, "L_m") << "\n" << table;

      // The value's sweep, collapsed under its anchor: its one member finished at the row's mean.
      const std::string &sweep = row.at("directory");
      const std::string block = between(page, "<details class=\"design-value\" id=\"d0-" + sweep + "\">", "</details>");
      EXPECT_NE(block.find("<h4>T_max over the seeds</h4>"), std::string::npos) << sweep;
      EXPECT_NE(block.find("<td>" + sweep + "</td><td>" + row.at("L_m") + "</td><td>finished</td><td>" +
                           four_digits(row.at("T_max_kN_per_m")) + "</td>"),
                std::string::npos)
        << block;
      sweep_pngs += fs::exists(design / sweep / "sweep.png") ? 1 : 0;
    }
  EXPECT_EQ(occurrences(page, "<img src=\"data:image/png;base64,iVBORw0KGgo"), 1 + sweep_pngs);

  // The browser reads the same: every value's sweep and every image.
  if (fs::exists(chromium))
    {
      const std::string dom = dom_of(page_file, d.path);
      EXPECT_EQ(occurrences(dom, "<details class=\"design-value\""), rows.size());
      EXPECT_EQ(occurrences(dom, "<img src=\"data:image/png;base64,iVBORw0KGgo"), 1 + sweep_pngs);
    }
}

// A dem design stopped by a failed run, its files written by geohybrid design's own writers with
// three seeds per value (so that mean, std, min, max and the criterion differ): no answer, the
// failed value's row with its two finished runs and its message, no design.png, and each value's
// sweep said to be unfinished (no sweep.csv was written).
TEST(Report, PageOfADesignStoppedByAFailedRun)
{
  geohybrid::testing::TemporaryDirectory d("report_design_failed");
  const fs::path directory = d.path / "design_b";
  fs::create_directories(directory);
  geohybrid::apps::DesignDefinition design;
  design.entry = "Anchorage/B";
  design.entry_name = "B";
  design.minimum = 0.1;
  design.maximum = 0.4;
  design.target_kN = 12.0;
  design.margin_factor = 1.0;
  design.tolerance = 0.02;
  design.mode = "dem";
  design.seeds = {"1", "2", "3"};
  const std::string failure = "B_0.25_seed_3 failed: <a reason>";
  const std::vector<geohybrid::apps::DesignStep> steps{{0.1, "0.1", "B_0.1", {9.1, 10.4, 9.7}, 3, ""},
                                                       {0.4, "0.4", "B_0.4", {13.2, 14.9, 13.5}, 3, ""},
                                                       {0.25, "0.25", "B_0.25", {11.0, 12.1}, 3, failure}};
  geohybrid::apps::DesignAnswer answer;
  answer.outcome = "runs failed";
  answer.message = "a run at B = 0.25 m did not finish (" + failure + "), so the criterion cannot be judged there";
  geohybrid::apps::write_design_table(design, steps, directory / "design.csv");
  geohybrid::apps::write_design_summary(design, steps, answer, 61.5, directory / "summary.json");
  std::ofstream(directory / "design.prm") << "set output directory = " << directory.string() << "\n";

  const fs::path page_file = d.path / "report.html";
  geohybrid::apps::write_report({directory}, page_file);
  const std::string page = geohybrid::testing::read_text(page_file);
  EXPECT_NE(page.find("<h2>design_b (design)</h2>"), std::string::npos);
  EXPECT_NE(page.find("<b>outcome</b>: runs failed &nbsp; <b>answer</b>: none"), std::string::npos) << page;
  EXPECT_NE(page.find("did not finish (B_0.25_seed_3 failed: &lt;a reason&gt;)"), std::string::npos);
  EXPECT_NE(page.find("<b>mode</b>: dem, seeds 1, 2, 3"), std::string::npos);
  EXPECT_EQ(occurrences(page, "<img"), 0u);
  // The figures worked out by hand: mean, std, min, max over the seeds, the criterion mean - std.
  const std::string table = between(page, "<table class=\"design-values\">", "</table>");
  EXPECT_EQ(occurrences(table, "<tr>"), 4u);
  for (const char *row :
       {"<tr><td>1</td><td>0.1</td><td>9.733</td><td>0.6506</td><td>9.1</td><td>10.4</td><td>3</td><td>9.083</td>"
        "<td>12</td><td>no</td><td>B_0.1</td><td></td></tr>",
        "<tr><td>2</td><td>0.4</td><td>13.87</td><td>0.9074</td><td>13.2</td><td>14.9</td><td>3</td><td>12.96</td>"
        "<td>12</td><td>yes</td><td>B_0.4</td><td></td></tr>",
        "<tr><td>3</td><td>0.25</td><td>11.55</td><td>0.7778</td><td>11</td><td>12.1</td><td>2</td><td></td>"
        "<td>12</td><td></td><td>B_0.25</td><td>B_0.25_seed_3 failed: &lt;a reason&gt;</td></tr>"})
    EXPECT_NE(table.find(row), std::string::npos) << row << "\n" << table;
  for (const auto &row : geohybrid::testing::csv_rows_by_name(directory / "design.csv"))
    EXPECT_NE(table.find(expected_design_row(row, "B_m")), std::string::npos) << row.at("step");
  EXPECT_EQ(occurrences(page, "<p>No sweep.csv: this value's sweep did not finish.</p>"), 3u);
  EXPECT_NE(page.find("<details class=\"design-value\" id=\"d0-B_0.25\"><summary>B = 0.25 m: its sweep, B_0.25/</summary>"),
            std::string::npos);
}

// A directory that is neither a finished run's, a sweep's nor a design's (here a run that did not
// finish: its curve, no summary.json) is refused by name, after a good one, and no page is written.
TEST(Report, RefusesADirectoryOfNoKnownKind)
{
  geohybrid::testing::TemporaryDirectory d("report_refused");
  const fs::path run = d.path / "gt230_h040_b025", unfinished = d.path / "unfinished";
  write_table3_run(run);
  fs::create_directories(unfinished);
  std::ofstream(unfinished / "pullout_curve.csv") << "head_displacement_m,head_tension_kN_per_m\n0,0\n";
  const fs::path page = d.path / "report.html";
  EXPECT_NE(run_report("'" + run.string() + "' '" + unfinished.string() + "' --output '" + page.string() + "'",
                       d.path / "report.log"),
            0);
  const std::string log = geohybrid::testing::read_text(d.path / "report.log");
  EXPECT_NE(log.find("'" + unfinished.string() +
                     "' is not a finished run's directory (no summary.json), a sweep's (no sweep.csv) nor a design's "
                     "(no design.csv)"),
            std::string::npos)
    << log;
  EXPECT_FALSE(fs::exists(page));
}
