// A pull-out in a checkpoint: the filled tank's description, the pull's progress and the stress
// measured before it, in the command state beside the system's (pullout_tank.h).
#include "pullout_tank.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace geohybrid::dem
{
namespace
{
constexpr const char *command_name = "pullout";
constexpr std::size_t layer_fields = 10;

void check_command(const CommandState &c)
{
  if (c.name != command_name)
    throw std::runtime_error("the checkpoint is not a pull-out's (" +
                             (c.name.empty() ? std::string("no command state") : "written by '" + c.name + "'") + ")");
}
} // namespace

void store_pullout_tank(const PullOutTank &tank, CommandState &c)
{
  c.name = command_name;
  const FilledTank &f = tank.tank;
  c.counts["tank_walls"] = {f.walls.base, f.walls.right, f.walls.lid, f.walls.left, f.walls.right_upper};
  c.reals["slot"] = {f.slot_bottom, f.slot_top};
  std::vector<double> layers;
  for (const TankLayer &l : f.layers)
    layers.insert(layers.end(), {l.bottom, l.top, static_cast<double>(l.first_body), static_cast<double>(l.n_bodies),
                                 l.target_porosity, l.porosity_grown, l.porosity, l.growth_friction_deg,
                                 static_cast<double>(l.n_growth_steps), static_cast<double>(l.n_settling_steps)});
  c.reals["layers"] = layers;
  std::vector<std::uint64_t> kept;
  for (const TankLayer &l : f.layers)
    kept.push_back(l.from_cache ? 1 : 0);
  c.counts["layers_kept"] = kept; // absent from checkpoints written before the lift cache
  c.reals["sheet_level"] = {tank.sheet_level};
  c.counts["sheet_nodes"] = {tank.lower_part_end, tank.first_node_inside};
  c.counts["final_settling_steps"] = {tank.n_final_settling_steps};
  c.reals["arc_length"] = tank.arc_length;
  std::vector<double> nodes;
  for (const Vec2 &v : tank.initial_nodes)
    nodes.insert(nodes.end(), {v.x(), v.y()});
  c.reals["initial_nodes"] = nodes;
}

PullOutTank restore_pullout_tank(DemSystemState state, const DemSettings &settings, const CommandState &c)
{
  check_command(c);
  DemSystem system(state.particles, LinearContactLaw(state.particle_contact), settings);
  for (const Wall &wall : state.walls)
    system.add_wall(wall); // replaced by the saved walls: restore_state needs as many
  system.restore_state(std::move(state));
  const std::vector<std::uint64_t> &w = c.count("tank_walls", 5);
  const std::vector<double> &slot = c.real("slot", 2);
  TankWalls walls{w[0], w[1], w[2], w[3], w[4]};
  std::vector<TankLayer> layers;
  const std::vector<double> &l = c.real("layers");
  if (l.size() % layer_fields != 0)
    throw std::runtime_error("checkpoint of 'pullout': array 'layers' is not a whole number of layers");
  for (std::size_t k = 0; k < l.size(); k += layer_fields)
    {
      TankLayer layer;
      layer.bottom = l[k];
      layer.top = l[k + 1];
      layer.first_body = static_cast<std::size_t>(l[k + 2]);
      layer.n_bodies = static_cast<std::size_t>(l[k + 3]);
      layer.target_porosity = l[k + 4];
      layer.porosity_grown = l[k + 5];
      layer.porosity = l[k + 6];
      layer.growth_friction_deg = l[k + 7];
      layer.n_growth_steps = static_cast<std::uint64_t>(l[k + 8]);
      layer.n_settling_steps = static_cast<std::uint64_t>(l[k + 9]);
      layers.push_back(layer);
    }
  if (c.counts.count("layers_kept"))
    {
      const std::vector<std::uint64_t> &kept = c.count("layers_kept", layers.size());
      for (std::size_t k = 0; k < layers.size(); ++k)
        layers[k].from_cache = kept[k] != 0;
    }
  const std::size_t n_nodes = system.sheets().empty() ? 0 : system.sheets()[0].n_nodes();
  if (n_nodes == 0)
    throw std::runtime_error("checkpoint of 'pullout': the saved system has no sheet");
  PullOutTank tank{FilledTank{std::move(system), walls, std::move(layers), slot[0], slot[1]}, c.real("sheet_level", 1)[0],
                   0, 0, c.real("arc_length", n_nodes), {}};
  const std::vector<std::uint64_t> &nodes = c.count("sheet_nodes", 2);
  tank.lower_part_end = nodes[0];
  tank.first_node_inside = nodes[1];
  tank.n_final_settling_steps = c.count("final_settling_steps", 1)[0];
  const std::vector<double> &initial = c.real("initial_nodes", 2 * n_nodes);
  for (std::size_t k = 0; k < n_nodes; ++k)
    tank.initial_nodes.emplace_back(initial[2 * k], initial[2 * k + 1]);
  if (tank.lower_part_end >= n_nodes || tank.first_node_inside >= n_nodes)
    throw std::runtime_error("checkpoint of 'pullout': sheet node indices out of range");
  return tank;
}

void store_pull_progress(const PullProgress &p, CommandState &c)
{
  c.reals["pull"] = {p.clamp_x0, p.time0, p.tension_sum, p.next_record};
  c.counts["pull"] = {p.n_summed, p.n_steps, p.finished ? 1u : 0u};
  const auto parts = p.parts_sum.as_array();
  c.reals["pull_parts_sum"] = std::vector<double>(parts.begin(), parts.end());
}

std::optional<PullProgress> restore_pull_progress(const CommandState &c)
{
  check_command(c);
  if (c.reals.count("pull") == 0)
    return std::nullopt;
  const std::vector<double> &r = c.real("pull", 4);
  const std::vector<std::uint64_t> &n = c.count("pull", 3);
  PullProgress p;
  p.clamp_x0 = r[0];
  p.time0 = r[1];
  p.tension_sum = r[2];
  p.next_record = r[3];
  p.n_summed = n[0];
  p.n_steps = n[1];
  p.finished = n[2] != 0;
  // Checkpoints written before the decomposition was recorded have no sums: the interval under
  // way then starts its decomposition from where the run resumes (the curve is unaffected).
  if (c.reals.count("pull_parts_sum") != 0)
    {
      const std::vector<double> &s = c.real("pull_parts_sum", HeadTensionParts::n_terms);
      std::array<double, HeadTensionParts::n_terms> a;
      std::copy(s.begin(), s.end(), a.begin());
      p.parts_sum = HeadTensionParts::from_array(a);
    }
  return p;
}

void store_sheet_level_stress(const SheetLevelStress &s, CommandState &c)
{
  c.reals["sheet_level_stress"] = {s.top_face, s.bottom_face, s.normal_force_both_faces, s.love_weber_above,
                                   s.lower_part_length};
}

SheetLevelStress restore_sheet_level_stress(const CommandState &c)
{
  check_command(c);
  const std::vector<double> &r = c.real("sheet_level_stress", 5);
  return SheetLevelStress{r[0], r[1], r[2], r[3], r[4]};
}
} // namespace geohybrid::dem
