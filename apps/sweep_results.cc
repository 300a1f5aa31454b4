#include "sweep_results.h"

#include "plot.h"
#include "run_directory.h"
#include "spread.h"

#include "dem/io/checked_output.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
/// The number of columns before the entries' in sweep.csv.
constexpr int n_number_columns = 7;

std::string optional_cell(const std::optional<double> &value) { return value ? number(*value) : ""; }

/// The number of members per value of the varied entries (the seeds), and the number of values.
std::size_t n_seeds_of(const SweepDefinition &sweep)
{
  return sweep.sweeps_seeds() ? sweep.entries.back().values.size() : 1;
}
} // namespace

std::string csv_field(const std::string &text)
{
  std::string field;
  for (const char c : text)
    field += (c == '\n' || c == '\r') ? ' ' : c;
  if (field.find_first_of(",\"") == std::string::npos)
    return field;
  std::string quoted = "\"";
  for (const char c : field)
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::vector<std::string> csv_fields(const std::string &line)
{
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k)
    {
      const char c = line[k];
      if (quoted && c == '"' && k + 1 < line.size() && line[k + 1] == '"')
        fields.back() += line[++k];
      else if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        fields.emplace_back();
      else if (c != '\r')
        fields.back() += c;
    }
  return fields;
}

void write_sweep_table(const SweepDefinition &sweep, const std::vector<MemberOutcome> &outcomes,
                       const std::filesystem::path &csv)
{
  std::ofstream out(csv);
  out << "row,status,T_max_kN_per_m,T_max_min_kN_per_m,T_max_max_kN_per_m,T_max_std_kN_per_m,n_seeds";
  for (const SweptEntry &entry : sweep.entries)
    out << ',' << csv_field(entry.path);
  out << ",member,message\n";
  for (std::size_t m = 0; m < sweep.members.size(); ++m)
    {
      const MemberOutcome &o = outcomes[m];
      out << "member," << o.status << ',' << optional_cell(o.T_max_kN) << ",,,,";
      for (const auto &[path, value] : sweep.members[m].values)
        out << ',' << csv_field(value);
      out << ',' << csv_field(sweep.members[m].name) << ',' << csv_field(o.message) << '\n';
    }
  // The members come in blocks of their seeds (sweep_definition.h): one row per block.
  const std::size_t n_seeds = n_seeds_of(sweep);
  for (std::size_t first = 0; first < sweep.members.size(); first += n_seeds)
    {
      std::vector<double> T_max;
      std::string seeds, failed;
      for (std::size_t m = first; m < first + n_seeds; ++m)
        {
          if (outcomes[m].T_max_kN)
            {
              T_max.push_back(*outcomes[m].T_max_kN);
              if (sweep.sweeps_seeds())
                seeds += (seeds.empty() ? "" : " ") + sweep.members[m].values.back().second;
            }
          if (outcomes[m].status == "failed")
            failed += (failed.empty() ? "failed: " : ", ") + sweep.members[m].name;
        }
      const std::string status = T_max.empty()             ? std::string("no result")
                                 : !sweep.sweeps_seeds()    ? std::string("one run")
                                 : T_max.size() == n_seeds ? "all " + std::to_string(n_seeds) + " seeds"
                                                           : std::to_string(T_max.size()) + " of " + std::to_string(n_seeds) + " seeds";
      out << "over seeds," << status;
      if (T_max.empty())
        out << ",,,,,0";
      else
        {
          const Spread s = spread_of(T_max);
          out << ',' << number(s.mean) << ',' << number(s.min) << ',' << number(s.max) << ','
              << (T_max.size() > 1 ? number(s.std) : "") << ',' << T_max.size();
        }
      const ParameterOverrides &values = sweep.members[first].values;
      for (std::size_t e = 0; e < sweep.n_varied(); ++e)
        out << ',' << csv_field(values[e].second);
      if (sweep.sweeps_seeds())
        out << ',' << seeds;
      out << ",," << csv_field(failed) << '\n';
    }
  dem::close_checked(out, csv);
}

bool plot_sweep(const SweepDefinition &sweep, const std::filesystem::path &csv, const std::filesystem::path &png)
{
  if (sweep.n_varied() == 0)
    {
      std::cerr << "note: " << png.string() << " not drawn: the sweep varies only the seed (sweep.csv has its spread)\n";
      return false;
    }
  const SweptEntry &x = sweep.entries[0];
  for (const std::string &value : x.values)
    {
      char *end = nullptr;
      std::strtod(value.c_str(), &end);
      if (end == value.c_str() || *end != '\0')
        {
          std::cerr << "note: " << png.string() << " not drawn: '" << x.path << "' = '" << value
                    << "' is not a number to plot against (sweep.csv has the results)\n";
          return false;
        }
    }
  const std::size_t n_members = sweep.members.size(), n_seeds = n_seeds_of(sweep);
  const std::size_t n_rows = n_members / n_seeds;
  const std::size_t block = sweep.grid ? x.values.size() : n_rows; // one curve per block
  const int x_column = n_number_columns + 1;
  const auto rows = [](std::size_t first, std::size_t last) {
    return "::" + std::to_string(first) + "::" + std::to_string(last);
  };
  PlotPanel panel{x.path, "T_max [kN/m]", {}, "set termoption noenhanced\nset key outside bottom center horizontal\n"
                                               "set offsets graph 0.05, graph 0.05, graph 0.1, graph 0.1"};
  panel.series.push_back({csv, x_column, 3, sweep.sweeps_seeds() ? "each seed" : "each member", 1.0, 1.0,
                          "points pt 7 ps 0.8 lc rgb 'gray40'", {}, {}, rows(0, n_members - 1)});
  for (std::size_t first = 0, curve = 1; first < n_rows; first += block, ++curve)
    {
      // The curve's label: the values of the other varied entries, if any.
      std::string label;
      const ParameterOverrides &values = sweep.members[first * n_seeds].values;
      for (std::size_t e = 1; e < sweep.n_varied(); ++e)
        if (sweep.entries[e].values.size() > 1) // an override of one value is every curve's
          label += (label.empty() ? "" : ", ") + values[e].first + " = " + values[e].second;
      const std::string colour = " lc " + std::to_string(curve);
      const std::string range = rows(n_members + first, n_members + first + block - 1);
      panel.series.push_back({csv, x_column, 3, label.empty() ? "mean over the seeds" : label + ": mean", 1.0, 1.0,
                              "linespoints lw 2 pt 5" + colour, {}, {}, range});
      if (n_seeds > 1)
        panel.series.push_back({csv, x_column, 3, label.empty() ? "min - max" : label + ": min - max", 1.0, 1.0,
                                "yerrorbars lw 1.5 ps 0" + colour, {4, 5}, {}, range});
    }
  return plot_png(png, "Maximum head tension against " + x.path + (n_seeds > 1 ? ", " + std::to_string(n_seeds) + " seeds per value" : ""),
                  {panel});
}
} // namespace geohybrid::apps
