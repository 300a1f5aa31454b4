#pragma once
// dem_bench's parts (bench/dem_bench.cc: the command line, the deposition and the timed runs;
// dem_bench_packing.cc: the packing file and the initial arrangement; dem_bench_lammps.cc: the
// LAMMPS input and the comparison of final states): the benchmark's fixed setup, and what one part
// calls in another.
#include "dem/dem_system.h"

#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace dem_bench
{
// ---- the benchmark's fixed setup -------------------------------------------------------------
inline constexpr double r_min       = 1.5e-3;  // [m]
inline constexpr double r_max       = 2.5e-3;  // [m]
inline constexpr double density     = 2650.0;  // [kg/m^3]
inline constexpr double box_width   = 1.0;     // [m]
inline constexpr double wall_height = 3.0;     // side walls reach well above the packing [m]
inline constexpr double kn          = 7.0e7;   // [N/m/m]
inline constexpr double friction_deg = 10.0;
inline constexpr double gravity     = 9.81;
// dt = 0.5 sqrt(m_min / kn), the step of every measurement in bench/RESULTS.md: the critical step
// of discs with ks = kn / 2 is sqrt(m / kn) / sqrt(3) (a dense-packing bound), so 0.866 of it.
inline constexpr double dt_safety   = 0.5 * 1.7320508075688772;
inline constexpr int packing_version = 2;      // bump when the deposition procedure changes

// ---- command line ----------------------------------------------------------------------------
struct Args
{
  std::map<std::string, std::string> values;
  std::string get(const std::string &key, const std::string &fallback = "") const
  {
    auto it = values.find(key);
    if (it != values.end())
      return it->second;
    if (fallback.empty())
      throw std::invalid_argument("missing option --" + key);
    return fallback;
  }
  bool flag(const std::string &key) const { return values.count(key) > 0; }
};

// ---- packing file (dem_bench_packing.cc) ------------------------------------------------------
struct Packing
{
  std::vector<double> x, y, r;
  std::map<std::string, std::string> info; // header key=value pairs
};

void write_packing(const std::string &path, const Packing &p);
/// false if there is no file at `path`.
bool read_packing(const std::string &path, Packing &p);
geohybrid::dem::ParticleSet to_particles(const Packing &p);
/// n discs in the box by the geometric "drop and roll", numbered row by row.
Packing drop_and_roll(std::size_t n, unsigned seed);

// ---- the timed phase (dem_bench.cc) -----------------------------------------------------------
/// Loads the packing into a fresh system configured for the timed phase.
geohybrid::dem::DemSystem timed_system(const Packing &packing, int threads, bool track_energy, bool shuffle,
                                       bool sort);

// ---- LAMMPS (dem_bench_lammps.cc) -------------------------------------------------------------
int write_lammps(const Args &a);
int compare(const Args &a);
} // namespace dem_bench
