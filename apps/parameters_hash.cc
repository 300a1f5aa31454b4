#include "parameters_hash.h"

#include <deal.II/base/parameter_handler.h>

#include "pullout_command.h"

#include <algorithm>
#include <map>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
std::uint64_t fnv1a_64(const std::string &text)
{
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : text)
    {
      hash ^= static_cast<unsigned char>(c);
      hash *= 0x100000001b3ULL;
    }
  return hash;
}

namespace
{
std::string trimmed(const std::string &s)
{
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos)
    return "";
  return s.substr(first, s.find_last_not_of(" \t") + 1 - first);
}
} // namespace

std::vector<std::pair<std::string, std::string>> parameter_entries(const dealii::ParameterHandler &prm)
{
  // ShortPRM: the values without the documentation, so that rewording an entry's description
  // does not change the hash of every run. Its lines are "subsection NAME", "set NAME = VALUE"
  // (padded to align the '=') and "end".
  std::ostringstream printed;
  prm.print_parameters(printed, dealii::ParameterHandler::OutputStyle::ShortPRM);
  std::istringstream lines(printed.str());
  std::vector<std::string> path;
  std::vector<std::pair<std::string, std::string>> entries;
  for (std::string line; std::getline(lines, line);)
    {
      line = trimmed(line);
      if (line.empty() || line[0] == '#')
        continue;
      if (line.rfind("subsection ", 0) == 0)
        path.push_back(trimmed(line.substr(11)));
      else if (line == "end" && !path.empty())
        path.pop_back();
      else if (line.rfind("set ", 0) == 0 && line.find('=') != std::string::npos)
        {
          const std::size_t equals = line.find('=');
          std::string entry;
          for (const std::string &subsection : path)
            entry += subsection + '/';
          entry += trimmed(line.substr(4, equals - 4));
          entries.emplace_back(entry, trimmed(line.substr(equals + 1)));
        }
      else
        throw std::logic_error("canonical_parameters: unexpected line '" + line + "' in ParameterHandler's output");
    }
  if (!path.empty())
    throw std::logic_error("canonical_parameters: subsection '" + path.back() + "' not closed in ParameterHandler's output");
  return entries;
}

namespace
{
/// Entries whose former default became an automatic one that gives the same numbers wherever
/// the former gave any: hashed as at their default, so that inputs and parameters.prm files that
/// spell the former out keep their hash. 'Hybrid/lift thickness' = 0.05 (auto takes those lifts
/// whenever the fill takes their grains: coupling/particle_box.h).
bool is_former_default(const std::string &entry, const std::string &value)
{
  return entry == "Hybrid/lift thickness" && value == "0.05";
}
} // namespace

std::string canonical_parameters(const dealii::ParameterHandler &prm, const dealii::ParameterHandler &defaults,
                                 const std::vector<std::string> &excluded)
{
  const auto declared = parameter_entries(defaults);
  std::map<std::string, std::string> default_of(declared.begin(), declared.end());
  std::string canonical = std::string(numbers_version) + '\n';
  for (const auto &[entry, value] : parameter_entries(prm))
    {
      if (std::find(excluded.begin(), excluded.end(), entry) != excluded.end())
        continue;
      const auto d = default_of.find(entry);
      if (d != default_of.end() && (d->second == value || is_former_default(entry, value)))
        continue; // at its declared default: an entry added later with its default leaves the hash
      canonical += entry + " = " + value + '\n';
    }
  return canonical;
}

std::string parameters_hash(const dealii::ParameterHandler &prm, const dealii::ParameterHandler &defaults,
                            const std::vector<std::string> &excluded)
{
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(fnv1a_64(canonical_parameters(prm, defaults, excluded))));
  return hex;
}

const std::vector<std::string> &pullout_run_control_entries()
{
  static const std::vector<std::string> entries{"output directory", "threads", "checkpoint interval", "stop after steps",
                                                 "Filling/lift cache directory", "Output/demonstration",
                                                 "Output/full-size runs"};
  return entries;
}

std::string pullout_parameters_hash(const dealii::ParameterHandler &prm)
{
  dealii::ParameterHandler defaults;
  declare_pullout_parameters(defaults);
  return parameters_hash(prm, defaults, pullout_run_control_entries());
}
} // namespace geohybrid::apps
