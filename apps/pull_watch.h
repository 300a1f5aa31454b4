#pragma once
// The watch of a DEM pull (dem and hybrid modes), at each point of the curve (apps/run_health.h):
// it stops a pull that is no pull-out any more (RunWentWrong: a non-finite tension, the head
// moving farther between two points than 'Pull/record interval' asks, grains that left the tank
// (or hybrid mode's particle box),
// the sheet's inertia or the motion of the whole carrying the work) and keeps the worst of the
// quality figures for the warnings the run finishes with. Its state goes into the checkpoint, so a
// resumed run warns as the straight run does.
#include "dem/laboratory/pullout_tank.h"

#include <optional>
#include <string>
#include <vector>

namespace geohybrid::dem
{
struct CommandState;
} // namespace geohybrid::dem
namespace geohybrid::coupling
{
struct ParticleBox;
} // namespace geohybrid::coupling

namespace geohybrid::apps
{
/// A region [x0, x1] x [y0, y1] (y1 may be infinite) the grains must not leave, named in messages
/// ("the tank", "the particle box").
struct GrainBounds
{
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  std::string name;
};

class PullWatch
{
public:
  struct Setup
  {
    double record_interval = 0.0;   ///< 'Pull/record interval' [m]
    double ramp_displacement = 0.0; ///< 'Pull/ramp displacement' [m]
    /// Where the grains must stay, in the particles' frame, and what to call it in a message:
    /// dem mode's tank [0, length] x [0, inf); hybrid mode's particle box, a lift beyond its
    /// edges shared with the continuum (they deform) and at its walls on the others.
    GrainBounds grains_inside;
    /// Whether the kinetic energy is checked against the clamp's work. In hybrid mode it is the
    /// particles' only (the continuum's is left out): a lower bound of the pull's share, so a
    /// stop or a warning is never a false one.
    bool kinetic_energy = true;
  };

  /// The watch of a pull of `system`: a fresh one (`saved` null; the kinetic energy of `system`
  /// now is the reference of the pull's own), or resumed from the state in `saved` (store()); a
  /// checkpoint written before the watch existed gives a fresh watch without the kinetic-energy
  /// check (the work so far unknown).
  PullWatch(const Setup &setup, const dem::DemSystem &system, const dem::CommandState *saved = nullptr);

  /// Checks `point` (just recorded) against the system now. Throws RunWentWrong.
  void check(const dem::PullPoint &point, const dem::DemSystem &system);
  std::vector<std::string> warnings() const;
  void store(dem::CommandState &command) const;

  // The bounds, and why they are where they are.
  /// The head moves v dt per step past each record point: more than 1.5 record intervals between
  /// two points is a clamp moving farther in a step than the curve's resolution.
  static constexpr double record_step_factor = 1.5;
  /// The sheet's mean inertial force over an interval (parts.inertia): the rate check measured it
  /// below 0.1 % of T (bench/RESULTS.md). Above half of T_max so far, the inertia of the
  /// mass-scaled sheet, not the soil, sets the tension: stopped. Its largest above 5 % of the
  /// pull's T_max: a warning (the ramp's interval included; 2 % on the tiny tank of the tests at
  /// its 10 mm/s, 22 % at 50 mm/s).
  static constexpr double fatal_inertia_share = 0.5, warning_inertia_share = 0.05;
  /// The pull's kinetic energy (grains and sheet, less that of the tank at the start) against
  /// the work of the clamp: in a quasi-static pull almost all the work goes to friction and
  /// stored energy. Half of it in motion is a pull that flings the soil: stopped; 5 %, a warning.
  /// Looked at after the ramp and two record intervals, when the work is no longer a few rows.
  static constexpr double fatal_kinetic_share = 0.5, warning_kinetic_share = 0.05;
  /// PFC's unbalanced-force ratio: the fill settles below 'Filling/equilibrium unbalanced ratio'
  /// (1e-4 by default); a pull whose grains keep a mean unbalanced force of a third of the mean contact
  /// force is accelerating the soil, not shearing it: a warning.
  static constexpr double warning_unbalanced_ratio = 0.3;

private:
  Setup setup_;
  bool check_kinetic_ = true;
  double kinetic_start_ = 0.0, work_ = 0.0, last_u_ = 0.0, T_max_ = 0.0;
  bool have_last_ = false;
  // The worst figures and where they were [N/m or -, m].
  double worst_inertia_ = 0.0, worst_inertia_u_ = 0.0;
  double worst_kinetic_ = 0.0, worst_kinetic_u_ = 0.0;
  double worst_unbalanced_ = 0.0, worst_unbalanced_u_ = 0.0;
};

/// Hybrid mode's bounds: the particle box in its own frame, a lift beyond each side it shares with
/// the continuum (those edges move with it, millimetres in a pull: a grain a lift past one has
/// left the coupling), at the tank's walls on the others, open above a free surface.
GrainBounds particle_box_bounds(const coupling::ParticleBox &box);

/// run_health.h's check_sheet_inertia for a DEM sheet (all its nodes but the clamp, masses as
/// scaled) pulled as `pull` asks with `time_step`, against `friction_limit` = 2 sigma_v L tan(delta).
std::optional<std::string> check_dem_sheet_inertia(const dem::SparSheet &sheet, const dem::PullSpec &pull,
                                                   double time_step, double friction_limit, const std::string &where);
} // namespace geohybrid::apps
