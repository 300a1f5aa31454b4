#pragma once
// pullout_forces.csv of a DEM sheet's pull (dem and hybrid modes): where the head tension comes
// from at each recorded point, each term the mean over the same steps as the curve's point
// (dem::HeadTensionParts), beside the soil's kinetic energy and the energy the grains' damping
// and friction have taken so far. A pull that is quasi-static carries its head tension in the
// interface terms; what grows with the rate (sheet inertia, damping, a normal force that rises)
// shows here first.
//   head_displacement_m, head_tension_kN_per_m,
//   interface_friction_kN_per_m, interface_normal_kN_per_m, node_wall_kN_per_m,
//   sheet_inertia_kN_per_m, sheet_damping_kN_per_m      (the five sum to the head tension)
//   normal_force_kN_per_m           springs only, both faces, whole sheet
//   mobilised_friction              sum |Ft| / (tan(delta) sum Fn): 1 where every contact slips
//   soil_kinetic_energy_J_per_m, local_damping_dissipated_J_per_m, friction_dissipated_J_per_m,
//   clamp_work_J_per_m              (the energy terms since the start of the pull)
// In hybrid mode the grains and the sheet are the particle box's, the energy terms theirs (the
// continuum's and the coupling's work: coupling_diagnostics.csv).
#include "dem/dem_system.h"
#include "dem/io/checkpoint.h"
#include "dem/laboratory/pullout_tank.h"

#include <filesystem>
#include <fstream>
#include <vector>

namespace geohybrid::apps
{
class PullForcesOutput
{
public:
  /// Creates the file with its header. `interface_friction_coefficient` is tan(delta) of the
  /// sheet's interface; `energy_at_start` is the system's budget when the pull starts.
  PullForcesOutput(const std::filesystem::path &directory, double interface_friction_coefficient,
                   const dem::EnergyBudget &energy_at_start);
  /// A resumed run: the rows and the starting budget `saved` holds (store()) are written again.
  PullForcesOutput(const std::filesystem::path &directory, double interface_friction_coefficient,
                   const dem::CommandState &saved);
  void store(dem::CommandState &command) const;

  void add_point(const dem::PullPoint &point, const dem::DemSystem &system);
  /// Flushes the file; throws std::runtime_error naming it if that fails.
  void finish();

  static constexpr std::size_t n_columns = 13;

private:
  void write_row(const double *row);

  std::filesystem::path file_;
  double mu_;
  dem::EnergyBudget start_;
  std::ofstream out_;
  std::vector<double> rows_; ///< every row written, n_columns each, for checkpoints
};
} // namespace geohybrid::apps
