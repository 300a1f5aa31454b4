#pragma once
// A run watches its own health (issue 24, section 1), so that a run that went wrong never looks
// finished. Three kinds of verdict:
//   - refused at set-up, before any file is written, what the input already shows (a pull far
//     too fast to be quasi-static, grains moving farther than their radius in one step):
//     std::invalid_argument naming the entry to change, as every bad input;
//   - stopped during the run (non-finite values, grains that left the box or the tank, an energy
//     balance that no longer closes, a pull that is not a pull-out any more): RunWentWrong; the
//     run writes no summary.json (its other files stay, for a look at what went wrong), prints
//     the message and exits with status 1 (main.cc's error path);
//   - finished with quality warnings: "warnings" in summary.json (a list, empty when none) and
//     one line each on the terminal.
// Watches only read the state, at record or output points (never in the time-step loop), so a
// valid input gives the same numbers, bit for bit, as before they existed.
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace geohybrid::dem
{
class DemSystem;
struct EnergyBudget;
struct PullOutTankSpec;
struct PullSpec;
} // namespace geohybrid::dem

namespace geohybrid::apps
{
class Summary;

/// A run that went wrong and must not finish: its message says what, when, the likely cause and
/// the input entry to change.
class RunWentWrong : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Writes `warnings` into `summary` as "warnings" and each, prefixed by `command`, on `terminal`.
void report_warnings(const std::vector<std::string> &warnings, const std::string &command, Summary &summary,
                     std::ostream &terminal);

/// The inertial number of the pull, I = v sqrt(rho / sigma_v): the clamp's speed v against the
/// speed sqrt(sigma_v / rho) at which the grains' inertia balances the confining stress, for a
/// shear zone one grain thick (the thinnest, so the largest I). rho is the grains' density (the
/// continuum's in fem mode), sigma_v = gamma H at the sheet.
double pull_inertial_number(double rate, double density, double vertical_stress);

/// The rate check's bounds on I (bench/RESULTS.md, "The pull rate on the full tank with sand 1";
/// VALIDATION.md 5.3): at 0.05 m/s, sand 1 (grains 1937 kg/m3, gamma H = 6.08 kPa), I = 0.028,
/// and T_max moved 0.44 % when the rate was halved: quasi-static.
struct PullRateBounds
{
  /// Beyond twice the rate check's I, nothing shows the curve converged: a warning.
  double warning = 0.06;
  /// At I = 1, rho v^2 = sigma_v: the grains' momentum flux at the clamp's speed is the whole
  /// confining stress, the soil round the sheet is flung, not sheared. Refused.
  double refusal = 1.0;
};

/// Refuses (std::invalid_argument naming `where` and 'Pull/rate') a pull beyond bounds.refusal;
/// returns a warning beyond bounds.warning.
std::optional<std::string> check_pull_rate(double rate, double density, double vertical_stress,
                                           const std::string &where, const PullRateBounds &bounds = {});

/// Refuses (std::invalid_argument naming `where` and the CSV file) particles of `system` whose
/// speed moves them more than half their smallest disc radius in one time step: their contacts
/// cannot build up before they pass through a wall or a grain.
void check_particle_speeds(const dem::DemSystem &system, const std::string &where);

/// The force the sheet's (mass-scaled) inertia takes to follow the clamp's ramp, M v^2 / (2 d_ramp)
/// (one time step's v / dt when there is no ramp), against the interface's friction limit on both
/// faces of the lower part, 2 sigma_v L tan(delta): the sheet's inertia must not set the answer.
struct SheetInertiaCheck
{
  double inertial_mass = 0.0;       ///< the free nodes' scaled inertial mass [kg/m]
  double rate = 0.0;                ///< [m/s]
  double ramp_displacement = 0.0;   ///< [m]
  double time_step = 0.0;           ///< [s]
  double friction_limit = 0.0;      ///< 2 sigma_v L tan(delta) [N/m]
  double mass_scaling = 1.0;        ///< the sheet's factor on its masses, for the message [-]
  double ramp_force() const;
};
/// Refuses (std::invalid_argument naming `where`) a sheet whose ramp force is above half the
/// friction limit (the answer would be its inertia's); warns above 5 % (the rate check found
/// the sheet's inertia below 0.1 % of T).
std::optional<std::string> check_sheet_inertia(const SheetInertiaCheck &check, const std::string &where);

/// The same at dem mode's set-up, before the tank is filled: the sheet's inertial mass and the
/// grains' step from dem::estimate_sheet_inertia, against the geostatic limit 2 gamma H L
/// tan(delta) (the filled tank's uses the measured stress on the sheet). Refused
/// (std::invalid_argument naming `where` and 'Sheet/axial stiffness') when the ramp force is above
/// sheet_inertia_setup_share of that limit: the estimate can be off by tens of per cent
/// (run_health.cc), so set-up refuses only a sheet far beyond the filled tank's bound of half the
/// limit, and the filled tank's check decides the cases near it.
void refuse_sheet_inertia_before_the_fill(const dem::PullOutTankSpec &tank, const dem::PullSpec &pull,
                                          const std::string &where);
inline constexpr double sheet_inertia_setup_share = 2.0;

/// fem mode's check of the result: T_max against the geostatic interface limit (the head tension
/// if the whole sheet slid on soil at rest). Dilatancy and a wrap-around's return raise T above
/// it (measured: 1.15 run-out, 1.37 wrap-around in fem mode; the experiment 2.4 x for the
/// wrap-around of Table 3), never by 10: above 10 x the pull is dynamic (RunWentWrong), above
/// 3 x a warning is returned.
std::optional<std::string> check_fem_tension(double T_max, double interface_limit);

/// `geohybrid dem`'s watch, at each output row, before the row is written: stops the run on a
/// non-finite energy, on grains outside the box, on an energy balance error beyond the whole
/// budget; keeps the largest error for a warning.
class DemRunWatch
{
public:
  /// The box of 'Box/width' x 'Box/height' (closed at the top with `top_wall`); a grain is
  /// outside when its centre is beyond a wall by more than its largest disc's radius (a wall's
  /// contact never lets it overlap that much).
  DemRunWatch(double width, double height, bool top_wall);
  /// Throws RunWentWrong naming the time, what went wrong and the entries to change.
  void check(const dem::DemSystem &system, const dem::EnergyBudget &energy, double balance_error);
  std::vector<std::string> warnings() const;

  /// |error| above it: energy created or lost beyond the largest term of the budget, no
  /// physics can do that (a time step too large, grains overlapping deeply at the start).
  static constexpr double fatal_balance_error = 1.0;
  /// |error| above it at any row: a warning (a deposition of 300 discs closes its balance to
  /// 5.3e-4 at every row: 100 times below).
  static constexpr double warning_balance_error = 0.05;

private:
  double width_, height_;
  bool top_wall_;
  double worst_error_ = 0.0, worst_error_time_ = 0.0;
};

/// The grains of `system` whose centre lies more than their largest radius outside the region
/// [x0, x1] x [y0, y1] (y1 infinite: open at the top); `side_height` > y: the side walls end
/// there, above them a grain may leave sideways (a free surface over a low wall).
struct GrainsOutside
{
  std::size_t count = 0;
  std::size_t first_id = 0;
  double first_x = 0.0, first_y = 0.0;
};
GrainsOutside grains_outside(const dem::DemSystem &system, double x0, double x1, double y0, double y1,
                             double side_height);
} // namespace geohybrid::apps
