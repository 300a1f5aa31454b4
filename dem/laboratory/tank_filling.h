#pragma once
// Filling a tank with soil layer by layer, as sand is placed in a laboratory pull-out tank: each
// lift is brought to its target density between two levels, then the next one is placed on it.
// Here each layer is made by REDF (sample_preparation.h) and settles under gravity:
//
//  1. the layer's particles are placed at random, at a fraction of their final size, above the
//     layer's bottom level, clear of the grains already there. A sheet standing across the
//     layer (a wrap-around's held return) walls it into compartments no grain passes between;
//     each gets the share of the particles that fills it at the target porosity (its space less
//     the sheets', less the solid already in it), placed in it;
//  2. without gravity, under a temporary lid wall, the layer's particles grow; while the layer is
//     jammed (lid stress above the growth stress: the lift's compaction stress) above its target
//     porosity, the growth friction is lowered step by step. Growth stops when the slab between
//     the layer's two levels is at the target porosity, counting every grain in it, each cut
//     exactly at the levels (slab_porosity). The grains below the slab are fixed meanwhile (a
//     compacted lift is nearly rigid under the next one); those of the layer below that reach
//     into the slab stay free and rearrange with the new ones;
//  3. a flat lid loosens the packing along it over about one particle size, so the lid of every
//     layer but the last stands one such band above the layer's top level: the loose band lies
//     in the next layer's slab, whose grains grow into its hollows (the last layer's lid is at
//     the fill's height). The lift a sheet is laid on is levelled instead: its lid is at its
//     top level, so that the sheet lies flat on it (the grains above cannot reach below the
//     sheet to fill a rough surface's hollows);
//  4. the material friction is restored, the lid is taken away, every grain is freed and the
//     whole fill settles under gravity, walls fixed, with local damping, until equilibrium.
//
// The steps are files of their own: lift_placement.h (1), lift_growth.h (2), lift_settling.h
// (4); the porosity of a slab in slab_porosity.h, the tank's walls with the front wall's slot in
// tank_walls.h, a sheet's laying and its checks in sheet_laying.h. tank_filling.cc holds the
// levels of the lifts and their lids (3) and each lift's share of the grains (its LiftPlan), and
// fill_tank_in_layers, which makes the lifts one after the other and lays the sheet between them.
//
// The result is a DemSystem in equilibrium under gravity, with the porosity of each layer's slab
// at the end of its growth and in the final fill (settling under the layers above compacts the
// lower ones a little).
//
// Porosities are of the space the grains can fill: the area of a sheet in a slab (its thickness
// times its length there) is not counted as void.
//
// A geosynthetic is laid as in the laboratory, on a lift at its depth (TankFillingSpec::sheet):
// once the layers below it have settled, the sheet is added to the system and stays in the tank
// while the layers above are placed, grown and settled around it. It leaves the tank through a
// slot in the front wall (x = width), cut at the level of its first node (the clamp, outside the
// tank) when it is laid: a gap between two wall segments, narrower than the grains (checked), so
// that the sheet passes and the soil does not.
//
// A sheet may be laid in two stages, as a wrap-around is in the laboratory
// (SheetLaying::second_part_layers_below): its lower part laid on its lift (with whatever of it
// stands in the lifts to come, e.g. the return, held there), the lifts placed up to a higher
// level, and the rest of the sheet (the upper part, folded over) laid on the lift at that level,
// which is levelled as the first one is. Laid in one stage, a part held above the lift being
// placed lay between that lift's grains and its lid, a band above: grains placed there were
// pinched between the held sheet and the lid, whose stress then counted the lift jammed long
// before its slab was dense (measured on a 1,400-cluster tank, lifts of 0.04 m, the upper part on
// the third: the third lift jammed at porosity 0.53 against 0.25, a row of grains between the
// sheet and the lid carrying 52 kPa on the lid; with the upper part on the second, the second
// lift the same way at 0.51).
#include "dem/dem_system.h"
#include "packing.h"
#include "sample_preparation.h" // RedfStartingSizes
#include "slab_porosity.h" // slab_porosity, which the fill reports its layers by

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::dem
{
/// A sheet laid while the tank is filled.
struct SheetLaying
{
  /// The sheet is laid once this many layers have settled: in [1, n_layers - 1].
  std::size_t layers_below = 1;
  /// Height of the slot in the front wall, centred on the sheet's first node; above the sheet's
  /// thickness, and the gap it leaves beside the sheet (height - thickness) below the smallest
  /// grain's diameter. 0 = the thickness plus half the smallest grain's diameter [m].
  double slot_height = 0.0;
  /// Makes the sheet from the settled layers below it (e.g. resting on their surface). Its first
  /// node must lie outside the front wall, x > width; make it kinematic (prescribe_velocity) to
  /// hold the sheet while the tank is filled.
  std::function<SparSheet(const DemSystem &settled)> lay;
  /// Two-stage laying: the rest of the sheet is laid once this many layers have settled, in
  /// [layers_below + 1, n_layers - 1]; its lift is levelled as the first one. 0 = the whole sheet
  /// is laid at once.
  std::size_t second_part_layers_below = 0;
  /// Makes the whole sheet from the sheet laid so far, as it stands in the settled layers (its
  /// nodes, their velocities and whether each is held), and the settled layers: that sheet's
  /// nodes first (the clamp where it was; others may be moved along the sheet, e.g. a held
  /// return's end to the level of the part laid now), then the new ones.
  std::function<SparSheet(const DemSystem &settled, const SparSheet &laid)> lay_second_part;
};

struct TankFillingSpec
{
  double width = 1.0;                 ///< inner width of the tank [m]
  double height = 0.5;                ///< height of the fill [m]
  std::size_t n_layers = 5;
  /// Each layer's top above the base, bottom first, rising, the last at `height` [m]. Empty: the
  /// layers are height / n_layers thick. (A particle box fills the margin below a sheet, the
  /// rise to a wrap-around's upper part and the margin above in lifts of their own thickness.)
  std::vector<double> layer_tops;
  std::size_t n_particles = 20000;    ///< in the whole fill (see TankLayer for each layer's share)
  ParticleShape shape = ParticleShape::two_disc_cluster;
  /// Relative sizes, scaled in each layer so that its particles fill it at its target porosity.
  SizeDistribution size_distribution = SizeDistribution::uniform(0.5);
  double cluster_diameter_ratio = 0.9; ///< small / large disc diameter in a cluster [-]
  double cluster_spacing = 0.95;       ///< centre spacing / large diameter; 0.95 = touching [-]
  double density = 2650.0;             ///< [kg/m^3]
  double target_porosity = 0.2;        ///< of every layer, unless layer_porosities is given [-]
  std::vector<double> layer_porosities; ///< one per layer, bottom first; empty = target_porosity
  double porosity_tolerance = 0.005;   ///< growth stops at most half of it above the target [-]
  /// Lid stress above which a growing layer counts as jammed: REDF's growth stress, the
  /// compaction stress of a lift. Best above the weight of the fill on the base,
  /// (1 - n) rho g height, so that no layer is later loaded beyond it [Pa].
  double growth_stress = 10e3;
  ContactParameters particle_contact;  ///< the material (friction restored after each growth)
  /// Friction angle at the start of each layer's growth; negative = the material's [deg].
  double initial_growth_friction_deg = -1.0;
  /// Each lift after the first with the porosity of the lift below starts its growth one REDF
  /// step (redf_friction_drop) above the friction that lift ended at, if that is lower than the
  /// above: the lifts of one fill are made of the same grains to the same porosity under the same
  /// stress, and end their growth at the same friction (a 6,000-cluster wrap-around tank: all
  /// three at 4.02 deg, from 29.7 deg in 19 drops of 2000 contact times each, most of each
  /// lift's growth). One step above, the lift still jams above its porosity and reaches it by the
  /// last drop, as it did from the top. False: every lift starts where the first does.
  bool later_lifts_start_near_the_lift_below = true;
  /// The soil goes on above the fill's top (a particle box under a continuum): the top lift's
  /// lid is then not the soil's surface, and the loose band of grains along it (one grain) is
  /// left out of that lift's porosity, which is measured a band below the lid, as every other
  /// lift's is below the band its lid stands above. Measured to the lid, a 0.1 m lift between a
  /// sheet and a lid could not reach porosity 0.2 even without friction. (A shared base is still
  /// measured to it: left out there too, the lift above a 0.1 m first lift jammed instead.)
  bool soil_continues_above = false;
  /// The soil goes on below the fill's base (a particle box over a continuum): the base is a
  /// temporary floor, and the loose band of grains along it is left out of the first lift's
  /// porosity, measured a band above it. Measured to the floor, the first lift's grains made up
  /// for that band's hollows: a solid fraction of 0.809 0.05-0.13 m above it against 0.801 in
  /// pure DEM's soil at the same place (the 3.7 m x 1.2 m tank's box, three seeds).
  bool soil_continues_below = false;
  ContactParameters wall_contact;      ///< the tank's walls and the lid
  double gravity = 9.81;               ///< [m/s^2], pointing down (-y)
  double local_damping = 0.7;          ///< during growth and settling [-]
  double equilibrium_unbalanced_ratio = 1e-4; ///< settling stops below this unbalanced-force ratio
  std::uint64_t seed = 1;
  int n_threads = 1;
  std::uint64_t max_steps_per_layer = 2'000'000; ///< growth and settling of one layer
  std::optional<SheetLaying> sheet;   ///< a geosynthetic laid at its depth while filling
  /// The lifts below the first sheet, grown and settled, are kept here and taken from here by a
  /// fill that starts one from the same state with the same settings (lift_cache.h): the cases
  /// and calibration attempts of one tank and seed share them. Empty: no cache.
  std::filesystem::path lift_cache_directory;
  /// Part of a lift's key: the code's numbers version (a change of the numbers must not take a
  /// lift made before it).
  std::string lift_cache_version;
};

/// The tank's walls: indices into DemSystem::walls(). The base spans [0, width] at y = 0, the
/// side walls x = 0 and x = width; the lid, used while a layer grows, ends parked above the fill
/// (it touches nothing). The lid never touches a sheet (Wall::touches_sheets): it only gauges a
/// growing layer's jamming, which a held sheet standing through it must not load.
struct TankWalls
{
  std::size_t base, right, lid, left;
  /// With a slot in the front wall: `right` is the wall below the slot, `right_upper` the one
  /// above it; without, right_upper == no_wall.
  std::size_t right_upper = no_wall;
  static constexpr std::size_t no_wall = static_cast<std::size_t>(-1);
};

struct TankLayer
{
  double bottom = 0.0, top = 0.0;     ///< levels of the layer's slab [m]
  /// The part of the slab whose porosity is measured: the slab but a band below a top above which,
  /// or above a base below which, the soil goes on (TankFillingSpec::soil_continues_above,
  /// soil_continues_below) [m].
  double measured_bottom = 0.0, measured_top = 0.0;
  /// The particles placed for this layer: bodies [first_body, first_body + n_bodies). Their
  /// number is in proportion to the space the layer fills (the first layer fills its band too,
  /// the last one the band of the layer below), so that all layers have the same sizes.
  std::size_t first_body = 0, n_bodies = 0;
  double target_porosity = 0.0;
  double porosity_grown = 0.0;        ///< porosity of its slab at the end of its growth, without the sheets' area [-]
  double porosity = 0.0;              ///< the same in the final fill (slab_porosity if there is no sheet) [-]
  double growth_friction_deg = 0.0;   ///< the lowest friction used in its growth
  std::uint64_t n_growth_steps = 0, n_settling_steps = 0;
  bool from_cache = false;            ///< taken from TankFillingSpec::lift_cache_directory (its steps were made once, before)
};

struct FilledTank
{
  DemSystem system;    ///< under gravity, in equilibrium, walls fixed
  TankWalls walls;
  std::vector<TankLayer> layers; ///< bottom first
  double slot_bottom = 0.0, slot_top = 0.0; ///< the front wall's slot, if a sheet was laid [m]
};

/// Fills the tank. `progress` (optional) is called now and then with a fraction in [0, 1].
/// Throws std::invalid_argument for a spec that cannot work (no layer, a porosity outside
/// [0.05, 0.8], layers too thin for their particles, a sheet laid outside [1, n_layers - 1] or whose
/// first node is inside the tank, a second part laid outside [layers_below + 1, n_layers - 1],
/// without its function, or moving the clamp or dropping nodes, a slot narrower than the sheet or leaving a gap beside it wider than the smallest grain) and std::runtime_error when a layer cannot
/// reach its porosity or the fill does not settle within max_steps_per_layer, naming the layer.
FilledTank fill_tank_in_layers(const TankFillingSpec &spec, const std::function<void(double)> &progress = {});

/// The whole fill's draw of spec.n_particles in the tank's area, grown to `porosity`, as
/// fill_tank_in_layers first checks it (the first layer's random stream; no size check here).
RedfStartingSizes whole_fill_sizes(const TankFillingSpec &spec, double porosity);

/// The largest particle of the fill once grown, as fill_tank_in_layers first checks it (the
/// whole fill's draw at the first layer's porosity): the fill refuses layers thinner than five
/// times this. Each layer's own draw scatters round it by about 1 / sqrt(its particles) [m].
double largest_particle_extent(const TankFillingSpec &spec);

/// Layer k's levels and thickness: its top is layer_tops[k], or (k + 1) height / n_layers with the
/// last at height exactly [m].
double layer_bottom(const TankFillingSpec &spec, std::size_t k);
double layer_top(const TankFillingSpec &spec, std::size_t k);
double layer_thickness(const TankFillingSpec &spec, std::size_t k);
/// The thinnest layer, which the fill's grains must fit (five of the largest across it) [m].
double thinnest_layer(const TankFillingSpec &spec);
/// The number of layers whose tops lie at or below `level`, if a layer's top (or the base) is at
/// `level` within `tolerance`; none otherwise.
std::optional<std::size_t> layers_below_level(const TankFillingSpec &spec, double level, double tolerance);

/// The settings of the filled tank's system (gravity along -y, the spec's local damping and
/// threads, the automatic time step): those a system continuing a saved tank must have.
DemSettings tank_settling_settings(const TankFillingSpec &spec);
} // namespace geohybrid::dem
