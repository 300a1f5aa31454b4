#pragma once
// The result files of `geohybrid pullout`, the same whatever the soil model (mode = dem or fem),
// so that discrete and continuum curves can be laid over each other (`geohybrid compare`):
//   pullout_curve.csv        head_displacement_m,head_tension_kN_per_m (per metre of width)
//   pullout_curve_sheet.csv  head_displacement_m,head_tension_kN for the sheet's width b (Table 6)
//   sheet_displacements.csv  displacement of the sheet's beginning, middle and end of its lower part
//   sheet_tension.csv        tension along the sheet at the chosen head displacements
//   pullout_curve.png        the curve, with the experimental T_max as a line if given
// and the summary keys every mode shares (T_max and its displacement, the experiment's value and
// the difference). Each mode adds its own keys and writes summary.json last. Under MPI only one
// rank (the caller chooses, rank 0) owns a PulloutOutput.
#include "apps/reference_runs.h"
#include "apps/run_directory.h"

#include "dem/io/checkpoint.h"
#include "dem/laboratory/pullout_tank.h"

#include <array>
#include <cstdint>
#include <functional>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// One segment of the sheet in a tension profile: its index, the arc length of its middle from
/// the clamp as laid, its middle's position now, its tension [-, m, m, m, N/m].
struct SheetTensionRow
{
  std::size_t segment = 0;
  double arc_length = 0.0, x = 0.0, y = 0.0, tension = 0.0;
};

class PulloutOutput
{
public:
  /// Creates the CSV files in `directory` with their headers. `profiles_at` are the head
  /// displacements at which a tension profile is written [m]; `sheet_width` is b [m].
  PulloutOutput(const std::filesystem::path &directory, double sheet_width, std::vector<double> profiles_at);
  /// A resumed run: the files are written again with the rows `saved` holds (store()), as the
  /// run that stored them had written them, and the rows an interrupted run wrote after them
  /// are dropped. Throws std::runtime_error if `saved` lacks them.
  PulloutOutput(const std::filesystem::path &directory, double sheet_width, std::vector<double> profiles_at,
                const dem::CommandState &saved);

  /// Keeps the rows written so far in `command` (for a checkpoint).
  void store(dem::CommandState &command) const;

  /// One point of the curve: head displacement [m], head tension [N/m], and the displacements
  /// along the pull of the sheet's beginning (first node inside the tank), the middle and the end
  /// of its lower part [m]. Its rows reach the files at once (flushed: a run killed later keeps
  /// them); a failed write (a full disk) throws std::runtime_error naming the file. So does
  /// add_profile().
  void add_point(double head_displacement, double head_tension, const std::array<double, 3> &sheet_displacements);
  /// Whether the next of 'tension profiles at' has been reached at this head displacement.
  bool profile_due(double head_displacement) const;
  /// Writes the profile once for each of 'tension profiles at' reached by `head_displacement`.
  void add_profile(double head_displacement, const std::vector<SheetTensionRow> &rows);

  /// Draws pullout_curve.png: the curve labelled `label`, the experimental T_max as a line over
  /// [0, final_displacement] if given, the full-size runs' mean curve (reference_curve.csv) if
  /// given, and for a demonstration a title that says so.
  void finish(const std::string &label, const CurveReferences &references, double final_displacement);

  double max_head_tension() const { return T_max_; }             ///< [N/m]
  double head_displacement_at_max() const { return u_at_T_max_; } ///< [m]

  /// The keys every mode writes: command, mode, anchorage, T_max (per metre and for b), its head
  /// displacement, the experiment's T_max with the difference in % when given, and for a
  /// demonstration or a full-size reference, "demonstration" and the reference's figures.
  void fill_summary(Summary &summary, const std::string &mode, const std::string &anchorage,
                    const CurveReferences &references) const;

private:
  /// Flushes the four CSV files; throws std::runtime_error naming the file that failed.
  void flush();
  void write_point(const double *row);
  void write_profile_row(const double *row);

  std::filesystem::path directory_;
  double sheet_width_;
  std::vector<double> profiles_at_;
  std::size_t next_profile_ = 0;
  std::ofstream curve_, per_sheet_, displacements_, profiles_;
  double T_max_ = 0.0, u_at_T_max_ = 0.0;
  // Every row written, as numbers, so that a checkpoint can hold them: 5 per point (u, T, the
  // three sheet displacements), 6 per profile row (u, segment, arc length, x, y, tension).
  std::vector<double> points_, profile_rows_;
};

/// The pull's loop of dem and hybrid modes: steps `pull` to its end, calling `record` at each
/// recorded point and `save_checkpoint` every `checkpoint_interval` s of wall time (0: never).
/// With `stop_after` > 0, stops after that many steps of this invocation (unless the pull is
/// done), saves a checkpoint, says so naming `checkpoint_file`, and returns false; true at the end.
/// After a SIGINT or SIGTERM (interrupt.h) it finishes the step, saves a checkpoint (whatever the
/// interval) and throws Interrupted.
bool pull_with_checkpoints(dem::PullOut &pull, const std::function<void(const dem::PullPoint &)> &record,
                           const std::function<void()> &save_checkpoint, double checkpoint_interval,
                           std::uint64_t stop_after, const std::filesystem::path &checkpoint_file);

/// A point of a DEM sheet's pull (dem and hybrid modes): the curve, the displacements of the
/// lower part's beginning, middle and end, and the tension profile when one is due. `origin` is
/// where the particles' frame lies in the tank's (hybrid mode's box; zero in dem mode) [m].
void add_dem_sheet_point(PulloutOutput &output, const dem::PullOutTank &tank, const dem::SparSheet &sheet,
                         const dem::PullPoint &point, const dem::Vec2 &origin = dem::Vec2::Zero());

/// dem::fill_pull_out_tank with a progress report "filling <what>" ("the tank", "the particle
/// box"); a SIGINT or SIGTERM stops it (Interrupted: a partial fill cannot be resumed).
dem::PullOutTank fill_with_progress(const dem::PullOutTankSpec &spec, const std::string &what);

/// The fill's steps per lift, "growth + settling" (a kept lift marked), and the lowest growth
/// friction each lift reached: where a fill's time went (dem and hybrid modes).
std::string fill_steps_per_layer(const dem::FilledTank &filled);

/// The summary keys of the DEM sheet as laid and of the soil's stress on it before the pull (dem
/// and hybrid modes): its nodes, its level and depth as laid (tank frame), gamma H, the normal
/// stresses on its faces, and the one-face friction top face x L x tan(delta).
void set_dem_sheet_summary(Summary &summary, const dem::SparSheet &sheet, double sheet_level, double cover_as_laid,
                           double gamma_H, const dem::SheetLevelStress &before, double one_face_friction);
} // namespace geohybrid::apps
