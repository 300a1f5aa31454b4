#include "tank_cut.h"

#include "tank_walls.h"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace geohybrid::dem
{
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

  // The grains wholly inside, at rest: those cut by a side would overlap its wall.
  const ParticleSet &all = tank.tank.system.particles();
  std::vector<std::uint32_t> inside;
  for (std::size_t b = 0; b < all.n_bodies(); ++b)
    {
      bool in = true;
      for (std::uint32_t d = all.first_disc[b]; in && d < all.first_disc[b] + all.n_discs[b]; ++d)
        {
          const double r = all.disc_radius[d];
          in = all.disc_x[d] - r >= x0 && all.disc_x[d] + r <= x1 && all.disc_y[d] - r >= y0 && all.disc_y[d] + r <= y1;
        }
      if (in)
        inside.push_back(static_cast<std::uint32_t>(b));
    }
  ParticleSet particles = bodies_of(all, inside);
  for (std::size_t b = 0; b < particles.n_bodies(); ++b)
    {
      particles.x[b] -= x0;
      particles.y[b] -= y0;
      particles.vx[b] = particles.vy[b] = particles.omega[b] = 0.0;
      particles.fx[b] = particles.fy[b] = particles.torque[b] = 0.0;
    }
  particles.update_disc_positions();

  SparSheet sheet = laid;
  for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
    {
      sheet.x[k] -= x0;
      sheet.y[k] -= y0;
      if (!sheet.is_kinematic(k))
        sheet.vx[k] = sheet.vy[k] = 0.0;
    }

  DemSystem system(std::move(particles), LinearContactLaw(f.particle_contact), tank_settling_settings(f));
  // The lid parked one lift above the fill, as a fill leaves it; the front wall's slot where the
  // tank's is.
  const double parked = f.height + f.height / static_cast<double>(f.n_layers);
  const FilledTank &t = tank.tank;
  const bool slot = t.slot_top > t.slot_bottom;
  const TankWalls walls = add_tank_walls(system, f, parked, slot ? t.slot_bottom - y0 : 0.0, slot ? t.slot_top - y0 : 0.0);
  system.add_sheet(sheet);

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
