#pragma once
// The inputs of the sweep, design and report tests (test_app_sweep.cc, test_app_design.cc,
// test_app_report.cc): a fem-mode base input on a small tank, whose members take about a second
// each, a sweep file over it, and their CSV outputs read back by column name.
#include "apps/sweep_results.h"
#include "temporary_directory.h"
#include "text_file.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace geohybrid::testing
{
inline bool is_rank_zero() { return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0; }

/// Rank 0's pid on every rank: the ranks of one mpirun share a directory, no other run does.
inline long rank_zero_pid()
{
  long pid = static_cast<long>(::getpid());
  MPI_Bcast(&pid, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  return pid;
}

/// A fresh directory geohybrid_test_app_<command>_<test name>_<pid>, made by rank 0, seen by every rank.
inline std::filesystem::path fresh_test_directory(const std::string &command)
{
  const std::string name = "test_app_" + command + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const long pid = rank_zero_pid();
  if (is_rank_zero())
    fresh_directory(name, pid);
  MPI_Barrier(MPI_COMM_WORLD);
  return scratch_path(name, pid);
}

/// A CSV file's rows (sweep.csv, design.csv) as maps from its header's names to the fields.
inline std::vector<std::map<std::string, std::string>> csv_rows_by_name(const std::filesystem::path &csv)
{
  const std::vector<std::string> lines = lines_of(csv);
  std::vector<std::map<std::string, std::string>> rows;
  if (lines.empty())
    return rows;
  const std::vector<std::string> header = apps::csv_fields(lines[0]);
  for (std::size_t k = 1; k < lines.size(); ++k)
    {
      const std::vector<std::string> fields = apps::csv_fields(lines[k]);
      std::map<std::string, std::string> row;
      for (std::size_t c = 0; c < header.size() && c < fields.size(); ++c)
        row[header[c]] = fields[c];
      rows.push_back(row);
    }
  return rows;
}

/// A run-out in a 0.6 m x 1 m tank of elastic soil (E = 20 MPa, nu = 0.3, 15.2 kN/m3), 50 mm
/// cells, the sheet (GT230, delta = 25.6 deg, nodes every 25 mm) at H = 0.775 m over L = 0.55 m,
/// pulled 4 mm at 4 mm/s: test_app_pullout_fem.cc's tank, whose T_max reaches the interface's
/// geostatic limit 2 gamma H tan(delta) L.
inline std::string write_fem_base_input(const std::filesystem::path &directory)
{
  const std::filesystem::path file = directory / "base.prm";
  std::ofstream(file) << "set output directory = " << (directory / "base_out").string() << "\n"
                      << "set mode = fem\n"
                      << "subsection Tank\n  set length = 0.6\n  set fill height = 1.0\nend\n"
                      << "subsection Anchorage\n  set H = 0.775\n  set L = 0.55\nend\n"
                      << "subsection Pull\n  set rate = 0.004\n  set final displacement = 0.004\n"
                      << "  set record interval = 0.0005\n  set ramp displacement = 0\n"
                      << "  set tension profiles at = 0.002, 0.004\nend\n"
                      << "subsection Continuum\n  set cell size = 0.05\n  set sheet node spacing = 0.025\n"
                      << "  set soil model = linear elastic\n  set Young modulus = 20e6\n  set Poisson ratio = 0.3\nend\n";
  return file.string();
}

/// A sweep file beside the base input (named relative to it), into DIRECTORY/sweep, with `lines`
/// inside its subsection Sweep and `top` at its top level.
inline std::string write_sweep_input(const std::filesystem::path &directory, const std::string &base_name,
                                     const std::string &lines, const std::string &top = "")
{
  const std::filesystem::path file = directory / "sweep_input.prm";
  std::ofstream(file) << "set base input = " << base_name << "\n"
                      << "set output directory = " << (directory / "sweep").string() << "\n"
                      << top << "subsection Sweep\n" << lines << "end\n";
  return file.string();
}
} // namespace geohybrid::testing
