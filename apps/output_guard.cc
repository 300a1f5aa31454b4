#include "output_guard.h"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <system_error>

namespace geohybrid::apps
{
namespace
{
bool overwrite_flag = false;

bool ends_with(const std::string &s, const std::string &tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool starts_with(const std::string &s, const std::string &head) { return s.rfind(head, 0) == 0; }

/// seed_N, N decimal digits: a member of a --seeds ensemble.
bool is_seed_directory(const std::string &name)
{
  return name.size() > 5 && starts_with(name, "seed_") &&
         name.find_first_not_of("0123456789", 5) == std::string::npos;
}

/// The files geohybrid writes whose names are fixed, every command's (apps/*_command.cc, the
/// pull-out's outputs, dem/snapshot_writer's pairs).
const std::set<std::string> &fixed_names()
{
  static const std::set<std::string> names{
    "summary.json", "parameters.prm", "checkpoint.h5", "filled_tank.h5", "filled_box.h5",
    // dem
    "time_series.csv", "time_series.png", "particle_history.csv", "final_particles.csv", "particles.h5",
    "particles.xdmf",
    // pullout
    "pullout_curve.csv", "pullout_curve.png", "pullout_curve_sheet.csv", "sheet_displacements.csv",
    "sheet_tension.csv", "experimental_T_max.csv", "reference_curve.csv", "pullout_forces.csv", "coupling_diagnostics.csv",
    "pullout_fields.h5", "pullout_fields.xdmf", "surface_uplift.csv", "surface_uplift.png",
    // biaxial, calibrate (its default fragment name), coupling-test
    "biaxial.png", "continuum_soil.prm", "calibration.csv", "calibrated_soil.prm", "energy_history.csv",
    "wave_reflection.csv",
    // sweep
    "sweep.csv", "sweep.png", "sweep.prm",
    // design (its values' sweeps are directories of their own)
    "design.csv", "design.png", "design.prm", "design_base.prm"};
  return names;
}
} // namespace

void set_overwrite_output(bool overwrite) { overwrite_flag = overwrite; }

bool overwrite_output() { return overwrite_flag; }

bool is_run_file(const std::string &name)
{
  // A plot's gnuplot script (FILE.png.gp, its .log) and a temporary file (FILE.tmp) of a run file.
  for (const char *tail : {".gp.log", ".gp", ".tmp"})
    if (ends_with(name, tail) && name.size() > std::char_traits<char>::length(tail))
      return is_run_file(name.substr(0, name.size() - std::char_traits<char>::length(tail)));
  if (fixed_names().count(name) != 0 || is_seed_directory(name) || name == "snapshots")
    return true;
  // The field outputs at each head displacement, the biaxial tests at each confinement.
  return starts_with(name, "grain_displacements_") || starts_with(name, "force_network_") ||
         (starts_with(name, "biaxial_") && ends_with(name, "kPa.csv"));
}

std::vector<std::filesystem::path> run_files(const std::filesystem::path &directory)
{
  std::vector<std::filesystem::path> files;
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error))
    return files;
  for (const auto &entry : std::filesystem::directory_iterator(directory, error))
    {
      const std::string name = entry.path().filename().string();
      if (!is_run_file(name))
        continue;
      if (!entry.is_directory(error))
        files.push_back(entry.path());
      else if (name == "snapshots") // fem mode's VTU files, named pullout_*
        {
          for (const auto &inner : std::filesystem::directory_iterator(entry.path(), error))
            if (starts_with(inner.path().filename().string(), "pullout"))
              files.push_back(inner.path());
        }
      else // a seed of an ensemble: a run directory of its own
        {
          const std::vector<std::filesystem::path> inner = run_files(entry.path());
          files.insert(files.end(), inner.begin(), inner.end());
        }
    }
  std::sort(files.begin(), files.end());
  return files;
}

void claim_output_directory(const std::filesystem::path &directory, bool resume)
{
  const std::vector<std::filesystem::path> files = run_files(directory);
  if (files.empty() || resume)
    return;
  if (!overwrite_flag)
    {
      std::string listed;
      for (std::size_t k = 0; k < files.size() && k < 4; ++k)
        listed += (k ? ", " : "") + files[k].lexically_relative(directory).string();
      if (files.size() > 4)
        listed += " and " + std::to_string(files.size() - 4) + " more";
      throw std::runtime_error("output directory '" + directory.string() + "' holds the files of another run (" +
                               listed + "): give --overwrite to remove them first (only the files geohybrid "
                               "writes), --resume to continue that run, or another 'output directory'");
    }
  for (const std::filesystem::path &file : files)
    {
      std::error_code error;
      std::filesystem::remove(file, error);
      if (error)
        throw std::runtime_error("--overwrite: cannot remove '" + file.string() + "': " + error.message());
    }
  // The seed_N and snapshots directories left empty (one with a user's file in it stays).
  std::error_code error;
  for (const auto &entry : std::filesystem::directory_iterator(directory, error))
    if (entry.is_directory(error) && is_run_file(entry.path().filename().string()) &&
        std::filesystem::is_empty(entry.path(), error))
      std::filesystem::remove(entry.path(), error);
}
} // namespace geohybrid::apps
