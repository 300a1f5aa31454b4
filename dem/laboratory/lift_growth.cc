#include "lift_growth.h"

#include "slab_porosity.h"
#include "tank_walls.h"

#include <stdexcept>
#include <utility>

namespace geohybrid::dem
{
DemSystemState grow_lift(ParticleSet particles, const TankFillingSpec &t, const RedfSpec &s,
                         const LinearContactLaw &material, const DemSettings &growth_settings,
                         const std::vector<SparSheet> &laid, const LiftLevels &levels, const std::string &where,
                         const std::function<void(double)> &progress, TankLayer &layer)
{
  const std::size_t first_body = layer.first_body;
  // While this layer grows, the grains below its slab are fixed (a compacted lift is nearly
  // rigid under the next one): their share of the slab is constant. The grains of the layer
  // below that stand in the slab (its band) stay free, so that they can rearrange with the new
  // grains, as the top of a lift does when the next one is compacted on it.
  // The porosity is that of the measured part of the slab (TankLayer::measured_bottom, _top).
  const double y0 = layer.measured_bottom, y1 = layer.measured_top;
  double fixed_solid = 0.0;
  std::vector<std::size_t> free_below;
  for (std::size_t b = 0; b < first_body; ++b)
    if (particles.y[b] < layer.bottom)
      {
        particles.fix_body(b);
        fixed_solid += share_in_slab(particles, b, y0, y1) * particles.body_area(b);
      }
    else
      free_below.push_back(b);
  const double sheet_area = sheet_area_in_slab(laid, 0.0, t.width, y0, y1);
  std::vector<double> starting_area(layer.n_bodies);
  for (std::size_t i = 0; i < layer.n_bodies; ++i)
    starting_area[i] = particles.body_area(first_body + i);

  DemSystem growing(std::move(particles), material, growth_settings);
  growing.set_skip_contacts_between_fixed_bodies(true); // the lifts below are fixed: their contacts cannot change
  const TankWalls walls = add_tank_walls(growing, t, levels.lid, levels.slot_bottom, levels.slot_top);
  // A sheet laid on the layers below stays where it lies while this layer grows round it.
  for (const SparSheet &sheet : laid)
    growing.add_sheet(sheet);
  double area_factor = 1.0; // (size now / starting size)^2 of the growing particles
  RedfGrowth growth;
  growth.jam_stress = [&] { return growing.walls()[walls.lid].normal_stress(); };
  growth.porosity = [&] {
    const ParticleSet &p = growing.particles();
    double solid = fixed_solid, grown_solid = 0.0; // grown_solid at the starting sizes
    for (const std::size_t b : free_below)
      solid += share_in_slab(p, b, y0, y1) * p.body_area(b);
    for (std::size_t i = 0; i < layer.n_bodies; ++i)
      grown_solid += share_in_slab(p, first_body + i, y0, y1) * starting_area[i];
    return 1.0 - (solid + area_factor * grown_solid) / (t.width * (y1 - y0) - sheet_area);
  };
  growth.grow = [&](double factor) {
    growing.scale_particle_sizes(factor, first_body); // the lifts below keep their sizes
    area_factor *= factor * factor;
  };
  RedfGrowthResult grown;
  try
    {
      grown = grow_by_redf(growing, s, growth, progress);
    }
  catch (const std::runtime_error &e)
    {
      throw std::runtime_error(where + e.what());
    }
  layer.porosity_grown = growth.porosity();
  layer.growth_friction_deg = grown.growth_friction_deg;
  layer.n_growth_steps = grown.n_steps;
  growing.set_particle_law(material);
  // The lid parked above the fill (its top layer's thickness above it), where it touches nothing.
  const double thickness = layer_thickness(t, t.n_layers - 1);
  growing.walls()[walls.lid].translate(Vec2(0.0, t.height + thickness - levels.lid));
  return growing.export_state();
}
} // namespace geohybrid::dem
