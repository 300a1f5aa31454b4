#include "report_design.h"

#include "report_command.h"
#include "report_html.h"
#include "run_directory.h"
#include "summary.h"
#include "sweep_results.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace geohybrid::apps::report
{
namespace
{
namespace fs = std::filesystem;

/// design.csv's columns that the section shows, after "step" and the value's ("B_m" or "L_m").
const std::vector<std::string> design_columns{"T_max_kN_per_m",     "T_max_std_kN_per_m", "T_max_min_kN_per_m",
                                              "T_max_max_kN_per_m", "n_runs",             "criterion_kN_per_m",
                                              "target_kN_per_m",    "met",                "directory",
                                              "message"};

/// design.csv read back: the entry it sizes ("B" or "L", from its second column's name) and its
/// rows, each cell in the order step, value, then design_columns.
struct DesignTable
{
  std::string entry_name;
  std::vector<std::vector<std::string>> rows;
};

DesignTable read_design_table(const fs::path &csv)
{
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = csv_fields(line);
  const auto is_value_column = [](const std::string &name) { return name.size() > 2 && name.substr(name.size() - 2) == "_m"; };
  if (header.size() < 2 || header[0] != "step" || !is_value_column(header[1]))
    throw std::runtime_error("report: " + csv.string() + " is not a design's table (it does not start with 'step,B_m' or 'step,L_m')");
  std::vector<std::size_t> columns{0, 1};
  for (const std::string &name : design_columns)
    {
      const auto at = std::find(header.begin(), header.end(), name);
      if (at == header.end())
        throw std::runtime_error("report: " + csv.string() + " has no column '" + name + "'");
      columns.push_back(static_cast<std::size_t>(at - header.begin()));
    }
  DesignTable table{header[1].substr(0, header[1].size() - 2), {}};
  while (std::getline(in, line))
    {
      std::vector<std::string> fields = csv_fields(line);
      fields.resize(header.size());
      std::vector<std::string> row;
      for (const std::size_t c : columns)
        row.push_back(fields[c]);
      table.rows.push_back(row);
    }
  return table;
}

/// The table of the values tried, in the order tried, numbers to 4 digits.
std::string values_table(const DesignTable &design)
{
  std::vector<std::vector<std::string>> rows;
  for (const std::vector<std::string> &r : design.rows)
    rows.push_back({r[0], r[1], html::short_number(r[2]), html::short_number(r[3]), html::short_number(r[4]),
                    html::short_number(r[5]), r[6], html::short_number(r[7]), html::short_number(r[8]), r[9], r[10],
                    r[11]});
  return html::table({"step", design.entry_name + " [m]", "mean T_max [kN/m]", "std", "min", "max", "runs",
                      "criterion [kN/m]", "target [kN/m]", "met", "sweep", "message"},
                     rows, "design-values");
}

/// The text at `key` of the summary, or empty (absent, or not a string).
std::string text_at(const nlohmann::json &summary, const char *key)
{
  const auto at = summary.find(key);
  return at != summary.end() && at->is_string() ? at->get<std::string>() : std::string();
}

/// The number at `key` of the summary to `digits`, or "?" (absent, or null: not finite).
std::string number_at(const nlohmann::json &summary, const char *key, int digits = 4)
{
  const auto at = summary.find(key);
  return at != summary.end() && at->is_number() ? number(at->get<double>(), digits) : std::string("?");
}

/// The outcome and the answer, then the design's own sentence about them.
std::string answer_in_words(const nlohmann::json &summary, const std::string &entry_name)
{
  const auto answer = summary.find("answer_m");
  const bool found = answer != summary.end() && answer->is_number();
  // The answer is a value that was run: shown as its directory names it (10 digits).
  std::string out = "<p class=\"outcome\"><b>outcome</b>: " + html::escaped(text_at(summary, "outcome")) +
                    " &nbsp; <b>answer</b>: " +
                    (found ? html::escaped(entry_name) + "* = " + number(answer->get<double>(), 10) + " m"
                           : std::string("none")) +
                    "</p>\n";
  if (const std::string message = text_at(summary, "message"); !message.empty())
    out += "<p class=\"answer\">" + html::escaped(message) + ".</p>\n";
  return out;
}

/// What the design sought and what it took: the criterion, the bracket, the runs.
std::string how_sought(const nlohmann::json &summary)
{
  std::string bracket = "?";
  if (const auto b = summary.find("bracket_m"); b != summary.end() && b->is_array() && b->size() == 2 &&
                                                (*b)[0].is_number() && (*b)[1].is_number())
    bracket = "[" + number((*b)[0].get<double>()) + ", " + number((*b)[1].get<double>()) + "] m";
  std::string seeds;
  if (const auto s = summary.find("seeds"); s != summary.end() && s->is_array())
    for (const nlohmann::json &seed : *s)
      seeds += (seeds.empty() ? "" : ", ") + (seed.is_string() ? seed.get<std::string>() : seed.dump());
  return "<p><b>criterion</b>: " + html::escaped(text_at(summary, "criterion")) + ", target " +
         number_at(summary, "target_T_max_kN_per_m") + " kN/m, k = " + number_at(summary, "margin_factor") +
         " &nbsp; <b>bracket</b>: " + bracket + ", to " + number_at(summary, "tolerance_m") + " m &nbsp; <b>mode</b>: " +
         html::escaped(text_at(summary, "mode")) + ", " +
         (seeds.empty() ? std::string("one run per value (std 0)") : "seeds " + html::escaped(seeds)) +
         " &nbsp; <b>tried</b>: " + number_at(summary, "n_values_tried") + " values, " + number_at(summary, "n_runs") +
         " runs in " + number_at(summary, "wall_time_s", 3) + " s</p>\n";
}

/// The summary's warnings (fem mode's seeds ignored, T_max falling as the value grows); none: empty.
std::string warnings_list(const nlohmann::json &summary)
{
  const auto warnings = summary.find("warnings");
  if (warnings == summary.end() || !warnings->is_array() || warnings->empty())
    return "";
  std::string out = "<ul class=\"warnings\">";
  for (const nlohmann::json &w : *warnings)
    out += "<li>" + html::escaped(w.is_string() ? w.get<std::string>() : w.dump()) + "</li>";
  return out + "</ul>\n";
}

/// Each value's sweep section, collapsed under the value and its directory, anchored as
/// `id`-<directory>; a value whose sweep did not finish (no sweep.csv) is said so.
std::string value_sweeps(const fs::path &directory, const DesignTable &design, const std::string &id)
{
  std::string out;
  for (const std::vector<std::string> &r : design.rows)
    {
      const std::string &sweep = r[10];
      const fs::path sweep_directory = directory / sweep;
      const std::string body = fs::exists(sweep_directory / "sweep.csv")
                                 ? sweep_section(sweep_directory, "h4")
                                 : "<p>No sweep.csv: this value's sweep did not finish.</p>\n";
      out += "<details class=\"design-value\" id=\"" + html::escaped(id + "-" + sweep) + "\"><summary>" +
             html::escaped(design.entry_name + " = " + r[1] + " m: its sweep, " + sweep + "/") + "</summary>\n" + body +
             "</details>\n";
    }
  return out;
}
} // namespace

bool is_design_directory(const fs::path &directory) { return fs::exists(directory / "design.csv"); }

std::string design_section(const fs::path &directory, const std::string &id)
{
  const DesignTable design = read_design_table(directory / "design.csv");
  std::string out = "<p class=\"path\">" + html::escaped(directory.string()) + "</p>\n";
  // summary.json is written last: without it the design is running or stopped, its table partial.
  if (fs::exists(directory / "summary.json"))
    {
      const nlohmann::json summary = read_summary(directory / "summary.json");
      out += answer_in_words(summary, design.entry_name) + how_sought(summary) + warnings_list(summary);
    }
  else
    out += "<p class=\"outcome\"><b>outcome</b>: none yet (no summary.json: the design is running or stopped); "
           "the values tried so far follow.</p>\n";
  if (fs::exists(directory / "design.png"))
    out += "<div class=\"figures\">" + html::png_figure(directory / "design.png", "design.png") + "</div>\n";
  out += "<h3>Values tried</h3>\n" + values_table(design);
  if (fs::exists(directory / "design.prm"))
    {
      out += "<h3>Input</h3>\n" + html::file_details("the resolved design input, design.prm", directory / "design.prm");
      if (fs::exists(directory / "design_base.prm"))
        out += html::file_details("the base input with the overrides, design_base.prm", directory / "design_base.prm");
    }
  if (!design.rows.empty())
    out += "<h3>The sweep of each value</h3>\n" + value_sweeps(directory, design, id);
  return out;
}
} // namespace geohybrid::apps::report
