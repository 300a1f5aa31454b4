#pragma once
// Sample generation by Radius Expansion with Decrease of Friction (REDF, Chareyre & Villard
// 2005), as used for the reference paper's samples (section 4.1):
//
//  1. particles are placed at random, without gravity and without overlap, at a fraction of their
//     final size, inside a box of four rigid walls;
//  2. their sizes grow slowly; when the assembly jams (mean wall stress above the target) while
//     the porosity is still above its target, the inter-particle friction used during growth is
//     lowered step by step, so the grains rearrange into a denser state; growth stops at the
//     target porosity;
//  3. the material friction is restored and the four walls are servo-controlled to the target
//     isotropic stress until the sample is in equilibrium.
//
// The final particle sizes follow from the box, the number of particles and the porosity:
// the size distribution given is a shape (relative sizes), scaled to fill the box.
#include "box.h"
#include "dem_system.h"
#include "packing.h"

#include <functional>

namespace geohybrid::dem
{
struct RedfSpec
{
  double width = 0.2, height = 0.4;    ///< inner size of the box [m]
  std::size_t n_particles = 4000;
  ParticleShape shape = ParticleShape::two_disc_cluster;
  double size_ratio = 0.5;             ///< smallest / largest large-disc radius (uniform) [-]
  double cluster_diameter_ratio = 0.9; ///< small / large disc diameter in a cluster [-]
  double cluster_spacing = 0.95;       ///< centre spacing / large diameter; 0.95 = touching [-]
  double density = 2650.0;             ///< [kg/m^3]
  double target_porosity = 0.2;
  double porosity_tolerance = 0.005;
  double target_stress = 10.0e3;       ///< isotropic confining stress of the final state [Pa]
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

/// Builds the sample. `progress` (optional) is called now and then with a fraction in [0, 1].
/// Throws std::invalid_argument for a spec that cannot work (target porosity outside [0.05, 0.8],
/// too many particles for random placement) and std::runtime_error when the target porosity is
/// not met within tolerance (too loose for the material friction, or too dense even without
/// friction), naming the porosity that was reached.
RedfSample make_redf_sample(const RedfSpec &spec, const std::function<void(double)> &progress = {});
} // namespace geohybrid::dem
