#include "resume_check.h"

#include "parameters_hash.h"
#include "pullout_command.h"
#include "run_directory.h"

#include <deal.II/base/parameter_handler.h>

#include "dem/laboratory/pullout_tank.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
/// The lines "entry = value" of an input record (the first, numbers_version, left out).
std::map<std::string, std::string> record_entries(const std::string &record)
{
  std::map<std::string, std::string> entries;
  std::istringstream lines(record);
  std::string line;
  std::getline(lines, line); // numbers_version
  while (std::getline(lines, line))
    {
      const std::size_t equals = line.find(" = ");
      if (equals != std::string::npos)
        entries[line.substr(0, equals)] = line.substr(equals + 3);
    }
  return entries;
}

/// The value of `entry` in a record: its own, or the declared default when it has none (empty
/// if `entry` is not declared any more); `shown` says which, quoted.
std::string value_in(const std::map<std::string, std::string> &entries, const std::string &entry,
                     const dealii::ParameterHandler &defaults, std::string &shown)
{
  const auto found = entries.find(entry);
  if (found != entries.end())
    {
      shown = "'" + found->second + "'";
      return found->second;
    }
  try
    {
      const std::string value = get_parameter(defaults, entry);
      shown = "'" + value + "' (default)";
      return value;
    }
  catch (...)
    {
      shown = "(not an entry of this version)";
      return "";
    }
}
} // namespace

void store_input(const dealii::ParameterHandler &prm, const dealii::ParameterHandler &defaults,
                 dem::CommandState &command)
{
  command.texts[checkpoint_input_key] = canonical_parameters(prm, defaults, {});
}

std::optional<std::string> differing_entries(const dem::CommandState &saved, const dealii::ParameterHandler &prm,
                                             const dealii::ParameterHandler &defaults,
                                             const std::vector<std::string> &may_differ)
{
  const auto stored = saved.texts.find(checkpoint_input_key);
  if (stored == saved.texts.end())
    return std::nullopt;
  const std::map<std::string, std::string> then = record_entries(stored->second),
                                           now = record_entries(canonical_parameters(prm, defaults, {}));
  std::set<std::string> entries;
  for (const auto &e : then)
    entries.insert(e.first);
  for (const auto &e : now)
    entries.insert(e.first);
  const auto allowed = [&](const std::string &entry) {
    return std::any_of(may_differ.begin(), may_differ.end(), [&](const std::string &m) {
      return m == entry || (!m.empty() && m.back() == '/' && entry.rfind(m, 0) == 0);
    });
  };
  std::string differing;
  for (const std::string &entry : entries)
    {
      if (allowed(entry))
        continue;
      std::string then_shown, now_shown;
      if (value_in(then, entry, defaults, then_shown) == value_in(now, entry, defaults, now_shown))
        continue;
      differing += std::string(differing.empty() ? "" : "; ") + "'" + entry + "' = " + now_shown +
                   " (checkpoint: " + then_shown + ")";
    }
  return differing;
}

void check_resumed_input(const dem::CommandState &saved, const dealii::ParameterHandler &prm,
                         const dealii::ParameterHandler &defaults, const std::vector<std::string> &may_differ,
                         const std::filesystem::path &checkpoint, const std::string &where, const std::string &command)
{
  const std::optional<std::string> differing = differing_entries(saved, prm, defaults, may_differ);
  if (!differing)
    {
      // The validation campaign's checkpoints in flight were written so: they must still resume.
      std::cout << command << ": " << checkpoint.string()
                << " was written before checkpoints kept their input: resuming it without checking that " << where
                << " is the input that made it" << std::endl;
      return;
    }
  if (differing->empty())
    return;
  std::string allowed;
  for (const std::string &entry : may_differ)
    allowed += (allowed.empty() ? "'" : ", '") + entry + "'";
  throw std::invalid_argument("cannot resume from '" + checkpoint.string() + "': " + where +
                              " differs from the input of the run that wrote it in entries that change its results: " +
                              *differing + ". Only " + allowed +
                              " may change on resuming; give the checkpoint's values, or run it again without --resume "
                              "(with --overwrite)");
}

const std::vector<std::string> &dem_resume_entries()
{
  static const std::vector<std::string> entries{"output directory",          "threads",
                                                "Simulation/checkpoint interval", "Simulation/end time",
                                                "Simulation/output interval", "Simulation/snapshot interval"};
  return entries;
}

const std::vector<std::string> &pullout_filled_tank_resume_entries()
{
  static const std::vector<std::string> entries = [] {
    std::vector<std::string> e = pullout_run_control_entries();
    e.insert(e.end(), {"Pull/rate", "Pull/grain local damping", "Pull/sheet local damping"});
    return e;
  }();
  return entries;
}
void store_pullout_input(const dealii::ParameterHandler &prm, dem::CommandState &command)
{
  dealii::ParameterHandler defaults;
  declare_pullout_parameters(defaults);
  store_input(prm, defaults, command);
}

void check_pullout_checkpoint(const std::filesystem::path &file, const dealii::ParameterHandler &prm,
                              const std::string &where)
{
  dem::CommandState saved;
  std::optional<dem::PullProgress> progress;
  try
    {
      saved = dem::read_checkpoint_command(file);
      progress = dem::restore_pull_progress(saved);
    }
  catch (const std::exception &e)
    {
      throw std::runtime_error("cannot resume from '" + file.string() + "' with " + where + ": " + e.what());
    }
  dealii::ParameterHandler defaults;
  declare_pullout_parameters(defaults);
  check_resumed_input(saved, prm, defaults,
                      progress && progress->n_steps == 0 ? pullout_filled_tank_resume_entries()
                                                         : pullout_run_control_entries(),
                      file, where, "geohybrid pullout");
}
bool holds_same_pullout_run(const std::filesystem::path &directory, const dealii::ParameterHandler &prm)
{
  const std::filesystem::path file = directory / "parameters.prm";
  if (!std::filesystem::is_regular_file(file))
    return false;
  dealii::ParameterHandler there;
  declare_pullout_parameters(there);
  try
    {
      parse_input_file(there, file.string());
    }
  catch (const std::exception &)
    {
      return false; // not a parameter file of this version: not known to be the same run
    }
  return pullout_parameters_hash(there) == pullout_parameters_hash(prm);
}
} // namespace geohybrid::apps
