#pragma once
// Conventions used everywhere in geohybrid's DEM, stated once.
//
// - 2D, plane strain, per metre of thickness. Forces are N/m, stiffnesses N/m/m, masses kg/m,
//   moments of inertia kg m^2/m, stresses Pa, energies J/m. SI units inside the code.
// - Angles and rotations are about +z (counter-clockwise positive).
// - For a contact between disc i and disc j, the unit normal n points from i to j; the tangent is
//   t = perp(n) = (-n_y, n_x). The overlap is positive in penetration.
// - A contact's normal force Fn is positive in compression; its tangential force Ft is the
//   component along t of the force acting on i. The force on i is  -Fn n + Ft t, on j the opposite.
// - A wall is the "j" side of a disc-wall contact: n points from the disc centre to the wall.
// - A body is a rigid particle: one disc or a cluster of discs. Dynamics (position, velocity,
//   rotation) live on bodies; contact detection lives on discs.
#include <Eigen/Core>
#include <cmath>

namespace geohybrid::dem
{
using Vec2 = Eigen::Vector2d;

/// z-component of the cross product a x b.
inline double cross(const Vec2 &a, const Vec2 &b) { return a.x() * b.y() - a.y() * b.x(); }

/// a rotated by +90 degrees: the tangent of a contact with normal a.
inline Vec2 perp(const Vec2 &a) { return Vec2(-a.y(), a.x()); }

/// omega (about +z) cross r: the velocity of a point at lever r on a body spinning at omega.
inline Vec2 spin_velocity(double omega, const Vec2 &r) { return Vec2(-omega * r.y(), omega * r.x()); }

constexpr double pi = 3.14159265358979323846;
inline double degrees_to_radians(double degrees) { return degrees * pi / 180.0; }
} // namespace geohybrid::dem
