#include "sheet_inertia_estimate.h"

#include "tank_filling.h"

#include <algorithm>

namespace geohybrid::dem
{
SheetInertiaEstimate estimate_sheet_inertia(const PullOutTankSpec &spec)
{
  const TankFillingSpec t = spec.resolved_filling();
  // The fill's sizes as REDF scales them for the whole tank (as tank filling checks them), at the
  // loosest lift's porosity: the smallest grains, so the shortest step and the lightest sheet
  // this estimate can give. A lighter estimate only refuses less.
  const RedfStartingSizes sizes = whole_fill_sizes(
    t, t.layer_porosities.empty() ? t.target_porosity
                                  : *std::max_element(t.layer_porosities.begin(), t.layer_porosities.end()));
  const double r = *std::min_element(sizes.radii.begin(), sizes.radii.end()) * sizes.growth_to_target;

  // The smallest grain alone in a tank with one of its walls: the system's critical step is the
  // one its lightest grain and stiffest law set (DemSystem::critical_time_step).
  ParticleSet grain;
  const Vec2 centre(0.5 * t.width, 0.5 * t.height);
  if (t.shape == ParticleShape::disc)
    grain.add_disc(centre, r, t.density);
  else
    grain.add_two_disc_cluster(centre, r, t.cluster_diameter_ratio * r, 2.0 * t.cluster_spacing * r, 0.0, t.density);
  DemSystem tank(std::move(grain), LinearContactLaw(t.particle_contact), tank_settling_settings(t));
  tank.add_wall(Wall("base", Vec2(0.0, 0.0), Vec2(t.width, 0.0), LinearContactLaw(t.wall_contact)));

  // The sheet as laid at its nominal levels, scaled as fill_pull_out_tank scales it.
  const PullOutGeometry &g = spec.geometry;
  SparSheet sheet("geosynthetic", subdivide_polyline(g.sheet_corners(g.sheet_level()), spec.max_segment_length),
                  spec.sheet);
  SheetInertiaEstimate estimate;
  estimate.mass_scaling = tank.required_sheet_mass_scaling(sheet);
  sheet.set_mass_scaling(estimate.mass_scaling);
  for (std::size_t k = 1; k < sheet.n_nodes(); ++k) // node 0 is the clamp
    estimate.inertial_mass += sheet.mass[k];
  sheet.prescribe_velocity(0, Vec2::Zero());
  tank.add_sheet(sheet); // its interface law may be the stiffest: the step of the tank with it
  estimate.grain_time_step = tank.time_step();
  return estimate;
}
} // namespace geohybrid::dem
