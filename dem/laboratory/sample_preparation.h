#pragma once
// Sample generation by Radius Expansion with Decrease of Friction (REDF, Chareyre & Villard
// 2005), as used for the reference paper's samples (section 4.1):
//
//  1. particles are placed at random, without gravity and without overlap, at a fraction of their
//     final size, inside a box of four rigid walls (or any convex polygon of walls);
//  2. their sizes grow slowly; when the assembly jams (mean wall stress above the target) while
//     the porosity is still above its target, the inter-particle friction used during growth is
//     lowered step by step, so the grains rearrange into a denser state; growth stops at the
//     target porosity;
//  3. the material friction is restored and the walls are servo-controlled to the target
//     isotropic stress until the sample is in equilibrium.
//
// The final particle sizes follow from the box, the number of particles and the porosity:
// the size distribution given is a shape (relative sizes, SizeDistribution), scaled to fill the
// box. The growth stage and the random placement are also offered on their own, for the
// layer-by-layer filling of a tank (tank_filling.h).
#include "dem/dem_system.h"
#include "box.h"
#include "packing.h"

#include <functional>
#include <string>
#include <vector>

namespace geohybrid::dem
{
struct RedfSpec
{
  double width = 0.2, height = 0.4;    ///< inner size of the box [m]
  std::size_t n_particles = 4000;
  ParticleShape shape = ParticleShape::two_disc_cluster;
  /// Relative sizes (uniform between a ratio and 1, or area fractions per size class), scaled so
  /// that the particles fill the box at the target porosity.
  SizeDistribution size_distribution = SizeDistribution::uniform(0.5);
  double cluster_diameter_ratio = 0.9; ///< small / large disc diameter in a cluster [-]
  double cluster_spacing = 0.95;       ///< centre spacing / large diameter; 0.95 = touching [-]
  double density = 2650.0;             ///< [kg/m^3]
  double target_porosity = 0.2;
  double porosity_tolerance = 0.005;
  /// Isotropic confining stress of the final state; growth also counts the assembly jammed when
  /// the walls' mean stress exceeds it [Pa]
  double target_stress = 10.0e3;
  double stress_tolerance = 0.02;      ///< relative, for the final equilibrium
  double equilibrium_unbalanced_ratio = 1e-3; ///< unbalanced-force ratio of the final equilibrium
  ContactParameters particle_contact;  ///< the material (friction restored at the end)
  /// Friction angle at the start of growth; negative = the material's. A higher one lets the
  /// assembly jam looser; REDF then lowers it step by step until it jams at the target porosity.
  double initial_growth_friction_deg = -1.0;
  ContactParameters wall_contact;      ///< the box walls (frictionless for a biaxial test)
  std::uint64_t seed = 1;
  int n_threads = 1;
  std::uint64_t max_steps = 3'000'000; ///< give up beyond this many steps
};

struct RedfResult
{
  double porosity = 0.0;
  double mean_stress = 0.0;            ///< mean of the four wall stresses [Pa]
  double growth_friction_deg = 0.0;    ///< the lowest friction used during growth
  double size_scale = 0.0;             ///< final radii / initial radii
  std::uint64_t n_steps = 0;
};

struct RedfSample
{
  DemSystem system;     ///< the sample, in equilibrium, walls servo-controlled to the stress
  RectangularBox box;
  RedfResult result;
};

/// Builds the sample in the box [0, width] x [0, height]. `progress` (optional) is called now and
/// then with a fraction in [0, 1]. Throws std::invalid_argument for a spec that cannot work
/// (target porosity outside [0.05, 0.8], too many particles for random placement) and
/// std::runtime_error when the target porosity is not met within tolerance (too loose for the
/// material friction, or too dense even without friction), naming the porosity that was reached.
RedfSample make_redf_sample(const RedfSpec &spec, const std::function<void(double)> &progress = {});

struct RedfPolygonSample
{
  DemSystem system;     ///< the sample, in equilibrium, walls servo-controlled to the stress
  WallPolygon boundary; ///< one wall per side; porosity = 1 - solid area / boundary.area()
  RedfResult result;    ///< mean_stress: WallPolygon::mean_stress
};

/// The same in the convex polygon of walls whose corners are `vertices` (counter-clockwise);
/// spec.width and spec.height are not used. Each wall is servo-controlled along its normal to
/// the target stress at the end, and the equilibrium holds every wall within the stress
/// tolerance. Throws as make_redf_sample, and std::invalid_argument for a polygon that is not
/// convex and counter-clockwise.
RedfPolygonSample make_redf_sample_in_polygon(const RedfSpec &spec, const std::vector<Vec2> &vertices,
                                              const std::function<void(double)> &progress = {});

// ---- building blocks (also used by tank filling) ----

struct RedfStartingSizes
{
  std::vector<double> radii;   ///< large-disc radii to place, largest first [m]
  double largest_extent = 0.0; ///< of the largest particle once grown to the target porosity [m]
  double growth_to_target = 1.0; ///< radii at the target porosity / the radii above [-]
};

/// The starting sizes of a REDF region: relative sizes from spec.size_distribution
/// (spec.n_particles of them, random from spec.seed) scaled so that they fill `region_area` at a
/// solid fraction of min(0.45, 0.75 (1 - target porosity)), where random placement succeeds
/// easily. Throws std::invalid_argument (naming `region`, e.g. "a 0.2 m x 0.4 m box") for an
/// invalid spec or if the largest particle at the target porosity would be wider than a fifth of
/// `region_narrowest_width`: a sample must be many particles across.
RedfStartingSizes redf_starting_sizes(const RedfSpec &spec, double region_area, double region_narrowest_width,
                                      const std::string &region);

/// Appends particles of the given large-disc radii (in that order) at random positions and
/// orientations inside the convex polygon `vertices`, without overlap with each other or with
/// the particles already in `particles`; shape, cluster geometry and density from the spec.
/// Throws std::invalid_argument if one finds no place after many tries.
void place_at_random(const RedfSpec &spec, const std::vector<Vec2> &vertices, const std::vector<double> &radii,
                     std::uint64_t seed, ParticleSet &particles);

/// Each lowering of REDF's growth friction multiplies it by this (below 0.5 degrees, it goes to 0).
inline constexpr double redf_friction_drop = 0.9;

/// What REDF's growth stage acts on, so that the same loop grows a whole sample or one layer.
struct RedfGrowth
{
  std::function<double()> jam_stress; ///< above spec.target_stress the assembly counts as jammed [Pa]
  std::function<double()> porosity;   ///< porosity of the growing region [-]
  std::function<void(double)> grow;   ///< scales the growing particles' sizes by a factor
};

struct RedfGrowthResult
{
  double growth_friction_deg = 0.0; ///< the lowest friction used
  std::uint64_t n_steps = 0;
};

/// Grows (without gravity: the system's settings) until the porosity is at most half a tolerance
/// above spec.target_porosity, lowering the growth friction step by step while the assembly is
/// jammed above it; leaves the growth friction in force. Throws std::runtime_error if the target
/// cannot be reached even without friction or after spec.max_steps steps.
RedfGrowthResult grow_by_redf(DemSystem &system, const RedfSpec &spec, const RedfGrowth &growing,
                              const std::function<void(double)> &progress = {});
} // namespace geohybrid::dem
