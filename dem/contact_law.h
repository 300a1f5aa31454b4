#pragma once
// The linear contact law of PFC2D as used in the reference paper (section 4.1):
// linear normal and shear springs (kn, ks, per metre of thickness), an elastic-perfectly plastic
// Coulomb slider (Cundall & Strack 1979) whose limit carries the contact shear strength a_s while
// the contact is bonded, a tensile strength a_n, and an optional normal dashpot set from a
// restitution coefficient e (damping ratio zeta = -ln e / sqrt(pi^2 + ln^2 e), the linear
// oscillator's). Without an intact bond the total normal force is never tensile: the dashpot is
// clipped where it would pull, so a rebound ends when the force reaches zero, before the overlap
// does, and its restitution is e exp(2 zeta asin(zeta) / sqrt(1 - zeta^2)) (0.550 for e = 0.5,
// 0.902 for 0.9, 0.325 for 0.2; tests/test_dem_impacts.cc) rather than e. One law serves
// disc-disc and disc-wall contacts (a wall is a body of infinite mass) and disc-sheet contacts
// (sheet_contacts.h). Sign conventions: see conventions.h.
#include "conventions.h"

#include <string>

namespace geohybrid::dem
{
/// What the user gives: the micro-parameters of Table 5 of the reference paper.
struct ContactParameters
{
  double normal_stiffness      = 7.0e7;  ///< kn [N/m/m]
  double shear_stiffness       = 3.5e7;  ///< ks [N/m/m]
  double friction_angle_deg    = 10.0;   ///< delta [deg]
  double shear_strength        = 0.0;    ///< a_s, carried while bonded [N/m]
  double tensile_strength      = 0.0;    ///< a_n, carried while bonded [N/m]
  double restitution           = 1.0;    ///< sets the normal dashpot (see above), 1 = none [-]
  /// Whether a contact starts bonded when it forms (if a_s > 0 or a_n > 0), i.e. a cementing
  /// soil. Off by default, as PFC's contact bonds: bonds are installed on the contacts touching at
  /// a chosen moment (DemSystem::bond_touching_contacts), break when a strength is exceeded, and
  /// stay broken. With it on, a pair that separates and touches again bonds anew.
  bool   bond_new_contacts     = false;

  /// Throws std::invalid_argument naming `where` and the offending parameter.
  void validate(const std::string &where) const;
};

/// History of one contact, kept across neighbour-list rebuilds.
struct ContactState
{
  double tangential_force = 0.0; ///< Ft along t, on the "i" side [N/m]
  bool   bonded           = false;
  bool   touching         = false; ///< overlap > 0 (or held by a bond) at the last evaluation
  double dashpot_force    = 0.0;   ///< dashpot part of Fn at the last evaluation (energy balance) [N/m]
};

/// The kinematics the law needs, measured by the caller in the contact frame.
struct ContactKinematics
{
  double overlap;                  ///< r_i + r_j - distance (> 0 in penetration) [m]
  double overlap_rate;             ///< d(overlap)/dt [m/s]
  double tangential_displacement;  ///< (v_cj - v_ci).t * dt this step [m]
  double inverse_mass_sum;         ///< 1/m_i + 1/m_j, or 1/m_i against a wall: 1 / effective mass [m/kg]
  double time_step;                ///< dt [s]
};

/// Forces of one evaluation, plus the energy it dissipated (for the energy balance).
struct ContactForce
{
  double normal_force     = 0.0; ///< Fn, positive in compression, dashpot included [N/m]
  double elastic_normal   = 0.0; ///< kn * overlap, without dashpot [N/m]
  double tangential_force = 0.0; ///< Ft on i along t [N/m]
  double friction_work    = 0.0; ///< energy dissipated by slip this step [J/m]
  double viscous_work     = 0.0; ///< energy dissipated by the dashpot this step [J/m]
  bool   bond_broke       = false;
};

/// The law with its derived constants computed once. evaluate() is the only hot function.
class LinearContactLaw
{
public:
  LinearContactLaw() : LinearContactLaw(ContactParameters{}) {}
  explicit LinearContactLaw(const ContactParameters &parameters);

  const ContactParameters &parameters() const { return parameters_; }
  double normal_stiffness() const { return parameters_.normal_stiffness; }
  double shear_stiffness() const { return parameters_.shear_stiffness; }
  double friction_coefficient() const { return friction_coefficient_; }
  /// Damping ratio of the normal dashpot, zeta = -ln e / sqrt(pi^2 + ln^2 e).
  double damping_ratio() const { return damping_ratio_; }
  /// Largest tensile gap a bond can hold, a_n / kn [m].
  double max_bonded_gap() const { return parameters_.tensile_strength / parameters_.normal_stiffness; }

  /// Advances one contact by one step: updates `state` and returns the forces.
  /// A contact with overlap <= 0 that is not bonded carries no force and loses its history.
  /// `with_dashpot = false` is for a law known to have none (has_dashpot() false): the same
  /// numbers, bit for bit, with the dashpot's arithmetic compiled out of a hot loop.
  template <bool with_dashpot = true>
  inline ContactForce evaluate(const ContactKinematics &k, ContactState &state) const;
  bool has_dashpot() const { return damping_ratio_ > 0.0; }

  /// Elastic energy stored in a contact with elastic normal force fn and tangential force ft.
  double elastic_energy(double fn, double ft) const
  {
    return 0.5 * fn * fn / parameters_.normal_stiffness + 0.5 * ft * ft / parameters_.shear_stiffness;
  }

private:
  ContactParameters parameters_;
  double friction_coefficient_;
  double damping_ratio_;
  bool   bonding_enabled_;
};

template <bool with_dashpot>
inline ContactForce LinearContactLaw::evaluate(const ContactKinematics &k, ContactState &state) const
{
  ContactForce f;
  const double kn = parameters_.normal_stiffness;
  const double ks = parameters_.shear_stiffness;

  if (k.overlap <= 0.0 && !state.bonded)
    {
      // Separated: the spring energy left in the tangential spring is released (counted as
      // friction work so that the energy balance closes), and the history is forgotten.
      if (state.touching)
        f.friction_work = 0.5 * state.tangential_force * state.tangential_force / ks;
      f.viscous_work         = 0.5 * state.dashpot_force * k.overlap_rate * k.time_step;
      state.dashpot_force    = 0.0;
      state.tangential_force = 0.0;
      state.touching         = false;
      return f;
    }

  if (!state.touching && !state.bonded && bonding_enabled_)
    state.bonded = true; // a contact that just formed starts bonded
  state.touching = true;

  // Normal: linear spring, tension only through an intact bond.
  f.elastic_normal = kn * k.overlap;
  if (state.bonded && -f.elastic_normal > parameters_.tensile_strength)
    {
      state.bonded  = false;
      f.bond_broke  = true;
      if (k.overlap <= 0.0)
        {
          f.friction_work        = elastic_energy(f.elastic_normal, state.tangential_force);
          f.viscous_work         = 0.5 * state.dashpot_force * k.overlap_rate * k.time_step;
          state.dashpot_force    = 0.0;
          state.tangential_force = 0.0;
          state.touching         = false;
          f.elastic_normal       = 0.0;
          return f;
        }
    }
  // Dashpot 2 zeta sqrt(m* kn) (d overlap / dt), m* = 1 / inverse_mass_sum; the square root is
  // only taken when there is a dashpot (the inner loop of a run without one skips it).
  double dashpot = (with_dashpot && damping_ratio_ > 0.0 && k.inverse_mass_sum > 0.0)
                     ? 2.0 * damping_ratio_ * std::sqrt(kn / k.inverse_mass_sum) * k.overlap_rate
                     : 0.0;
  // Without a bond the soil carries no tension: at the end of a rebound the dashpot may unload
  // the spring to zero but not pull (PFC's no-tension dashpot). The force applied is the one
  // booked below. (An unbonded touching contact has overlap > 0: elastic_normal > 0.)
  if (with_dashpot && !state.bonded)
    dashpot = std::max(dashpot, -f.elastic_normal);
  f.normal_force       = f.elastic_normal + dashpot;
  // The integrator applies this force in the half kicks on either side of v(t), so its work is
  // dashpot * rate(t) * dt with rate(t) the mean of the half-step rates: book half now (with
  // this step's rate) and half at the next evaluation (trapezoidal, as the walls' work).
  f.viscous_work       = 0.5 * (state.dashpot_force + dashpot) * k.overlap_rate * k.time_step;
  state.dashpot_force  = dashpot;

  // Tangential: incremental spring, capped by the Mohr-Coulomb limit a_s + Fn tan(delta).
  const double trial = state.tangential_force + ks * k.tangential_displacement;
  const double frictional_limit = friction_coefficient_ * std::max(f.elastic_normal, 0.0);
  double limit = frictional_limit + (state.bonded ? parameters_.shear_strength : 0.0);
  if (std::abs(trial) > limit && state.bonded)
    {
      state.bonded = false; // shear failure of the bond: pure friction from now on
      f.bond_broke = true;
      limit        = frictional_limit;
      // The spring energy above the friction limit is released at once (with the slip work
      // below: 0.5 (trial^2 - limit^2) / ks in all).
      f.friction_work = 0.5 * (std::abs(trial) - limit) * (std::abs(trial) - limit) / ks;
    }
  if (std::abs(trial) > limit)
    {
      const double capped = std::copysign(limit, trial);
      f.friction_work    += limit * (std::abs(trial) - limit) / ks;
      state.tangential_force = capped;
    }
  else
    state.tangential_force = trial;
  f.tangential_force = state.tangential_force;
  return f;
}
} // namespace geohybrid::dem
