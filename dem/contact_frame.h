#pragma once
// One builder of a contact's kinematics for every kind of contact of the DEM: disc-disc pairs
// (DemSystem's pair loop), disc-wall, disc-sheet (sheet_contacts.h) and a sheet node on a wall.
// Each kind measures its own geometry, the overlap and the unit normal n from side i to side j
// (conventions.h), and hands them to ContactFrame. The frame gives the rest: the contact point on
// a disc, its lever from the body's centre, the velocity there, the ContactKinematics the law
// reads (relative velocity v_j - v_i along n and t) and the force on side i, -Fn n + Ft t.
//
// All of it is inline, with no virtual call and no allocation. The pair loop, the hot one, calls
// the frame's arithmetic (point_on_disc, body_velocity_at, kinematics, force_on_i) on its own
// locals: gcc 12 left a frame object there on the stack, 2 % more instructions in the loop. The
// arithmetic is the loops' own, term for term: results are pinned bit for bit.
#include "contact_law.h"
#include "particles.h"

#include <cstdint>

namespace geohybrid::dem
{
class ContactFrame
{
public:
  /// Side i is disc `disc` of a rigid body. The contact point is on the disc's radius along n,
  /// half the overlap inside its surface, and moves with the body (translation and spin).
  static ContactFrame of_disc(const ParticleSet &p, std::uint32_t disc, const Vec2 &unit_normal, double overlap)
  {
    const std::uint32_t body = p.disc_body[disc];
    const Vec2 point = point_on_disc(p, disc, unit_normal, overlap);
    const Vec2 lever = point - Vec2(p.x[body], p.y[body]);
    return ContactFrame(unit_normal, overlap, lever, body_velocity_at(p, body, lever));
  }

  /// Side i is a point mass (a sheet node) moving at `velocity`: the force acts at the node.
  static ContactFrame of_point(const Vec2 &velocity, const Vec2 &unit_normal, double overlap)
  {
    return ContactFrame(unit_normal, overlap, Vec2::Zero(), velocity);
  }

  /// The unit normal from `centre` towards the closest point of side j, at `distance` from it;
  /// `fallback()` (side j's own normal, negated) when the centre lies on side j and has no
  /// direction to it. For walls and sheets; a disc-disc pair has the inverse distance at hand.
  template <class Fallback>
  static Vec2 normal_towards(const Vec2 &centre, const Vec2 &closest, double distance, const Fallback &fallback)
  {
    return distance > 0.0 ? Vec2((closest - centre) / distance) : Vec2(fallback());
  }

  // ---- the arithmetic, on its own: the pair loop calls these on its locals, which gcc keeps in
  // registers (a frame object there cost 2 % more instructions in the loop) -----------------------
  /// The contact point on disc `disc`: on its radius along n, half the overlap inside its surface.
  static Vec2 point_on_disc(const ParticleSet &p, std::uint32_t disc, const Vec2 &unit_normal, double overlap)
  {
    return Vec2(p.disc_x[disc], p.disc_y[disc]) + (p.disc_radius[disc] - 0.5 * overlap) * unit_normal;
  }
  /// What LinearContactLaw::evaluate reads, for `relative_velocity` = v_j - v_i at the contact point.
  static ContactKinematics kinematics(const Vec2 &normal, const Vec2 &tangent, double overlap,
                                      const Vec2 &relative_velocity, double inverse_mass_sum, double dt)
  {
    return {overlap, -relative_velocity.dot(normal), relative_velocity.dot(tangent) * dt, inverse_mass_sum, dt};
  }
  /// The force on side i: -Fn n + Ft t (side j gets the opposite) [N/m].
  static Vec2 force_on_i(const Vec2 &normal, const Vec2 &tangent, const ContactForce &f)
  {
    return -f.normal_force * normal + f.tangential_force * tangent;
  }
  /// The velocity of the point at `lever` from the centre of body b: v_b + omega_b x lever.
  static Vec2 body_velocity_at(const ParticleSet &p, std::uint32_t body, const Vec2 &lever)
  {
    return Vec2(p.vx[body], p.vy[body]) + spin_velocity(p.omega[body], lever);
  }

  Vec2 normal() const { return Vec2(normal_x_, normal_y_); }    ///< unit, from side i towards side j
  Vec2 tangent() const { return perp(normal()); }               ///< perp(normal)
  double overlap() const { return overlap_; }                   ///< > 0 in penetration [m]
  /// From the centre of side i's body to the contact point (zero for a node) [m].
  Vec2 lever() const { return Vec2(lever_x_, lever_y_); }
  Vec2 velocity() const { return Vec2(velocity_x_, velocity_y_); } ///< of side i at the contact point [m/s]

  /// What LinearContactLaw::evaluate reads, side j moving at `velocity_j` at the contact point.
  /// `inverse_mass_sum`: 1 / the effective mass (1/m_i + 1/m_j; 1/m_i against a wall).
  ContactKinematics kinematics(const Vec2 &velocity_j, double inverse_mass_sum, double dt) const
  {
    const Vec2 relative_velocity = velocity_j - velocity();
    return kinematics(normal(), tangent(), overlap_, relative_velocity, inverse_mass_sum, dt);
  }
  /// d(overlap)/dt, side j moving at `velocity_j` [m/s].
  double overlap_rate(const Vec2 &velocity_j) const
  {
    const Vec2 relative_velocity = velocity_j - velocity();
    return -relative_velocity.dot(normal());
  }

  /// The force on side i: -Fn n + Ft t (side j gets the opposite) [N/m].
  Vec2 force_on_i(const ContactForce &f) const { return force_on_i(normal(), tangent(), f); }

  /// The same frame for another overlap (the interface wall's contact point stays on the surface
  /// of a disc still apart, while its law reads the true gap).
  ContactFrame with_overlap(double overlap) const
  {
    ContactFrame frame = *this;
    frame.overlap_ = overlap;
    return frame;
  }

private:
  // Plain doubles: gcc 12 keeps a struct of Eigen vectors on the stack.
  ContactFrame(const Vec2 &normal, double overlap, const Vec2 &lever, const Vec2 &velocity)
    : normal_x_(normal.x()), normal_y_(normal.y()), overlap_(overlap), lever_x_(lever.x()), lever_y_(lever.y())
    , velocity_x_(velocity.x()), velocity_y_(velocity.y())
  {}

  double normal_x_, normal_y_, overlap_, lever_x_, lever_y_, velocity_x_, velocity_y_;
};
} // namespace geohybrid::dem
