#include "tank_cut.h"

#include "tank_walls.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace geohybrid::dem
{
namespace
{
/// Gives the contacts of `to` (made of the bodies `kept` of `from`, in that order, and of its
/// sheet) the history they had in `from`: the tangential forces between the kept grains and
/// between them and the sheet, as the grains stood at rest there. The lists are found again at
/// the first step, which carries each state over by its pair (contact_list.h).
void carry_contact_history(const DemSystem &from, const std::vector<std::uint32_t> &kept, DemSystem &to)
{
  const ParticleSet &all = from.particles();
  constexpr std::uint32_t none = static_cast<std::uint32_t>(-1);
  // Each kept disc's index in `to`: increasing with its index in `from`, so sorted lists stay sorted.
  std::vector<std::uint32_t> disc_in_to(all.n_discs_total(), none);
  std::uint32_t next = 0;
  for (const std::uint32_t b : kept)
    for (std::uint32_t d = all.first_disc[b]; d < all.first_disc[b] + all.n_discs[b]; ++d)
      disc_in_to[d] = next++;
  const DemSystemState was = from.export_state();
  DemSystemState s = to.export_state();
  s.pairs = PairContacts();
  for (std::size_t k = 0; k < was.pairs.size(); ++k)
    {
      const std::uint32_t i = disc_in_to[was.pairs.disc_i[k]], j = disc_in_to[was.pairs.disc_j[k]];
      if (i == none || j == none)
        continue;
      s.pairs.disc_i.push_back(i);
      s.pairs.disc_j.push_back(j);
      s.pairs.state.push_back(was.pairs.state[k]);
    }
  s.pairs.resize_results();
  SheetContacts &sheet = s.sheet_contacts.at(0);
  const SheetContacts &laid = was.sheet_contacts.at(0);
  sheet.disc.clear();
  sheet.segment.clear();
  sheet.state.clear();
  for (std::size_t k = 0; k < laid.size(); ++k)
    if (const std::uint32_t d = disc_in_to[laid.disc[k]]; d != none)
      {
        sheet.disc.push_back(d);
        sheet.segment.push_back(laid.segment[k]);
        sheet.state.push_back(laid.state[k]);
      }
  sheet.resize_results();
  s.rebuild_needed = true;
  to.restore_state(std::move(s));
}
} // namespace

PullOutTank cut_pull_out_tank(const PullOutTank &tank, double tank_length, const PullOutTankSpec &region,
                              const Vec2 &origin, const std::string &where)
{
  const TankFillingSpec f = region.resolved_filling();
  const double x0 = origin.x(), y0 = origin.y(), x1 = x0 + f.width, y1 = y0 + f.height;
  const double tolerance = 1e-9 * tank_length;
  if (!(x0 >= -tolerance && y0 >= -tolerance) || std::abs(x1 - tank_length) > tolerance)
    {
      std::ostringstream message;
      message << where << ": the region [" << x0 << ", " << x1 << "] x [" << y0 << ", " << y1
              << "] m must lie in the tank and reach its front wall at x = " << tank_length << " m";
      throw std::invalid_argument(message.str());
    }
  const SparSheet &laid = tank.tank.system.sheets().at(0);
  for (std::size_t k = 0; k < laid.n_nodes(); ++k)
    // The clamp and the nodes through the slot stand beyond the front wall, as in the tank.
    if (laid.y[k] < y0 || laid.y[k] > y1 || laid.x[k] < x0)
      throw std::invalid_argument(where + ": the sheet's node " + std::to_string(k) +
                                  " lies outside the region cut from the filled tank");

  // The grains whose centres lie inside, at rest: a grain cut by a side stays, as the soil beyond
  // it goes on (left out, they left a looser ring round the box).
  const ParticleSet &all = tank.tank.system.particles();
  std::vector<std::uint32_t> inside;
  for (std::size_t b = 0; b < all.n_bodies(); ++b)
    if (all.x[b] >= x0 && all.x[b] <= x1 && all.y[b] >= y0 && all.y[b] <= y1)
      inside.push_back(static_cast<std::uint32_t>(b));
  ParticleSet particles = bodies_of(all, inside);
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    {
      particles.x[b] -= x0;
      particles.y[b] -= y0;
      particles.vx[b] = particles.vy[b] = particles.omega[b] = 0.0;
      particles.fx[b] = particles.fy[b] = particles.torque[b] = 0.0;
    }
  particles.update_disc_positions();
  // How far the cut grains stand past the region's left side, its base and its top.
  double left = 0.0, below = 0.0, above = 0.0;
  for (std::size_t d = 0; d < particles.n_discs_total(); ++d)
    {
      const double r = particles.disc_radius[d];
      left = std::max(left, -(particles.disc_x[d] - r));
      below = std::max(below, -(particles.disc_y[d] - r));
      above = std::max(above, particles.disc_y[d] + r - f.height);
    }

  SparSheet sheet = laid;
  for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
    {
      sheet.x[k] -= x0;
      sheet.y[k] -= y0;
      if (!sheet.is_kinematic(k))
        sheet.vx[k] = sheet.vy[k] = 0.0;
    }

  DemSystem system(std::move(particles), LinearContactLaw(f.particle_contact), tank_settling_settings(f));
  // The lid parked one lift above the fill, as a fill leaves it, and above the grains cut by the
  // top; the base and the left wall moved out past the grains cut by them (they touch none); the
  // front wall's slot where the tank's is.
  const double parked = f.height + above + layer_thickness(f, f.n_layers - 1);
  const FilledTank &t = tank.tank;
  const bool slot = t.slot_top > t.slot_bottom;
  const TankWalls walls = add_tank_walls(system, f, parked, slot ? t.slot_bottom - y0 : 0.0, slot ? t.slot_top - y0 : 0.0);
  system.walls()[walls.left].translate(Vec2(-left, 0.0));
  system.walls()[walls.base].translate(Vec2(0.0, -below));
  system.add_sheet(sheet);
  carry_contact_history(tank.tank.system, inside, system);

  PullOutTank cut{FilledTank{std::move(system), walls, {}, slot ? t.slot_bottom - y0 : 0.0, slot ? t.slot_top - y0 : 0.0},
                  tank.sheet_level - y0,
                  tank.lower_part_end,
                  tank.first_node_inside,
                  tank.arc_length,
                  {},
                  0};
  for (const Vec2 &node : tank.initial_nodes)
    cut.initial_nodes.emplace_back(node.x() - x0, node.y() - y0);
  return cut;
}
} // namespace geohybrid::dem
