#pragma once
// A rigid straight wall: a segment from `start` to `end` whose active side is on its left
// (the unit normal perp(end - start) points into the granular sample). A wall has its own
// contact law, moves at a prescribed velocity or is servo-controlled to a target normal stress,
// and reports the force the particles exert on it.
#include "contact_law.h"

#include <string>

namespace geohybrid::dem
{
enum class WallControl
{
  prescribed_velocity, ///< moves at `velocity`
  servo_stress         ///< moves along its normal so that its normal stress tends to target_stress
};

struct WallServo
{
  double target_stress = 0.0;  ///< compressive normal stress to hold [Pa]
  /// Fraction of the stress error removed per step (PFC's alpha), against the contacts' force
  /// change per unit speed over a step, N kn dt, plus their dashpots' c if the wall has some.
  double relaxation    = 0.5;
  double max_speed     = 1.0;  ///< cap on the servo speed [m/s]
  /// Integral action: fraction of the accumulated error fed back per step. A purely
  /// proportional servo lags a wall that must keep moving (a dilating sample) by a constant
  /// error; the integral removes it. 0 = PFC's proportional servo.
  double integral_gain = 0.01;
  double integral      = 0.0;  ///< accumulated stress error (state) [Pa]
};

struct Wall
{
  std::string name;
  Vec2 start, end;
  LinearContactLaw law;
  WallControl control = WallControl::prescribed_velocity;
  Vec2 velocity = Vec2::Zero(); ///< current velocity (prescribed, or set by the servo) [m/s]
  WallServo servo;
  /// Length over which the wall's normal force is spread to give its stress; 0 = the segment's
  /// own length. Walls of a box overhang its corners, so their loaded length is the box side.
  double loaded_length = 0.0;
  /// Whether the nodes of sheets touch this wall (sheet_contacts.h). False for the two walls
  /// whose gap is the slot a sheet leaves a tank through: the slot guides the grains, while the
  /// sheet, held at the slot's level by its clamp, slides through it without catching on its
  /// edges (a gap narrower than the grains leaves a sheet almost no room).
  bool touches_sheets = true;

  // Reported after each step.
  Vec2 force_from_particles = Vec2::Zero(); ///< resultant force the particles apply [N/m]
  std::size_t n_contacts = 0;

  Wall(std::string name_, const Vec2 &start_, const Vec2 &end_, const LinearContactLaw &law_)
    : name(std::move(name_)), start(start_), end(end_), law(law_) {}

  double length() const { return (end - start).norm(); }
  Vec2 normal() const { return perp(end - start).normalized(); }
  /// Compressive normal stress on the wall: normal force from the particles over its loaded
  /// length [Pa].
  double normal_stress() const { return -force_from_particles.dot(normal()) / stress_length(); }
  /// The length the normal force is spread over [m].
  double stress_length() const { return loaded_length > 0.0 ? loaded_length : length(); }
  void translate(const Vec2 &d) { start += d; end += d; }
};
} // namespace geohybrid::dem
