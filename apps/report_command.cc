#include "report_command.h"

#include "paper_experiments.h"
#include "parameters_hash.h"
#include "plot.h"
#include "pullout_command.h"
#include "report_design.h"
#include "report_html.h"
#include "run_directory.h"
#include "summary.h"
#include "sweep_definition.h"
#include "sweep_results.h"

#include "dem/io/checked_output.h"

#include <deal.II/base/parameter_handler.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
namespace fs = std::filesystem;

bool has_prefix(const std::string &s, const std::string &head) { return s.rfind(head, 0) == 0; }

/// A directory's name as the page shows it (a trailing slash ignored).
std::string name_of(const fs::path &directory)
{
  const fs::path normal = directory.lexically_normal();
  return normal.filename().empty() ? normal.parent_path().filename().string() : normal.filename().string();
}

std::string difference_percent(double value, double reference)
{
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f %%", 100.0 * (value / reference - 1.0));
  return text;
}

/// The entries of `file` that differ from their defaults, as (path, value), read with `declare`;
/// false if the file cannot be read so (another command's, or of an older version).
bool entries_off_default(const fs::path &file, const std::function<void(dealii::ParameterHandler &)> &declare,
                         std::vector<std::vector<std::string>> &rows, dealii::ParameterHandler &prm)
{
  dealii::ParameterHandler defaults;
  declare(prm);
  declare(defaults);
  try
    {
      parse_input_file(prm, file.string());
    }
  catch (const std::exception &)
    {
      return false;
    }
  std::istringstream lines(canonical_parameters(prm, defaults, {}));
  std::string line;
  std::getline(lines, line); // numbers_version
  while (std::getline(lines, line))
    {
      const std::size_t equals = line.find(" = ");
      rows.push_back({line.substr(0, equals), line.substr(equals + 3)});
    }
  return true;
}

/// The paper's rows for a pull-out input and geohybrid's T_max against them.
std::vector<std::vector<std::string>> comparison_rows(const dealii::ParameterHandler &pullout, double T_max)
{
  std::vector<std::vector<std::string>> rows;
  for (const PaperValue &v : paper_values_for(pullout))
    rows.push_back({v.table + ", " + v.kind, paper_case_name(v), number(v.T_max_kN_per_m, 4), number(T_max, 4),
                    difference_percent(T_max, v.T_max_kN_per_m)});
  return rows;
}

const std::vector<std::string> comparison_header{"the paper", "case", "T_max [kN/m]", "geohybrid T_max [kN/m]",
                                                 "difference"};

std::string summary_cell(const nlohmann::json &value)
{
  if (value.is_null())
    return "null (not finite)";
  if (value.is_string())
    return value.get<std::string>();
  if (value.is_number())
    return number(value.get<double>(), 6);
  if (value.is_array())
    {
      std::string text;
      for (const nlohmann::json &item : value)
        text += (text.empty() ? "" : "; ") + summary_cell(item);
      return text;
    }
  return value.dump();
}

/// The PNGs of a run's directory by kind: curves, field images, others (each sorted by name).
void collect_pngs(const fs::path &directory, std::vector<fs::path> &curves, std::vector<fs::path> &fields,
                  std::vector<fs::path> &others)
{
  std::vector<fs::path> pngs;
  for (const auto &entry : fs::directory_iterator(directory))
    if (entry.is_regular_file() && entry.path().extension() == ".png")
      pngs.push_back(entry.path());
  std::sort(pngs.begin(), pngs.end());
  for (const fs::path &png : pngs)
    {
      const std::string name = png.filename().string();
      if (name.find("curve") != std::string::npos || name == "time_series.png" || name == "biaxial.png")
        curves.push_back(png);
      else if (has_prefix(name, "grain_displacements_") || has_prefix(name, "force_network_") ||
               has_prefix(name, "surface_uplift"))
        fields.push_back(png);
      else
        others.push_back(png);
    }
}

std::string run_section(const fs::path &directory)
{
  const nlohmann::json summary = read_summary(directory / "summary.json");
  const auto text = [&](const char *key) {
    const auto at = summary.find(key);
    return at != summary.end() && at->is_string() ? at->get<std::string>() : std::string();
  };
  const std::string command = text("command");
  std::string out = "<p class=\"path\">" + html::escaped(directory.string()) + "</p>\n<p>";
  for (const char *key : {"command", "mode", "anchorage"})
    if (!text(key).empty())
      out += "<b>" + std::string(key) + "</b>: " + html::escaped(text(key)) + " &nbsp; ";
  const auto T_max = summary.find("T_max_kN_per_m");
  const bool has_T_max = T_max != summary.end() && T_max->is_number();
  if (has_T_max)
    out += "<b>T_max</b>: " + number(T_max->get<double>(), 4) + " kN/m" +
           (command == "pullout --seeds" ? " (the mean over the seeds)" : "");
  out += "</p>\n";
  if (const auto warnings = summary.find("warnings"); warnings != summary.end() && warnings->is_array() && !warnings->empty())
    {
      out += "<ul class=\"warnings\">";
      for (const nlohmann::json &w : *warnings)
        out += "<li>" + html::escaped(summary_cell(w)) + "</li>";
      out += "</ul>\n";
    }

  std::vector<fs::path> curves, fields, others;
  collect_pngs(directory, curves, fields, others);
  std::string curve_figures;
  for (const fs::path &png : curves)
    curve_figures += html::png_figure(png, png.filename().string());
  if (!fs::exists(directory / "pullout_curve.png") && fs::exists(directory / "pullout_curve.csv"))
    {
      // No PNG (gnuplot was missing when it ran): the curve plotted now, into a temporary file.
      const fs::path png = fs::temp_directory_path() / ("geohybrid_report_" + std::to_string(getpid()) + "_curve.png");
      if (plot_png(png, name_of(directory), {{"head displacement [mm]", "head tension [kN/m]",
                                              {{directory / "pullout_curve.csv", 1, 2, "head tension", 1e3, 1.0}}}}))
        curve_figures += html::png_figure(png, "pullout_curve.csv, plotted by the report");
      std::error_code ignored;
      for (const fs::path &file : {png, fs::path(png.string() + ".gp")})
        fs::remove(file, ignored);
    }
  if (!curve_figures.empty())
    out += "<h3>Curves</h3>\n<div class=\"figures\">" + curve_figures + "</div>\n";

  std::vector<std::vector<std::string>> input_rows;
  dealii::ParameterHandler input;
  const bool pullout_input = has_prefix(command, "pullout") && fs::exists(directory / "parameters.prm") &&
                             entries_off_default(directory / "parameters.prm", declare_pullout_parameters, input_rows, input);
  if (pullout_input && has_T_max)
    if (const auto rows = comparison_rows(input, T_max->get<double>()); !rows.empty())
      out += "<h3>Against the paper</h3>\n" + html::table(comparison_header, rows, "comparison");

  if (!fields.empty())
    {
      out += "<h3>Fields</h3>\n<div class=\"figures\">";
      for (const fs::path &png : fields)
        out += html::png_figure(png, png.filename().string());
      out += "</div>\n";
    }
  if (!others.empty())
    {
      out += "<h3>Other figures</h3>\n<div class=\"figures\">";
      for (const fs::path &png : others)
        out += html::png_figure(png, png.filename().string());
      out += "</div>\n";
    }
  std::vector<std::vector<std::string>> figures;
  for (const auto &[key, value] : summary.items())
    if (key != "warnings")
      figures.push_back({key, summary_cell(value)});
  out += "<h3>Summary figures (summary.json)</h3>\n" + html::table({"key", "value"}, figures, "summary");
  if (fs::exists(directory / "parameters.prm"))
    {
      out += "<h3>Input</h3>\n";
      if (pullout_input)
        out += "<p>The entries off their defaults:</p>\n" + html::table({"entry", "value"}, input_rows, "input");
      out += html::file_details("the resolved input, parameters.prm", directory / "parameters.prm");
    }
  return out;
}

} // namespace

std::string report::sweep_section(const fs::path &directory, const std::string &heading)
{
  const auto titled = [&](const std::string &title) { return "<" + heading + ">" + title + "</" + heading + ">\n"; };
  std::ifstream csv(directory / "sweep.csv");
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = csv_fields(line);
  const auto column = [&](const std::string &name) -> std::size_t {
    const auto at = std::find(header.begin(), header.end(), name);
    if (at == header.end())
      throw std::runtime_error("report: " + (directory / "sweep.csv").string() + " has no column '" + name + "'");
    return static_cast<std::size_t>(at - header.begin());
  };
  const std::size_t first_entry = column("n_seeds") + 1, member_column = column("member");
  std::vector<std::vector<std::string>> members, values;
  while (std::getline(csv, line))
    {
      std::vector<std::string> fields = csv_fields(line);
      fields.resize(header.size());
      (fields[0] == "member" ? members : values).push_back(fields);
    }
  const auto is_seed = [&](std::size_t c) { return header[c] == sweep_seed_entry; };
  std::string out = "<p class=\"path\">" + html::escaped(directory.string()) + "</p>\n";
  if (fs::exists(directory / "sweep.png"))
    out += "<div class=\"figures\">" + html::png_figure(directory / "sweep.png", "sweep.png") + "</div>\n";

  // T_max over the seeds, per value, with the paper's values where the value is one of its cases
  // (read from the first of its members that has a parameters.prm).
  std::vector<std::string> value_header;
  for (std::size_t c = first_entry; c < member_column; ++c)
    value_header.push_back(is_seed(c) ? "seeds" : header[c]);
  for (const char *name : {"status", "mean T_max [kN/m]", "min", "max", "std", "the paper"})
    value_header.push_back(name);
  std::vector<std::vector<std::string>> value_rows;
  for (const std::vector<std::string> &v : values)
    {
      std::vector<std::string> row(v.begin() + static_cast<long>(first_entry), v.begin() + static_cast<long>(member_column));
      row.push_back(v[1]);
      for (const std::size_t c : {std::size_t(2), std::size_t(3), std::size_t(4), std::size_t(5)})
        row.push_back(html::short_number(v[c]));
      std::string paper;
      for (const std::vector<std::string> &m : members)
        {
          bool same = true;
          for (std::size_t c = first_entry; c < member_column; ++c)
            same = same && (is_seed(c) || m[c] == v[c]);
          std::vector<std::vector<std::string>> ignored;
          dealii::ParameterHandler input;
          if (!same || v[2].empty() ||
              !entries_off_default(directory / m[member_column] / "parameters.prm", declare_pullout_parameters, ignored, input))
            continue;
          for (const PaperValue &p : paper_values_for(input))
            paper += (paper.empty() ? "" : "; ") + p.table + " (" + p.kind + ") " + number(p.T_max_kN_per_m, 4) +
                     ": " + difference_percent(std::stod(v[2]), p.T_max_kN_per_m);
          break;
        }
      row.push_back(paper.empty() ? "-" : paper);
      value_rows.push_back(row);
    }
  out += titled("T_max over the seeds") + html::table(value_header, value_rows, "sweep-values");

  std::vector<std::string> member_header{"member"};
  for (std::size_t c = first_entry; c < member_column; ++c)
    member_header.push_back(header[c]);
  for (const char *name : {"status", "T_max [kN/m]", "message"})
    member_header.push_back(name);
  std::vector<std::vector<std::string>> member_rows;
  for (const std::vector<std::string> &m : members)
    {
      std::vector<std::string> row{m[member_column]};
      row.insert(row.end(), m.begin() + static_cast<long>(first_entry), m.begin() + static_cast<long>(member_column));
      for (const std::string &cell : {m[1], html::short_number(m[2]), m[member_column + 1]})
        row.push_back(cell);
      member_rows.push_back(row);
    }
  out += titled("Members") + html::table(member_header, member_rows, "sweep-members");
  if (fs::exists(directory / "sweep.prm"))
    {
      std::vector<std::vector<std::string>> input_rows;
      dealii::ParameterHandler input;
      out += titled("Input");
      if (entries_off_default(directory / "sweep.prm", declare_sweep_parameters, input_rows, input))
        out += html::table({"entry", "value"}, input_rows, "input");
      out += html::file_details("the resolved sweep input, sweep.prm", directory / "sweep.prm");
    }
  return out;
}

namespace
{
const char *const page_style = R"(
body { font-family: sans-serif; margin: 2em auto; max-width: 1200px; color: #222; }
h1 { border-bottom: 2px solid #456; } h2 { margin-top: 2.5em; border-bottom: 1px solid #aaa; }
.path { color: #666; font-family: monospace; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.6em; text-align: left; vertical-align: top; }
th { background: #e8edf2; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; }
figure { margin: 0; } figure img { max-width: 580px; border: 1px solid #ddd; }
figcaption { font-size: 0.85em; color: #555; }
.warnings li { color: #a40; }
pre { background: #f6f6f6; padding: 0.5em; overflow-x: auto; font-size: 0.8em; }
)";
} // namespace

void write_report(const std::vector<fs::path> &directories, const fs::path &html_file)
{
  if (directories.empty())
    throw std::runtime_error("report: no result directories given");
  std::string sections, contents;
  for (std::size_t k = 0; k < directories.size(); ++k)
    {
      const fs::path &directory = directories[k];
      // A design's directory holds a summary.json too: told apart by its design.csv first.
      const bool design = report::is_design_directory(directory), sweep = !design && fs::exists(directory / "sweep.csv");
      if (!design && !sweep && !fs::exists(directory / "summary.json"))
        throw std::runtime_error("report: '" + directory.string() +
                                 "' is not a finished run's directory (no summary.json), a sweep's (no sweep.csv) "
                                 "nor a design's (no design.csv)");
      const std::string id = "d" + std::to_string(k),
                        title = name_of(directory) + (design ? " (design)" : sweep ? " (sweep)" : "");
      contents += "<li><a href=\"#" + id + "\">" + html::escaped(title) + "</a></li>";
      sections += "<section id=\"" + id + "\">\n<h2>" + html::escaped(title) + "</h2>\n" +
                  (design  ? report::design_section(directory, id)
                   : sweep ? report::sweep_section(directory)
                           : run_section(directory)) +
                  "</section>\n";
    }
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  if (!html_file.parent_path().empty())
    fs::create_directories(html_file.parent_path());
  std::ofstream out(html_file);
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>geohybrid report</title>\n<style>"
      << page_style << "</style>\n</head>\n<body>\n<h1>geohybrid report</h1>\n<p>" << directories.size()
      << " result director" << (directories.size() > 1 ? "ies" : "y") << ", " << date
      << ". The paper: Lajevardi, Briançon, Dias et al., <i>Experimental and numerical studies for geosynthetics "
         "anchorage with wrap around</i> (Tables 3, 4: experiments; Table 6: its PFC2D).</p>\n<ul class=\"contents\">"
      << contents << "</ul>\n" << sections << "</body>\n</html>\n";
  dem::close_checked(out, html_file);
}

int run_report_command(const std::vector<std::string> &arguments)
{
  std::vector<fs::path> directories;
  fs::path html_file = "report.html";
  for (std::size_t k = 0; k < arguments.size(); ++k)
    {
      if (arguments[k] == "--output")
        {
          if (k + 1 >= arguments.size())
            throw std::runtime_error("report: --output needs a file name (FILE.html)");
          html_file = arguments[++k];
        }
      else if (has_prefix(arguments[k], "--"))
        throw std::runtime_error("report: unexpected option '" + arguments[k] +
                                 "' (usage: geohybrid report DIR1 DIR2 ... [--output FILE.html])");
      else
        directories.emplace_back(arguments[k]);
    }
  write_report(directories, html_file);
  std::cout << "wrote " << html_file.string() << " (" << directories.size() << " director"
            << (directories.size() > 1 ? "ies" : "y") << ")\n";
  return 0;
}
} // namespace geohybrid::apps
