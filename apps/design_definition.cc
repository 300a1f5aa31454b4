#include "design_definition.h"

#include "run_directory.h"
#include "sweep_definition.h"

#include <algorithm>
#include <cmath>
#include <locale>
#include <set>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

std::string trimmed_design_text(const std::string &s)
{
  const auto first = s.find_first_not_of(" \t");
  return first == std::string::npos ? "" : s.substr(first, s.find_last_not_of(" \t") + 1 - first);
}

/// The number of 'Design/<name>', read here rather than by a pattern, so that a missing or
/// negative value is refused with the entry's meaning and the file.
double design_number(const ParameterHandler &prm, const std::string &name, const std::string &where)
{
  const std::string text = trimmed_design_text(get_parameter(prm, "Design/" + name));
  if (text.empty())
    throw std::runtime_error(where + ": 'Design/" + name + "' is not set");
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  double value = 0.0;
  if (!(in >> value) || !(in >> std::ws).eof() || !std::isfinite(value))
    throw std::runtime_error(where + ": 'Design/" + name + "' = '" + text + "' is not a number");
  return value;
}

[[noreturn]] void refuse(const std::string &where, const std::string &name, double value, const std::string &why)
{
  throw std::runtime_error(where + ": 'Design/" + name + "' = " + number(value) + " " + why);
}
} // namespace

std::string design_value_text(double value) { return number(value, 10); }

void declare_design_parameters(ParameterHandler &prm)
{
  prm.declare_entry("base input", "", Patterns::Anything(),
                    "The pull-out input every run starts from (geohybrid pullout's file), relative to the design "
                    "file's directory (or, if not there, to the working directory); its mode (dem, fem or hybrid) is "
                    "the design's");
  prm.declare_entry("output directory", "output/design", Patterns::Anything(),
                    "Directory of the design: design.csv, design.png, summary.json, design.prm, design_base.prm, "
                    "and one sweep directory per value tried (B_0.3, ...)");
  prm.enter_subsection("Design");
  prm.declare_entry("entry", "B", Patterns::Anything(),
                    "The entry sized: B (a wrap-around's upper part, Anchorage/B) or L (the sheet's lower part, "
                    "Anchorage/L, a run-out's length) [-]");
  prm.declare_entry("minimum", "", Patterns::Anything(), "The bracket's lower end, positive [m]");
  prm.declare_entry("maximum", "", Patterns::Anything(),
                    "The bracket's upper end: B shorter than L, L shorter than 'Tank/length' [m]");
  prm.declare_entry("target T_max", "", Patterns::Anything(),
                    "The maximum head tension to reach, positive [kN/m]");
  prm.declare_entry("margin factor", "1", Patterns::Anything(),
                    "k of the criterion mean - k std >= target, over the seeds' T_max (sample standard deviation; "
                    "0 for one run per value), not negative [-]");
  prm.declare_entry("tolerance", "", Patterns::Anything(),
                    "The bisection stops when the highest value that fails and the lowest that meets the "
                    "criterion are this close; positive, below maximum - minimum [m]");
  prm.declare_entry("seeds", "", Patterns::Anything(),
                    "Filling/seed values each value is run with, comma-separated (dem and hybrid modes; fem mode "
                    "runs once per value); empty: the base input's seed, once [-]");
  prm.leave_subsection();
  prm.enter_subsection("Overrides");
  declare_pullout_entry_texts(prm, "A value",
                              " for every run, in place of the base input's; empty: the base input's value. Not the "
                              "sized entry, nor Filling/seed (Design/seeds)");
  prm.leave_subsection();
}

void read_design_base(const DesignDefinition &design, ParameterHandler &pullout)
{
  declare_pullout_parameters(pullout);
  parse_input_file(pullout, design.base_input);
  for (const auto &[path, value] : design.overrides)
    set_parameter(pullout, path, value);
}

DesignDefinition parse_design(const std::string &input_file, ParameterHandler &prm)
{
  parse_input_file(prm, input_file);
  const std::string where = "input file '" + input_file + "'";
  DesignDefinition d;
  d.input_file = input_file;
  d.output_directory = prm.get("output directory");
  if (d.output_directory.empty())
    throw std::runtime_error(where + ": 'output directory' is empty");
  const std::string base = trimmed_design_text(prm.get("base input"));
  if (base.empty())
    throw std::runtime_error(where + ": 'base input' is empty: name the pull-out input the runs start from");
  d.base_input = resolve_base_input(input_file, base);

  d.entry_name = trimmed_design_text(get_parameter(prm, "Design/entry"));
  if (d.entry_name != "B" && d.entry_name != "L")
    throw std::runtime_error(where + ": 'Design/entry' = '" + d.entry_name +
                             "' is not one a design sizes: B (a wrap-around's upper part) or L (the sheet's lower "
                             "part, a run-out's length)");
  d.entry = "Anchorage/" + d.entry_name;

  for (const std::string &path : sweepable_entries())
    {
      const std::string value = trimmed_design_text(get_parameter(prm, "Overrides/" + path));
      if (value.empty())
        continue;
      if (path == d.entry || path == "Filling/seed")
        throw std::runtime_error(where + ": 'Overrides/" + path + "' is set by the design (" +
                                 (path == d.entry ? "Design/minimum and maximum" : "Design/seeds") + "): remove it");
      d.overrides.emplace_back(path, value);
    }
  ParameterHandler pullout; // the base input, read as its runs read it: its errors name it
  declare_pullout_parameters(pullout);
  parse_input_file(pullout, d.base_input);
  for (const auto &[path, value] : d.overrides)
    try
      {
        set_parameter(pullout, path, value); // its pattern checks it
      }
    catch (const std::exception &)
      {
        throw std::runtime_error(where + ": 'Overrides/" + path + "' = '" + value + "' is not a value that '" + path +
                                 "' takes (geohybrid pullout --print-parameters)");
      }
  d.mode = pullout.get("mode");

  d.minimum = design_number(prm, "minimum", where);
  d.maximum = design_number(prm, "maximum", where);
  d.target_kN = design_number(prm, "target T_max", where);
  d.margin_factor = design_number(prm, "margin factor", where);
  d.tolerance = design_number(prm, "tolerance", where);
  if (!(d.minimum > 0.0))
    refuse(where, "minimum", d.minimum, "m must be positive");
  if (!(d.maximum > d.minimum))
    refuse(where, "maximum", d.maximum, "m must be above 'Design/minimum' = " + number(d.minimum) + " m");
  if (!(d.target_kN > 0.0))
    refuse(where, "target T_max", d.target_kN, "kN/m must be positive");
  if (!(d.margin_factor >= 0.0))
    refuse(where, "margin factor", d.margin_factor, "must not be negative (the criterion is mean - k std >= target)");
  if (!(d.tolerance > 0.0 && d.tolerance < d.maximum - d.minimum))
    refuse(where, "tolerance", d.tolerance,
           "m must be positive and below the bracket's width, maximum - minimum = " + number(d.maximum - d.minimum) + " m");

  // The bracket in the tank, with the base input's geometry.
  const double L = std::stod(get_parameter(pullout, "Anchorage/L"));
  const double B = std::stod(get_parameter(pullout, "Anchorage/B"));
  const double tank_length = std::stod(get_parameter(pullout, "Tank/length"));
  const bool wrap_around = get_parameter(pullout, "Anchorage/type") == "wrap-around";
  const std::string base_where = " (the base input '" + d.base_input + "'";
  if (d.entry_name == "B")
    {
      if (!wrap_around)
        throw std::runtime_error(where + ": 'Design/entry' = B sizes a wrap-around's upper part, but the base input '" +
                                 d.base_input + "' is a simple run-out: size L, or set 'Anchorage/type' = wrap-around");
      if (!(d.maximum < L))
        refuse(where, "maximum", d.maximum,
               "m does not fit the tank: B must be shorter than L = " + number(L) + " m" + base_where +
                 "), as the upper part runs back from the return towards the front wall");
    }
  else
    {
      if (!(d.maximum < tank_length))
        refuse(where, "maximum", d.maximum,
               "m does not fit the tank: L must be shorter than 'Tank/length' = " + number(tank_length) + " m" +
                 base_where + ")");
      if (wrap_around && !(d.minimum > B))
        refuse(where, "minimum", d.minimum,
               "m does not fit the wrap-around: L must be longer than B = " + number(B) + " m" + base_where + ")");
    }

  // The seeds: the replicate dimension of dem and hybrid modes.
  const std::string seed_text = trimmed_design_text(get_parameter(prm, "Design/seeds"));
  for (const std::string &seed : dealii::Utilities::split_string_list(seed_text, ','))
    {
      const bool digits = !seed.empty() && seed.find_first_not_of("0123456789") == std::string::npos;
      if (!digits)
        throw std::runtime_error(where + ": 'Design/seeds' = '" + seed_text + "': '" + seed +
                                 "' is not a seed (a whole number, not negative)");
      d.seeds.push_back(seed);
    }
  if (std::set<std::string>(d.seeds.begin(), d.seeds.end()).size() != d.seeds.size())
    throw std::runtime_error(where + ": 'Design/seeds' = '" + seed_text + "' repeats a seed");
  if (d.mode == "fem" && !d.seeds.empty())
    {
      d.notes.push_back("mode = fem: the continuum does not see the seed, so each value is run once ('Design/seeds' "
                        "ignored) and the spread over the seeds is 0");
      d.seeds.clear();
    }
  if (d.mode != "fem" && d.seeds.size() < 2 && d.margin_factor > 0.0)
    refuse(where, "margin factor", d.margin_factor,
           "needs a spread over the seeds, and 'Design/seeds' gives " + std::to_string(d.seeds.size()) + " in mode = " +
             d.mode + ": give two seeds or more, or 'margin factor' = 0");

  // Either end as a run of it would check it (the mesh, the fill's layers, ...): a refusal now,
  // not a failed run after others have been made.
  for (const double value : {d.minimum, d.maximum})
    {
      ParameterOverrides overrides = d.overrides;
      overrides.emplace_back(d.entry, design_value_text(value));
      if (!d.seeds.empty())
        overrides.emplace_back("Filling/seed", d.seeds.front());
      try
        {
          check_pullout_input(d.base_input, MPI_COMM_SELF, overrides);
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error(where + ": 'Design/" + (value == d.minimum ? "minimum" : "maximum") + "' = " +
                                   number(value) + ": the base input with " + d.entry_name + " = " +
                                   design_value_text(value) + " is refused: " + e.what());
        }
    }
  return d;
}
} // namespace geohybrid::apps
