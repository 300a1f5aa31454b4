#pragma once
// The input of `geohybrid design FILE.prm`: a pull-out input (the base), the entry to size and
// the criterion its runs must meet:
//
//   set base input       = wraparound.prm    # beside this file, or from the working directory
//   set output directory = output/design_B
//   subsection Design
//     set entry          = B                 # B (a wrap-around's upper part) or L (the lower part)
//     set minimum        = 0.1               # the bracket [m]
//     set maximum        = 0.5
//     set target T_max   = 5                 # [kN/m]
//     set margin factor  = 1                 # k: mean - k std of T_max over the seeds >= target
//     set tolerance      = 0.02              # [m]: the bisection stops within it
//     set seeds          = 1, 2, 3           # dem and hybrid modes; empty: the base input's seed
//   end
//   subsection Overrides                     # optional: entries of the base input set otherwise,
//     set mode = fem                         # one value each ('Pull/tension profiles at = 0.006, 0.02')
//   end
//
// Everything is checked when the file is read, before anything is written: each entry's value,
// the bracket against the tank (B shorter than L, L shorter than the tank and longer than B),
// and the base input with either end of the bracket as a run of it would check it.
#include "apps/pullout_command.h"

#include <deal.II/base/parameter_handler.h>

#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
struct DesignDefinition
{
  std::string input_file;                 ///< the design file
  std::string base_input;                 ///< the pull-out input, resolved as an include
  std::filesystem::path output_directory; ///< design.csv, design.png, summary.json, one sweep per value tried
  std::string entry;                      ///< "Anchorage/B" or "Anchorage/L"
  std::string entry_name;                 ///< "B" or "L"
  double minimum = 0.0, maximum = 0.0;    ///< the bracket [m]
  double target_kN = 0.0;                 ///< [kN/m]
  double margin_factor = 0.0;             ///< k in mean - k std >= target
  double tolerance = 0.0;                 ///< [m]
  std::string mode;                       ///< the base input's (with the overrides): dem, fem or hybrid
  /// The seeds each value is run with (Filling/seed), empty: one run per value with the base
  /// input's seed (always so in fem mode, where the continuum does not see the seed).
  std::vector<std::string> seeds;
  ParameterOverrides overrides;           ///< subsection Overrides: (path, value)
  std::vector<std::string> notes;         ///< said on the terminal and in summary.json (fem mode's seeds)
};

void declare_design_parameters(dealii::ParameterHandler &prm);

/// Reads and checks `input_file` (into `prm`, declared by declare_design_parameters). Throws
/// std::runtime_error naming the file and the entry for any value refused (above).
DesignDefinition parse_design(const std::string &input_file, dealii::ParameterHandler &prm);

/// The base input with the design's overrides, as each of its runs starts from (`pullout`
/// undeclared on entry).
void read_design_base(const DesignDefinition &design, dealii::ParameterHandler &pullout);

/// A value as it is run and names its directory: 10 significant digits, the C locale.
std::string design_value_text(double value);
} // namespace geohybrid::apps
