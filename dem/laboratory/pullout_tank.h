#pragma once
// The INSA pull-out tank of the reference paper (sections 2.2 and 4.3, Figure 7) as a DEM model:
// a rectangular tank filled with soil in layers, a geosynthetic anchored in it, pulled out by a
// clamp that moves horizontally at a set rate; the head tension against the head displacement.
//
// Geometry (x along the pull, y up, per metre of width as everything in 2D):
//
//   y = fill_height  +------------------------------------------------+
//                    |                  soil                          |
//                    |        (wrap-around: upper part B at D2 depth) |
//                    |        +--------------- B ----->               |  front wall x = length,
//                    |        | D1                                    |  slot at the sheet level
//   y = sheet level  |        +============= L ======================== o clamp (outside)
//                    |                                                |
//   y = 0            +------------------------------------------------+
//                  x = 0 (back wall)                                x = length
//
// Simple run-out: the sheet runs from the clamp, through the slot, L into the soil at depth H
// below the surface. Wrap-around: the same lower part, a vertical return D1 up at its end, and an
// upper part B back towards the front wall, D2 below the surface (H = D1 + D2). One SparSheet.
//
// The soil's unit weight is that of the sand in the tank: a 2D assembly of porosity n has the
// unit weight gamma when its grains have the density gamma / (g (1 - n)) (sand 1: 15.2 kN/m3 at
// n = 0.2 gives 1937 kg/m3). The weight per metre of the 2D model is gamma times the area.
//
// Filling (tank_filling.h): layers up to the sheet level, the sheet laid on their surface, layers
// above. The sheet therefore lies on the grains of the last lift below it, a little above the
// nominal level (about one grain); its actual depth is reported. A wrap-around is laid in two
// stages, as in the laboratory: the lower part on its lift with the return standing up from its
// end, held, while the lifts up to the upper part's level are placed; then the upper part folded
// over the lift at that level (levelled as the one under the lower part) and held, with the
// return, until the tank is full. The layers must put a boundary at both levels. Walls have the
// wall friction (28 degrees in the paper, measured) and the soil's stiffness.
//
// The implementation, split by idea: pullout_tank.cc (the checks, the filling spec, the fill),
// pullout_tank_sheet_forces.cc (the head tension and its parts, the stresses on the sheet),
// pullout_tank_pull.cc (the pull) and pullout_tank_checkpoint.cc (a pull-out in a checkpoint).
#include "dem/io/checkpoint.h"
#include "tank_filling.h"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::dem
{
enum class Anchorage
{
  simple_run_out,
  wrap_around
};

/// The tank and the anchorage, plain data. Defaults: the INSA bench with a simple run-out of
/// GT230 under H = 0.40 m of sand 1 (L = 1 m, as the paper's calibration). The paper's text does
/// not give the tank's length and the soil depth below the sheet (Figure 7 is lost): 1.5 m and
/// 0.2 m are this model's choice, long enough behind the anchorage (0.5 m) for the soil to move.
struct PullOutGeometry
{
  double tank_length = 1.5;        ///< inner length, back wall (x = 0) to front wall [m]
  double fill_height = 0.6;        ///< height of the soil surface above the base [m]
  Anchorage anchorage = Anchorage::simple_run_out;
  double cover = 0.40;             ///< H: soil above the lower part of the sheet [m]
  double anchorage_length = 1.0;   ///< L: length of the lower part in the soil [m]
  double return_height = 0.2;      ///< D1: wrap-around, vertical return [m]
  double upper_cover = 0.2;        ///< D2: wrap-around, soil above the upper part [m]
  double upper_length = 0.5;       ///< B: wrap-around, length of the upper part [m]
  double sheet_width = 0.5;        ///< b: the sheet's width in the bench, for per-sheet outputs [m]
  double wall_friction_deg = 28.0; ///< soil-wall friction angle (measured, section 4.3) [deg]
  double clamp_offset = 0.02;      ///< distance of the clamp outside the front wall [m]

  /// Throws std::invalid_argument naming `where` and the parameter (by its input-file name) if
  /// the sheet does not fit in the tank: H not below the fill height, L not shorter than the
  /// tank, B longer than L (the upper part would leave through the front wall), H != D1 + D2, ...
  void validate(const std::string &where) const;
  /// y of the lower part of the sheet, nominally: fill_height - H [m].
  double sheet_level() const { return fill_height - cover; }
  /// Corners of the sheet's polyline with the lower part at `level`: the clamp first.
  std::vector<Vec2> sheet_corners(double level) const;
};

/// Solid density that gives a 2D assembly of porosity `porosity` the unit weight `unit_weight`:
/// gamma / (g (1 - n)) [kg/m^3].
double solid_density_for_unit_weight(double unit_weight, double porosity, double gravity);

struct PullOutTankSpec
{
  PullOutGeometry geometry;
  SheetParameters sheet;            ///< GT230 and the paper's interface by default
  double max_segment_length = 0.01; ///< of the sheet's spars [m]
  /// The soil and the layers: width, height, density, wall contact and sheet are set from the
  /// geometry and unit_weight (the wall law is the soil's with the wall friction angle); the
  /// number of layers must put a layer boundary at the sheet level (and, for a wrap-around, at
  /// its upper part's, with a layer above it).
  TankFillingSpec filling;
  double unit_weight = 15.2e3;      ///< gamma of the soil at the fill's target porosity [N/m^3]

  /// Throws std::invalid_argument naming the parameter.
  void validate(const std::string &where) const;
  /// The filling spec as used: the geometry's tank, density from the unit weight, the sheet.
  TankFillingSpec resolved_filling() const;
};

/// A filled tank with its sheet (index 0 of system.sheets()), in equilibrium, clamp fixed.
struct PullOutTank
{
  FilledTank tank;
  double sheet_level = 0.0;          ///< actual y of the lower part as laid [m]
  std::size_t lower_part_end = 0;    ///< node at the far end of the lower part
  std::size_t first_node_inside = 0; ///< first node inside the front wall
  std::vector<double> arc_length;    ///< of each node from the clamp, as laid [m]
  std::vector<Vec2> initial_nodes;   ///< node positions before the pull [m]
  std::uint64_t n_final_settling_steps = 0; ///< steps of the settling with the sheet freed, after the layers
};

/// Fills the tank in layers, laying the sheet at its depth, then frees the sheet (but the clamp)
/// and lets everything settle. Throws as fill_tank_in_layers.
PullOutTank fill_pull_out_tank(const PullOutTankSpec &spec, const std::function<void(double)> &progress = {});

/// The steps the fill took: each layer's growth and settling, then the settling with the sheet
/// freed (the cost of a fill in steps; the system's own step count restarts with each lift).
std::uint64_t fill_steps(const PullOutTank &tank);

/// Of fill_steps, those of lifts taken from a lift cache (made by an earlier run).
std::uint64_t fill_steps_of_kept_lifts(const PullOutTank &tank);

/// What the soil does to the lower part of the sheet: the normal stresses on its top and bottom
/// faces (sheet_face_stresses over every segment of the lower part that is, wholly or partly,
/// inside the tank now, over the length inside), the total normal force on both faces, and the
/// Love-Weber vertical stress in a band of soil of `band` height just above the lower part (x
/// over the anchorage) [Pa, N/m]. Compression positive. (The segment through the slot counts:
/// the grains at the front wall press it hardest. Leaving it out, as an earlier version did,
/// missed 10-35 % of the normal force on the 400-cluster test tank, and so the head tension
/// seemed to exceed tan(delta) times the normal force by up to 26 %.)
struct SheetLevelStress
{
  double top_face = 0.0, bottom_face = 0.0;
  double normal_force_both_faces = 0.0;
  double love_weber_above = 0.0;
  double lower_part_length = 0.0; ///< current length of the segments measured [m]
};
SheetLevelStress measure_sheet_level_stress(const DemSystem &system, const PullOutTank &tank,
                                            const PullOutGeometry &geometry, double band);

/// The head tension now: the clamp's reaction along the pull (+x) [N/m].
double head_tension(const DemSystem &system);

/// Where the head tension comes from, at the last force evaluation. The clamp holds node 0 of
/// sheet 0; the other nodes obey m a = forces, and the axial forces are internal to the chain,
/// so the reaction along the pull is the sum of what resists the sheet along -x:
///   reaction = interface_friction + interface_normal + node_wall + inertia + damping,
/// with each contact's force on the sheet split along its own normal (from the disc centre to
/// the contact point on the sheet) and tangent. On a flat sheet the normal forces have no
/// component along the pull; on a sheet kinked by the grains they do. [N/m]
struct HeadTensionParts
{
  double reaction = 0.0;            ///< head_tension(system)
  double interface_friction = 0.0;  ///< - sum of the x-components of the tangential forces on the sheet
  double interface_normal = 0.0;    ///< - sum of the x-components of the normal forces on the sheet
  double node_wall = 0.0;           ///< - sum of the x-components of the node-wall forces
  double inertia = 0.0;             ///< sum over the free nodes of (inertial mass) a_x
  double damping = 0.0;             ///< - sum of the x-components of the nodes' local damping forces
  double normal_force = 0.0;        ///< sum of the interface normal forces on the whole sheet, both faces
  double elastic_normal_force = 0.0; ///< the same, springs only (kn overlap): the Coulomb limit is tan(delta) times it
  double tangential_force = 0.0;    ///< sum of the magnitudes of the interface tangential forces
  double sum() const { return interface_friction + interface_normal + node_wall + inertia + damping; }

  /// Adds `other` term by term (the interval sums of a pull); scale() turns a sum into a mean.
  void add(const HeadTensionParts &other);
  void scale(double factor);
  /// The terms in the order above (reaction first), for checkpoints and files.
  static constexpr std::size_t n_terms = 9;
  std::array<double, n_terms> as_array() const;
  static HeadTensionParts from_array(const std::array<double, n_terms> &values);
};
HeadTensionParts head_tension_parts(const DemSystem &system);

/// The same system (state, walls, sheets, contacts and their history) run on `n_threads`
/// threads: a pull-out started from one filled tank on several thread counts.
DemSystem with_threads(const DemSystem &system, int n_threads);

struct PullSpec
{
  double rate = 5e-3;               ///< clamp speed [m/s]
  double final_displacement = 0.06; ///< head displacement at the end [m]
  double record_interval = 5e-4;    ///< head displacement between recorded points [m]
  /// The clamp's speed rises linearly from 0 to `rate` over this head displacement: a clamp
  /// started at full speed jerks the sheet, and the inertia and local damping of the nodes and
  /// grains then give a spurious early peak of head tension (measured on a 400-cluster tank:
  /// 2.4 x the plateau at 20 mm/s, 1.4 x at 5 mm/s) [m].
  double ramp_displacement = 2.5e-4;
  /// Local damping of the sheet's nodes while pulling (the grains keep the system's). Damping a
  /// node by alpha |F| against its velocity drags a sheet that slides one way through
  /// fluctuating contacts, whatever the rate: measured on a 400-cluster tank at 5 mm/s with the
  /// sheet damped like the grains (0.7), T = 1.4 tan(delta) N. 0 by default [-].
  double sheet_local_damping = 0.0;
  /// Local damping of the grains while pulling; empty: the system's (the fill's). The damping's
  /// drag on grains that keep moving one way (the soil dilating round the sheet) is what a pull
  /// too fast for its damping turns into normal stress on the sheet (bench/RESULTS.md, the rate).
  std::optional<double> grain_local_damping;
};

/// One recorded point: averages over the interval that ends at head_displacement.
struct PullPoint
{
  double head_displacement = 0.0;   ///< [m]
  double head_tension = 0.0;        ///< mean clamp reaction along the pull [N/m]
  /// Where it comes from: each term's mean over the same steps (parts.reaction = head_tension).
  /// Which of them grows with the pull rate is what a rate check must look at.
  HeadTensionParts parts;
};

/// What the pull carries from one step to the next, plain data: with the DemSystemState, all a
/// checkpoint needs to continue a pull bit for bit.
struct PullProgress
{
  double clamp_x0 = 0.0;            ///< x of the clamp at the start of the pull [m]
  double time0 = 0.0;               ///< the system's time at the start of the pull [s]
  double tension_sum = 0.0;         ///< sum of the head tensions of the steps since the last record [N/m]
  HeadTensionParts parts_sum;       ///< the same steps' decompositions, summed term by term [N/m]
  std::uint64_t n_summed = 0;       ///< steps in tension_sum
  double next_record = 0.0;         ///< head displacement of the next recorded point [m]
  std::uint64_t n_steps = 0;        ///< pull steps done
  bool finished = false;
};

/// The pull, one step at a time: the clamp (node 0 of sheet 0) moves along +x at spec.rate, the
/// grains keep the system's local damping, the sheet's nodes have spec.sheet_local_damping.
/// Each recorded point is the mean head tension over the steps since the last one.
class PullOut
{
public:
  /// Starts a pull: throws std::invalid_argument for a non-positive rate, displacement or
  /// interval, or a ramp outside [0, final displacement).
  PullOut(DemSystem &system, const PullSpec &spec);
  /// Continues a pull from `progress` (of a system restored from the same checkpoint).
  PullOut(DemSystem &system, const PullSpec &spec, const PullProgress &progress);
  /// A pull of a system that something else advances (a coupled run's stepper, which steps the
  /// particles with the continuum and keeps their forces, the coupling's included, current):
  /// each step() calls `advance` instead of DemSystem::step, and the forces are not evaluated
  /// again at the start (that would apply the coupling's forces twice). Throws as the first.
  PullOut(DemSystem &system, const PullSpec &spec, std::function<void()> advance);
  /// Continues such a pull from `progress` (the system and what advances it restored from the
  /// same checkpoint). Throws as the first, or if `advance` is empty.
  PullOut(DemSystem &system, const PullSpec &spec, const PullProgress &progress, std::function<void()> advance);

  /// The point at the start (displacement 0, the tension of the filled tank).
  PullPoint start_point() const;
  /// One time step; true when it reached a record point, then given by last_point().
  bool step();
  const PullPoint &last_point() const { return last_point_; }
  bool finished() const { return progress_.finished; }
  /// Holds the clamp still (after the last step).
  void stop_clamp();
  const PullProgress &progress() const { return progress_; }
  /// Head displacement now [m].
  double head_displacement() const;
  /// Steps the whole pull takes, the ramp included (from the rate and the time step).
  std::uint64_t expected_steps() const;

private:
  double clamp_speed() const;
  /// What both new pulls do: the clamp's start, its first speed, the sheet's damping.
  void start();

  DemSystem &system_;
  PullSpec spec_;
  PullProgress progress_;
  std::function<void()> advance_; ///< empty: DemSystem::step
  double ramp_time_ = 0.0;
  PullPoint last_point_;
};

/// Checkpoints of a pull-out: the filled tank's description (PullOutTank but its system), the
/// pull's progress and the vertical stress measured before the pull, in a CommandState named
/// "pullout" beside the system's state (dem/io/checkpoint.h).
void store_pullout_tank(const PullOutTank &tank, CommandState &command);
/// The tank of a checkpoint: its system rebuilt from `state` with `settings` (those of the fill,
/// tank_settling_settings) and its description from `command`. Throws std::runtime_error naming
/// what is missing if `command` is not a pull-out's.
PullOutTank restore_pullout_tank(DemSystemState state, const DemSettings &settings, const CommandState &command);
void store_pull_progress(const PullProgress &progress, CommandState &command);
/// The progress stored, if the checkpoint was written during the pull (not right after the fill).
std::optional<PullProgress> restore_pull_progress(const CommandState &command);
void store_sheet_level_stress(const SheetLevelStress &stress, CommandState &command);
SheetLevelStress restore_sheet_level_stress(const CommandState &command);

/// Pulls the clamp (node 0 of sheet 0) along +x at spec.rate, with the system's local damping,
/// until spec.final_displacement; after each record interval calls `record` with the point and
/// the system (for profiles and progress). `advance`, if given, steps the system instead of
/// DemSystem::step (a coupled run's stepper: PullOut's third constructor). Throws
/// std::invalid_argument for a non-positive rate, displacement or interval.
std::vector<PullPoint> pull_out(DemSystem &system, const PullSpec &spec,
                                const std::function<void(const PullPoint &, const DemSystem &)> &record = {},
                                const std::function<void()> &advance = {});
} // namespace geohybrid::dem
