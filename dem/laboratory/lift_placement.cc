#include "lift_placement.h"

#include "slab_porosity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace geohybrid::dem
{
namespace
{
/// A part of a lift's space that the laid sheets wall off from the rest: x in [x0, x1].
struct Compartment
{
  double x0 = 0.0, x1 = 0.0;
};

/// The parts, left to right, into which the laid sheets divide a lift's space [0, width] x
/// [bottom, lid]: a standing run of a sheet's segments (a wrap-around's held return: each
/// segment steeper than 45 degrees, all within `gap` of one x) whose faces reach from within
/// `gap` of the bottom to within `gap` of the lid is a wall no grain can pass (gap: the smallest
/// grain's width; a held return's foot stands on the lift below it, 0.1 t above its highest
/// grain, and its end 0.1 t below the lid of the lift the upper part is laid on).
/// The compartments end half the sheet's thickness from it; one, [0, width], if no sheet stands
/// across the lift.
std::vector<Compartment> lift_compartments(const std::vector<SparSheet> &sheets, double width, double bottom,
                                           double lid, double gap)
{
  std::vector<std::pair<double, double>> partitions; // [x_min, x_max] of each standing wall
  for (const SparSheet &sheet : sheets)
    {
      std::size_t k = 0;
      while (k < sheet.n_segments())
        {
          const auto steep = [&](std::size_t j) {
            const Vec2 a = sheet.node(j), b = sheet.node(j + 1);
            return std::abs(b.y() - a.y()) > std::abs(b.x() - a.x());
          };
          if (!steep(k))
            {
              ++k;
              continue;
            }
          // Its height over the whole run, its x over the segments in the lift's space (the foot
          // of a return, drawn along by the lower part, may stand a little off it).
          double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
          double y_min = sheet.y[k], y_max = y_min;
          const double half = 0.5 * sheet.thickness();
          for (; k < sheet.n_segments() && steep(k); ++k)
            {
              const Vec2 a = sheet.node(k), b = sheet.node(k + 1);
              y_min = std::min(y_min, b.y());
              y_max = std::max(y_max, b.y());
              if (std::max(a.y(), b.y()) + half > bottom && std::min(a.y(), b.y()) - half < lid)
                {
                  x_min = std::min({x_min, a.x(), b.x()});
                  x_max = std::max({x_max, a.x(), b.x()});
                }
            }
          if (x_max - x_min < gap && y_min - half < bottom + gap && y_max + half > lid - gap)
            partitions.emplace_back(x_min - 0.5 * sheet.thickness(), x_max + 0.5 * sheet.thickness());
        }
    }
  std::sort(partitions.begin(), partitions.end());
  std::vector<Compartment> compartments;
  double x = 0.0;
  for (const auto &[x_min, x_max] : partitions)
    {
      if (x_min - x > gap)
        compartments.push_back({x, x_min});
      x = std::max(x, x_max);
    }
  if (width - x > gap || compartments.empty())
    compartments.push_back({compartments.empty() ? 0.0 : x, width});
  return compartments;
}


/// The radii of the lift's grains shared among the compartments, one list each. Each
/// compartment's room is (1 - n) of its space less the sheets', less the solid of the grains
/// already in it (the band of the lift below, the tops of those under it).
std::vector<std::vector<double>> share_grains_among(const std::vector<Compartment> &compartments,
                                                    const std::vector<double> &radii, const std::vector<SparSheet> &laid,
                                                    const TankLayer &layer, double lid_level, const ParticleSet &particles)
{
  std::vector<double> room(compartments.size(), 0.0);
  double total_room = 0.0;
  for (std::size_t c = 0; c < compartments.size(); ++c)
    {
      const Compartment &part = compartments[c];
      double existing = 0.0;
      for (std::size_t b = 0; b < particles.n_bodies(); ++b)
        if (particles.x[b] >= part.x0 && particles.x[b] <= part.x1)
          existing += share_in_slab(particles, b, layer.bottom, lid_level) * particles.body_area(b);
      const double space_c = (part.x1 - part.x0) * (lid_level - layer.bottom) -
                             sheet_area_in_slab(laid, part.x0, part.x1, layer.bottom, lid_level);
      room[c] = std::max(0.0, (1.0 - layer.target_porosity) * space_c - existing);
      total_room += room[c];
    }
  if (!(total_room > 0.0)) // no room anywhere: the layer is too dense already; REDF says so
    {
      for (std::size_t c = 0; c < compartments.size(); ++c)
        room[c] = compartments[c].x1 - compartments[c].x0;
      total_room = 0.0;
      for (const double r : room)
        total_room += r;
    }
  // The grains, largest first, each to the compartment furthest below its share of the area
  // placed so far (areas as r^2: the grains have one shape): the shares come out exact to within
  // about the last grain's area.
  std::vector<std::vector<double>> radii_of(compartments.size());
  std::vector<double> placed(compartments.size(), 0.0);
  double placed_total = 0.0;
  for (const double r : radii)
    {
      placed_total += r * r;
      std::size_t best = 0;
      double lag_best = -std::numeric_limits<double>::infinity();
      for (std::size_t c = 0; c < compartments.size(); ++c)
        {
          const double lag = room[c] / total_room * placed_total - placed[c];
          if (lag > lag_best)
            {
              lag_best = lag;
              best = c;
            }
        }
      radii_of[best].push_back(r);
      placed[best] += r * r;
    }
  return radii_of;
}

/// Moves each new body [first_body, end) that a sheet would cut (a disc closer than r + t/2 to a
/// segment, possibly the two discs of a cluster on both sides of it) off the sheet, along the
/// segment's normal to the side of the body's centre (away from the node, near a free end).
/// Grains are placed at random in the next layer's space, through which a laid sheet runs; a
/// cluster placed astride the sheet would hold it pinched between its two discs forever. The
/// grains are then at a fraction of their final size, so the short moves leave them clear of
/// one another or nearly so (growth sorts out the rest).
void move_new_bodies_off_sheets(ParticleSet &p, std::size_t first_body, const std::vector<SparSheet> &sheets,
                                int n_threads)
{
  for (int pass = 0; pass < 4; ++pass)
    {
      bool moved = false;
      for (std::size_t b = first_body; b < p.n_bodies(); ++b)
        for (const SparSheet &sheet : sheets)
          for (std::size_t k = 0; k < sheet.n_segments(); ++k)
            {
              const Vec2 a = sheet.node(k), e = sheet.node(k + 1), centre(p.x[b], p.y[b]);
              const double length = (e - a).norm();
              const Vec2 u = (e - a) / length, n = perp(u);
              const double side = n.dot(centre - a) >= 0.0 ? 1.0 : -1.0;
              double shift = 0.0;
              Vec2 direction = side * n;
              for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
                {
                  const Vec2 c(p.disc_x[d], p.disc_y[d]);
                  const double clearance = p.disc_radius[d] + 0.5 * sheet.thickness() + 1e-6;
                  const double along = u.dot(c - a);
                  if (along >= 0.0 && along <= length)
                    shift = std::max(shift, clearance - side * n.dot(c - a));
                  else
                    {
                      // Past an end: away from the end node (at a joint, the next segment acts).
                      const Vec2 node = along < 0.0 ? a : e;
                      const double distance = (c - node).norm();
                      if (distance < clearance && ((along < 0.0 && k == 0) || (along > length && k + 1 == sheet.n_segments())))
                        {
                          direction = distance > 0.0 ? Vec2((c - node) / distance) : direction;
                          shift = std::max(shift, clearance - distance);
                        }
                    }
                }
              if (shift > 0.0)
                {
                  p.x[b] += shift * direction.x();
                  p.y[b] += shift * direction.y();
                  for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
                    {
                      p.disc_x[d] += shift * direction.x();
                      p.disc_y[d] += shift * direction.y();
                    }
                  moved = true;
                }
            }
      if (!moved)
        break;
    }
  p.update_disc_positions(n_threads); // the same positions, computed as everywhere else
}
} // namespace

void place_lift_grains(const TankFillingSpec &t, const RedfSpec &s, const std::vector<double> &radii,
                       const std::vector<SparSheet> &laid, const TankLayer &layer, double lid_level,
                       const std::string &where, ParticleSet &particles)
{
  const std::size_t first_body = particles.n_bodies();
  // A sheet standing across the lift (a wrap-around's held return) walls its space into
  // compartments that no grain passes between while the lift grows: each is a lift of its own,
  // and gets the share of the grains that fills it at the target porosity, the room its space
  // (less the sheets) leaves at that porosity beside the grains already there. Placed at random
  // over the whole lift, a compartment got its share of the area give or take the placement's
  // scatter: in the particle box of the full-size wrap-around (seed 2, lifts of 0.1 m), the third
  // lift's compartment behind the return, 0.098 m of its 1.1 m, got 9.4 % of its grains' area
  // for 9.0 % of its room; it jammed, frictionless, at porosity 0.18 under 229 kPa, which is all
  // of the 20.5 kPa the lid read, while the rest of the lift lay loose at 0.21 and the lift could
  // not be grown.
  const std::vector<Compartment> compartments = [&] {
    if (laid.empty())
      return std::vector<Compartment>{{0.0, t.width}};
    // The narrowest a grain is at its starting size: a gap below it passes none.
    const double smallest =
      2.0 * *std::min_element(radii.begin(), radii.end()) * (t.shape == ParticleShape::disc ? 1.0 : t.cluster_diameter_ratio);
    return lift_compartments(laid, t.width, layer.bottom, lid_level, smallest);
  }();
  try
    {
      if (compartments.size() == 1)
        place_at_random(s,
                        {Vec2(compartments[0].x0, layer.bottom), Vec2(compartments[0].x1, layer.bottom),
                         Vec2(compartments[0].x1, lid_level), Vec2(compartments[0].x0, lid_level)},
                        radii, s.seed, particles);
      else
        {
          const std::vector<std::vector<double>> radii_of =
            share_grains_among(compartments, radii, laid, layer, lid_level, particles);
          for (std::size_t c = 0; c < compartments.size(); ++c)
            if (!radii_of[c].empty())
              {
                const Compartment &part = compartments[c];
                // Each compartment its own random stream.
                place_at_random(s,
                                {Vec2(part.x0, layer.bottom), Vec2(part.x1, layer.bottom), Vec2(part.x1, lid_level),
                                 Vec2(part.x0, lid_level)},
                                radii_of[c], s.seed ^ (0xbf58476d1ce4e5b9ULL * (c + 1)), particles);
              }
        }
    }
  catch (const std::invalid_argument &e)
    {
      throw std::invalid_argument(where + e.what());
    }
  if (!laid.empty())
    move_new_bodies_off_sheets(particles, first_body, laid, t.n_threads);
}
} // namespace geohybrid::dem
