#pragma once
// The input of `geohybrid pullout` as read from its file, shared by the soil models: the tank, the
// anchorage, the sheet and the pull (dem/laboratory/pullout_tank.h's plain data, which the
// continuum mode maps onto fem::PulloutProblemParameters), and the outputs asked for.
#include "apps/reference_runs.h"
#include "dem/laboratory/pullout_tank.h"

#include <deal.II/base/parameter_handler.h>

#include <optional>
#include <string>
#include <vector>

namespace geohybrid::apps
{
struct PullOutInput
{
  dem::PullOutTankSpec tank;
  dem::PullSpec pull;
  std::vector<double> profiles_at;
  std::vector<double> fields_at; ///< head displacements of the field outputs (dem mode) [m]
  CurveReferences references; ///< the experiment, the case at full size, a demonstration
  double stress_band = 0.05;
  /// Quality warnings found in the input (apps/run_health.h), for the summary's "warnings".
  std::vector<std::string> warnings;
};

/// Reads the sections every mode uses (and those of the DEM, which fem mode leaves unused) and
/// checks them; the fill's layers (Filling) are checked in dem mode only. Throws
/// std::invalid_argument naming `where` and the entry.
PullOutInput parse_pullout(dealii::ParameterHandler &prm, const std::string &where, bool dem_mode);

/// "simple run-out" or "wrap-around".
inline std::string anchorage_name(const dem::PullOutGeometry &g)
{
  return g.anchorage == dem::Anchorage::wrap_around ? "wrap-around" : "simple run-out";
}

/// The anchorage for the first line of a run's log: its name, H and L (and D1, B for a wrap-around).
std::string anchorage_description(const dem::PullOutGeometry &g);
} // namespace geohybrid::apps
