#include "sheet_contacts.h"

#include "contact_frame.h"

#include <algorithm>
#include <cmath>

namespace geohybrid::dem
{
void SheetWallContacts::resize_results()
{
  const std::size_t n = size();
  for (auto *v : {&force_x, &force_y, &elastic_normal_force, &friction_work, &viscous_work})
    v->assign(n, 0.0);
}

void SheetContacts::resize_results()
{
  const std::size_t n = size();
  for (auto *v : {&position, &overlap, &force_x, &force_y, &elastic_normal_force, &friction_work, &viscous_work})
    v->assign(n, 0.0);
  counted.assign(n, 0);
}

namespace
{
/// Parameter in [0, 1] of the point of segment [a, b] closest to c (0 for a collapsed segment,
/// which a slack sheet may have).
double closest_parameter(const Vec2 &c, const Vec2 &a, const Vec2 &b)
{
  const Vec2 ab = b - a;
  const double length2 = ab.squaredNorm();
  return length2 > 0.0 ? std::clamp((c - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
}
} // namespace

void SheetContactSearch::rebuild(const ParticleSet &p, const NeighbourSearch &search, const SparSheet &sheet,
                                 const std::vector<Wall> &walls, double skin, SheetContacts &c)
{
  const double half_thickness = 0.5 * sheet.thickness();

  // Disc-segment candidates, as keys (disc << 32 | segment) so that one sort orders them.
  double r_max = 0.0;
  for (double r : p.disc_radius)
    r_max = std::max(r_max, r);
  const double margin = r_max + half_thickness + skin;
  keys_.clear();
  for (std::size_t k = 0; k < sheet.n_segments(); ++k)
    {
      const Vec2 a = sheet.node(k), b = sheet.node(k + 1);
      const Vec2 lo = a.cwiseMin(b) - Vec2::Constant(margin), hi = a.cwiseMax(b) + Vec2::Constant(margin);
      near_.clear();
      search.append_discs_near_box(lo, hi, near_);
      for (std::uint32_t d : near_)
        {
          const Vec2 centre(p.disc_x[d], p.disc_y[d]);
          const double s = closest_parameter(centre, a, b);
          const double reach = p.disc_radius[d] + half_thickness + skin;
          if ((centre - point_on_segment(sheet, k, s)).squaredNorm() < reach * reach)
            keys_.push_back((std::uint64_t(d) << 32) | k);
        }
    }
  std::sort(keys_.begin(), keys_.end());

  // The history is the contact state and the last elastic normal force (the energy a contact
  // switched off by the node rule releases).
  std::swap(previous_.disc, c.disc);
  std::swap(previous_.segment, c.segment);
  std::swap(previous_.state, c.state);
  std::swap(previous_.elastic_normal_force, c.elastic_normal_force);
  c.disc.resize(keys_.size());
  c.segment.resize(keys_.size());
  c.state.assign(keys_.size(), ContactState{});
  c.resize_results();
  std::size_t old = 0;
  for (std::size_t q = 0; q < keys_.size(); ++q)
    {
      c.disc[q] = static_cast<std::uint32_t>(keys_[q] >> 32);
      c.segment[q] = static_cast<std::uint32_t>(keys_[q] & 0xffffffffu);
      // Carry the history over: both lists are sorted by key.
      const auto old_key = [this](std::size_t i) {
        return (std::uint64_t(previous_.disc[i]) << 32) | previous_.segment[i];
      };
      while (old < previous_.disc.size() && old_key(old) < keys_[q])
        ++old;
      if (old < previous_.disc.size() && old_key(old) == keys_[q])
        {
          c.state[q] = previous_.state[old];
          c.elastic_normal_force[q] = previous_.elastic_normal_force[old];
        }
    }

  // Node-wall candidates, per wall, sorted by node.
  c.walls.resize(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w)
    {
      SheetWallContacts &wc = c.walls[w];
      std::swap(previous_wall_.node, wc.node);
      std::swap(previous_wall_.state, wc.state);
      wc.node.clear();
      Vec2 closest;
      for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
        if (walls[w].touches_sheets &&
            closest_point_on_segment(sheet.node(k), walls[w].start, walls[w].end, closest) < half_thickness + skin)
          wc.node.push_back(static_cast<std::uint32_t>(k));
      wc.state.assign(wc.node.size(), ContactState{});
      std::size_t o = 0;
      for (std::size_t q = 0; q < wc.node.size(); ++q)
        {
          while (o < previous_wall_.node.size() && previous_wall_.node[o] < wc.node[q])
            ++o;
          if (o < previous_wall_.node.size() && previous_wall_.node[o] == wc.node[q])
            wc.state[q] = previous_wall_.state[o];
        }
      wc.resize_results();
    }

  c.node_x_at_rebuild = sheet.x;
  c.node_y_at_rebuild = sheet.y;
}

double largest_node_move(const SparSheet &sheet, const SheetContacts &c)
{
  double move2 = 0.0;
  for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
    {
      const double dx = sheet.x[k] - c.node_x_at_rebuild[k], dy = sheet.y[k] - c.node_y_at_rebuild[k];
      move2 = std::max(move2, dx * dx + dy * dy);
    }
  return std::sqrt(move2);
}

namespace
{
/// The node rule (see the header): whether the contact of the disc at `centre` with segment k
/// counts. Decided from the signs of the projections on segment k and, at its end, on k + 1;
/// the same products, computed the same way, decide for both segments at a shared node, so
/// exactly one of them claims a disc whose projections clamp at that node.
bool node_rule_counts(const SparSheet &sheet, std::size_t k, const Vec2 &centre)
{
  const Vec2 a = sheet.node(k), b = sheet.node(k + 1), ab = b - a;
  if ((centre - a).dot(ab) <= 0.0) // clamped at the start node
    return k == 0;                 // the free end's cap; otherwise segment k - 1 decides
  if ((centre - b).dot(ab) >= 0.0) // clamped at the end node
    return k + 1 == sheet.n_segments() || (centre - b).dot(sheet.node(k + 2) - b) <= 0.0; // convex vertex
  return true;
}

/// Two counted contacts of one disc on adjacent segments are interior contacts on the concave side
/// of their joint. If the segments turn by less than this angle (nearly straight), the disc
/// presses one face, not two: only the deeper contact counts, and ownership passes from one to
/// the other where their overlaps are equal, so the force magnitude is continuous (its direction
/// turns by the joint's angle). At a sharper concave corner both count: a second contact then
/// starts at zero overlap, unless the disc overlaps the sheet by more than r (1 - cos(angle)),
/// 1.5 % of r at 10 degrees (an impact, not a quasi-static contact).
const double same_face_cosine = std::cos(degrees_to_radians(10.0));

/// Applies the rule above to the counted contacts [begin, end) of one disc (sorted by segment):
/// along a chain of adjacent segments whose contact normals differ by less than the angle, the
/// deepest contact counts (the lower segment on a tie).
void one_contact_per_face(const ParticleSet &p, const SparSheet &sheet, SheetContacts &c, std::size_t begin,
                          std::size_t end)
{
  const Vec2 centre(p.disc_x[c.disc[begin]], p.disc_y[c.disc[begin]]);
  const auto normal = [&](std::size_t q) {
    return Vec2(point_on_segment(sheet, c.segment[q], c.position[q]) - centre).normalized();
  };
  std::size_t deepest = end, last = end; // the current chain
  for (std::size_t q = begin; q < end; ++q)
    {
      if (!c.counted[q])
        {
          deepest = last = end;
          continue;
        }
      if (last != end && c.segment[q] == c.segment[last] + 1 && normal(q).dot(normal(last)) > same_face_cosine)
        {
          if (c.overlap[q] > c.overlap[deepest])
            {
              c.counted[deepest] = 0;
              deepest = q;
            }
          else
            c.counted[q] = 0;
        }
      else
        deepest = q;
      last = q;
    }
}

/// Moves the history of contacts switched off by the node rule to the adjacent segment's contact
/// of the same disc that has just been switched on and touches, so friction carries across a
/// node. Contacts [begin, end) are one disc's, sorted by segment.
void hand_over_at_nodes(SheetContacts &c, std::size_t begin, std::size_t end)
{
  for (std::size_t q = begin; q < end; ++q)
    {
      ContactState &taker = c.state[q];
      if (!c.counted[q] || taker.touching || taker.bonded || !(c.overlap[q] > 0.0))
        continue;
      for (std::size_t o = begin; o < end; ++o)
        {
          const bool adjacent = c.segment[o] + 1 == c.segment[q] || c.segment[q] + 1 == c.segment[o];
          if (adjacent && !c.counted[o] && (c.state[o].touching || c.state[o].bonded))
            {
              taker = c.state[o];
              c.state[o] = ContactState{};
              break;
            }
        }
    }
}
} // namespace

SheetContactWork evaluate_sheet_contacts(ParticleSet &p, SparSheet &sheet, SheetContacts &c, double dt,
                                         bool track_energy)
{
  const LinearContactLaw &law = sheet.interface_law();
  const double half_thickness = 0.5 * sheet.thickness();
  const std::size_t n = c.size();

  // 1. Geometry and the node rule, for every candidate.
  for (std::size_t q = 0; q < n; ++q)
    {
      const std::uint32_t d = c.disc[q], k = c.segment[q];
      const Vec2 centre(p.disc_x[d], p.disc_y[d]);
      const double s = closest_parameter(centre, sheet.node(k), sheet.node(k + 1));
      c.position[q] = s;
      c.overlap[q] = p.disc_radius[d] + half_thickness - (point_on_segment(sheet, k, s) - centre).norm();
      c.counted[q] = node_rule_counts(sheet, k, centre) ? 1 : 0;
    }
  // 2. One contact per face at nearly straight concave joints, then the hand-over of the
  //    tangential history at nodes, disc by disc (a disc's candidates are consecutive).
  for (std::size_t begin = 0, end = 0; begin < n; begin = end)
    {
      end = begin + 1;
      while (end < n && c.disc[end] == c.disc[begin])
        ++end;
      if (end - begin > 1)
        {
          one_contact_per_face(p, sheet, c, begin, end);
          hand_over_at_nodes(c, begin, end);
        }
    }
  // 3. Forces, in list order.
  SheetContactWork work;
  for (std::size_t q = 0; q < n; ++q)
    {
      ContactState &state = c.state[q];
      const double overlap = c.overlap[q];
      const bool holds_history = state.touching || state.bonded;
      if (!holds_history && (!c.counted[q] || overlap <= 0.0))
        {
          c.force_x[q] = c.force_y[q] = c.elastic_normal_force[q] = 0.0;
          c.friction_work[q] = c.viscous_work[q] = 0.0;
          continue;
        }
      const std::uint32_t d = c.disc[q], k = c.segment[q], b = p.disc_body[d];
      const double s = c.position[q];
      const Vec2 centre(p.disc_x[d], p.disc_y[d]), closest = point_on_segment(sheet, k, s);
      const double distance = (closest - centre).norm();
      // A disc centre on the centre line (a very deep overlap) has no defined normal: take the
      // segment's right-hand normal.
      const Vec2 normal = ContactFrame::normal_towards(centre, closest, distance, [&]() -> Vec2 {
        const Vec2 ab = sheet.node(k + 1) - sheet.node(k);
        return ab.squaredNorm() > 0.0 ? Vec2(-perp(ab).normalized()) : Vec2(0.0, -1.0);
      });
      const ContactFrame contact = ContactFrame::of_disc(p, d, normal, overlap);
      const Vec2 v_sheet((1.0 - s) * sheet.vx[k] + s * sheet.vx[k + 1], (1.0 - s) * sheet.vy[k] + s * sheet.vy[k + 1]);
      if (!c.counted[q])
        {
          // Switched off by the node rule while it held forces, and not handed over: the energy
          // of its springs as last stored is released, and the dashpot's last force does its
          // second half of work (as when a contact opens in LinearContactLaw).
          c.friction_work[q] = law.elastic_energy(c.elastic_normal_force[q], state.tangential_force);
          c.viscous_work[q] = 0.5 * state.dashpot_force * contact.overlap_rate(v_sheet) * dt;
          if (track_energy)
            {
              work.friction += c.friction_work[q];
              work.viscous += c.viscous_work[q];
            }
          state = ContactState{};
          c.force_x[q] = c.force_y[q] = c.elastic_normal_force[q] = 0.0;
          continue;
        }
      // The sheet point's inverse mass: a force F shared (1 - s, s) accelerates it by
      // ((1 - s)^2 / m_a + s^2 / m_b) F.
      const double sheet_inverse_mass =
        (1.0 - s) * (1.0 - s) * sheet.inverse_mass[k] + s * s * sheet.inverse_mass[k + 1];
      const ContactForce f =
        law.evaluate(contact.kinematics(v_sheet, p.inverse_mass[b] + sheet_inverse_mass, dt), state);
      const Vec2 force = contact.force_on_i(f); // on the disc
      c.force_x[q] = force.x();
      c.force_y[q] = force.y();
      c.elastic_normal_force[q] = state.touching ? f.elastic_normal : 0.0;
      c.friction_work[q] = f.friction_work;
      c.viscous_work[q] = f.viscous_work;
      if (track_energy)
        {
          work.friction += f.friction_work;
          work.viscous += f.viscous_work;
        }
      work.broken_bonds += f.bond_broke;
      p.fx[b] += force.x();
      p.fy[b] += force.y();
      p.torque[b] += cross(contact.lever(), force);
      sheet.fx[k] -= (1.0 - s) * force.x();
      sheet.fy[k] -= (1.0 - s) * force.y();
      sheet.fx[k + 1] -= s * force.x();
      sheet.fy[k + 1] -= s * force.y();
    }
  return work;
}

SheetWallLoad evaluate_sheet_wall_contacts(SparSheet &sheet, const Wall &wall, SheetWallContacts &c, double dt)
{
  const double half_thickness = 0.5 * sheet.thickness();
  SheetWallLoad load;
  for (std::size_t q = 0; q < c.size(); ++q)
    {
      const std::uint32_t k = c.node[q];
      ContactState &state = c.state[q];
      const Vec2 centre = sheet.node(k);
      Vec2 closest;
      const double distance = closest_point_on_segment(centre, wall.start, wall.end, closest);
      const double overlap = half_thickness - distance;
      if (overlap <= 0.0 && !state.bonded && !state.touching)
        {
          c.force_x[q] = c.force_y[q] = c.elastic_normal_force[q] = 0.0;
          c.friction_work[q] = c.viscous_work[q] = 0.0;
          continue;
        }
      const Vec2 normal =
        ContactFrame::normal_towards(centre, closest, distance, [&]() -> Vec2 { return -wall.normal(); });
      const ContactFrame contact = ContactFrame::of_point(Vec2(sheet.vx[k], sheet.vy[k]), normal, overlap);
      const ContactForce f = wall.law.evaluate(contact.kinematics(wall.velocity, sheet.inverse_mass[k], dt), state);
      const Vec2 force = contact.force_on_i(f); // on the node
      c.force_x[q] = force.x();
      c.force_y[q] = force.y();
      c.elastic_normal_force[q] = state.touching ? f.elastic_normal : 0.0;
      c.friction_work[q] = f.friction_work;
      c.viscous_work[q] = f.viscous_work;
      load.work.friction += f.friction_work;
      load.work.viscous += f.viscous_work;
      load.work.broken_bonds += f.bond_broke;
      sheet.fx[k] += force.x();
      sheet.fy[k] += force.y();
      load.force_on_wall -= force;
      load.n_touching += state.touching;
    }
  return load;
}
} // namespace geohybrid::dem
