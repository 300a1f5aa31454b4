#include "sweep_definition.h"

#include "parameters_hash.h"
#include "run_directory.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

std::vector<std::string> split_path(const std::string &path)
{
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t slash; (slash = path.find('/', start)) != std::string::npos; start = slash + 1)
    parts.push_back(path.substr(start, slash - start));
  parts.push_back(path.substr(start));
  return parts;
}

std::string trimmed_value(const std::string &s)
{
  const auto first = s.find_first_not_of(" \t");
  return first == std::string::npos ? "" : s.substr(first, s.find_last_not_of(" \t") + 1 - first);
}

/// The values of a swept entry: separated by ';' if there is one (list-valued entries; a final ';'
/// ends the last value), else by ','.
std::vector<std::string> split_values(const std::string &text)
{
  const char separator = text.find(';') != std::string::npos ? ';' : ',';
  std::vector<std::string> values;
  std::size_t start = 0;
  for (std::size_t at; (at = text.find(separator, start)) != std::string::npos; start = at + 1)
    values.push_back(trimmed_value(text.substr(start, at - start)));
  values.push_back(trimmed_value(text.substr(start)));
  if (separator == ';' && values.back().empty() && values.size() > 1)
    values.pop_back(); // "0.006, 0.02;": one value that is a list
  return values;
}

/// A value as part of a directory name: letters, digits, '.', '+' and '-' kept, anything else '-'.
std::string name_part(const std::string &text)
{
  std::string part;
  for (const char c : text)
    part += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-') ? c : '-';
  return part;
}

} // namespace

std::vector<std::string> sweepable_entries()
{
  ParameterHandler pullout;
  declare_pullout_parameters(pullout);
  const std::vector<std::string> &excluded = pullout_run_control_entries();
  std::vector<std::string> paths;
  for (const auto &[path, value] : parameter_entries(pullout))
    if (std::find(excluded.begin(), excluded.end(), path) == excluded.end())
      paths.push_back(path);
  return paths;
}

std::string resolve_base_input(const std::string &input_file, const std::string &base)
{
  const std::filesystem::path beside = std::filesystem::path(input_file).parent_path() / base;
  if (std::filesystem::path(base).is_relative() && std::filesystem::is_regular_file(beside))
    return beside.lexically_normal().string();
  return base;
}

void declare_pullout_entry_texts(ParameterHandler &prm, const std::string &head, const std::string &tail)
{
  for (const std::string &path : sweepable_entries())
    {
      const std::vector<std::string> parts = split_path(path);
      for (std::size_t k = 0; k + 1 < parts.size(); ++k)
        prm.enter_subsection(parts[k]);
      prm.declare_entry(parts.back(), "", Patterns::Anything(),
                        head + " of the pull-out's entry '" + path + "' (geohybrid pullout --print-parameters gives "
                        "its meaning)" + tail);
      for (std::size_t k = 0; k + 1 < parts.size(); ++k)
        prm.leave_subsection();
    }
}

void declare_sweep_parameters(ParameterHandler &prm)
{
  prm.declare_entry("base input", "", Patterns::Anything(),
                    "The pull-out input every member runs (geohybrid pullout's file), relative to the sweep file's "
                    "directory (or, if not there, to the working directory); its own output directory is replaced "
                    "by the member's");
  prm.declare_entry("output directory", "output/sweep", Patterns::Anything(),
                    "Directory of the sweep: one directory per member, sweep.csv, sweep.png, sweep.prm");
  prm.declare_entry("combination", "grid", Patterns::Selection("grid|list"),
                    "grid: every combination of the swept entries' values; list: the k-th values of every entry "
                    "together (the entries then have as many values each). 'Filling/seed' is crossed with the "
                    "others either way: it is the replicate dimension, averaged over in sweep.csv");
  prm.enter_subsection("Sweep");
  declare_pullout_entry_texts(prm, "Values", ", separated by commas (by semicolons if a value is itself a list); empty: the "
                                   "base input's value");
  prm.leave_subsection();
}

SweepDefinition parse_sweep(const std::string &input_file, ParameterHandler &prm)
{
  parse_input_file(prm, input_file);
  return make_sweep(input_file, prm);
}

SweepDefinition make_sweep(const std::string &input_file, const ParameterHandler &prm)
{
  const std::string where = "input file '" + input_file + "'";
  SweepDefinition sweep;
  sweep.input_file = input_file;
  sweep.output_directory = prm.get("output directory");
  if (sweep.output_directory.empty())
    throw std::runtime_error(where + ": 'output directory' is empty");
  sweep.grid = prm.get("combination") == "grid";
  const std::string base = prm.get("base input");
  if (base.empty())
    throw std::runtime_error(where + ": 'base input' is empty: name the pull-out input the members run");
  sweep.base_input = resolve_base_input(input_file, base);
  ParameterHandler pullout; // the base input, read as its run reads it: its errors named now
  declare_pullout_parameters(pullout);
  parse_input_file(pullout, sweep.base_input);

  std::optional<SweptEntry> seeds;
  for (const std::string &path : sweepable_entries())
    {
      const std::string text = trimmed_value(get_parameter(prm, "Sweep/" + path));
      if (text.empty())
        continue;
      SweptEntry entry{path, split_values(text)};
      for (const std::string &value : entry.values)
        {
          if (value.empty())
            throw std::runtime_error(where + ": 'Sweep/" + path + "' = '" + text + "' has an empty value");
          try
            {
              set_parameter(pullout, path, value); // its pattern checks it
            }
          catch (const std::exception &)
            {
              throw std::runtime_error(where + ": 'Sweep/" + path + "': the value '" + value +
                                       "' is not one that '" + path + "' takes (geohybrid pullout --print-parameters)");
            }
        }
      // A grid (and the seeds) would run one member twice; a list may repeat a value of one
      // entry (B = 0.25 at two depths): there the members' whole tuples must differ (below).
      if ((sweep.grid || path == sweep_seed_entry) &&
          std::set<std::string>(entry.values.begin(), entry.values.end()).size() != entry.values.size())
        throw std::runtime_error(where + ": 'Sweep/" + path + "' = '" + text + "' repeats a value");
      if (path == sweep_seed_entry)
        seeds = entry;
      else
        sweep.entries.push_back(entry);
    }
  // The entries with several values first (the first is sweep.png's x axis), those with one (a
  // plain override of the base input) after them, the seed last.
  std::stable_partition(sweep.entries.begin(), sweep.entries.end(),
                        [](const SweptEntry &e) { return e.values.size() > 1; });
  if (seeds)
    sweep.entries.push_back(*seeds);
  if (sweep.entries.empty())
    throw std::runtime_error(where + ": subsection Sweep gives no values: set at least one entry, as "
                                     "'subsection Sweep / subsection Anchorage / set B = 0.25, 0.5'");
  const std::size_t n_varied = sweep.n_varied();
  if (!sweep.grid)
    for (std::size_t e = 1; e < n_varied; ++e)
      if (sweep.entries[e].values.size() != sweep.entries[0].values.size())
        throw std::runtime_error(where + ": 'combination' = list needs as many values of each entry: 'Sweep/" +
                                 sweep.entries[0].path + "' has " + std::to_string(sweep.entries[0].values.size()) +
                                 ", 'Sweep/" + sweep.entries[e].path + "' " +
                                 std::to_string(sweep.entries[e].values.size()));

  // The combinations of the varied entries, as indices into their values: the first entry
  // fastest (a block of sweep.png's curve), the last slowest.
  std::vector<std::vector<std::size_t>> combinations;
  if (n_varied == 0)
    combinations.emplace_back();
  else if (!sweep.grid)
    {
      std::map<std::vector<std::string>, std::size_t> seen;
      for (std::size_t k = 0; k < sweep.entries[0].values.size(); ++k)
        {
          combinations.emplace_back(n_varied, k);
          std::vector<std::string> tuple;
          for (std::size_t e = 0; e < n_varied; ++e)
            tuple.push_back(sweep.entries[e].values[k]);
          const auto [at, inserted] = seen.emplace(tuple, k);
          if (!inserted)
            throw std::runtime_error(where + ": 'combination' = list: values " + std::to_string(at->second + 1) + " and " +
                                     std::to_string(k + 1) + " of every entry are the same: one member would run twice");
        }
    }
  else
    {
      std::vector<std::size_t> digit(n_varied, 0);
      for (bool more = true; more;)
        {
          combinations.push_back(digit);
          more = false;
          for (std::size_t e = 0; e < n_varied && !more; ++e)
            if (++digit[e] < sweep.entries[e].values.size())
              more = true;
            else
              digit[e] = 0;
        }
    }
  // Directory names: each entry by its last name (its whole path if two share one) and value;
  // the entries of one value only if no entry has more.
  std::map<std::string, int> last_names;
  std::set<std::string> named;
  for (const SweptEntry &e : sweep.entries)
    if (e.values.size() > 1 || sweep.entries.front().values.size() == 1)
      {
        ++last_names[split_path(e.path).back()];
        named.insert(e.path);
      }
  const auto label = [&](const std::string &path) {
    const std::string last = split_path(path).back();
    return name_part(last_names[last] > 1 ? path : last);
  };
  const std::vector<std::string> seed_values = seeds ? seeds->values : std::vector<std::string>{""};
  std::set<std::string> names;
  for (const std::vector<std::size_t> &combination : combinations)
    for (const std::string &seed : seed_values)
      {
        SweepMember member;
        member.index = sweep.members.size();
        for (std::size_t e = 0; e < n_varied; ++e)
          member.values.emplace_back(sweep.entries[e].path, sweep.entries[e].values[combination[e]]);
        if (seeds)
          member.values.emplace_back(sweep_seed_entry, seed);
        for (const auto &[path, value] : member.values)
          if (named.count(path) != 0)
            member.name += (member.name.empty() ? "" : "_") + label(path) + "_" + name_part(value);
        names.insert(member.name);
        sweep.members.push_back(member);
      }
  if (names.size() != sweep.members.size()) // values that differ only in characters a name drops
    for (SweepMember &member : sweep.members)
      member.name = "member_" + std::to_string(member.index) + "_" + member.name;
  return sweep;
}

ParameterOverrides member_overrides(const SweepDefinition &sweep, const SweepMember &member)
{
  ParameterOverrides overrides = member.values;
  overrides.emplace_back("output directory", (sweep.output_directory / member.name).string());
  return overrides;
}

void read_member_input(const SweepDefinition &sweep, const SweepMember &member, ParameterHandler &prm)
{
  declare_pullout_parameters(prm);
  parse_input_file(prm, sweep.base_input);
  for (const auto &[path, value] : member_overrides(sweep, member))
    set_parameter(prm, path, value);
}
} // namespace geohybrid::apps
