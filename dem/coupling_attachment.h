#pragma once
// What a coupling to a continuum attaches to a DemSystem (DemSystem::attach): the bridging
// domain's energy weights, the band's scaled inertia, the bodies whose translation a constraint
// sets, and the hooks through which the coupling adds its forces. coupling/ creates and owns it
// (coupling/coupled_stepper.h); the system only reads it while it is attached. A system without
// one runs the code it always ran: weights and constrained bodies select separate compiled
// variants of its loops, a hook costs one test per step.
#include "energy_weights.h"
#include "particles.h"
#include "soa_vector.h"
#include "spar_sheet.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace geohybrid::dem
{
class DemSystem;

class CouplingAttachment
{
public:
  /// Called once per force evaluation, after every contact, wall and sheet force and before the
  /// second half kick: it may add external forces to the bodies (the coupling's). Its second
  /// argument is the time over which they will act on the bodies' current velocities before the
  /// next drift: the time step, or half of it at the first evaluation (velocities at t = 0).
  /// They count in the unbalanced force but not in the energy budget: the caller books their work.
  using ForceHook = std::function<void(ParticleSet &particles, double impulse_time)>;
  /// Called once per force evaluation, after the sheets' node forces are restarted (weight and
  /// loads) and before their segments', contacts' and damping forces: it may add forces to the
  /// nodes (coupling/sheet_crossing.h), which are at their new positions. Not in the energy budget.
  using SheetForceHook = std::function<void(std::vector<SparSheet> &sheets)>;

  // Before DemSystem::attach (std::logic_error after): these change the particles' masses, from
  // which the system sets its time step when the attachment arrives.

  /// Bridging-domain energy weights (energy_weights.h; Xiao & Belytschko 2004): each body's mass
  /// and inertia are multiplied by its weight, here and once; the attached system weights each
  /// particle-particle contact's force, energy and dissipation by the mean weight along its
  /// branch. Wall and sheet contacts are not weighted (keep walls and sheets out of the band).
  /// Throws std::invalid_argument if the coordinates do not match the bodies, 'band width' is not
  /// positive, or a free body has no weight left (it lies in the continuum-only region: only
  /// fixed bodies, moved by the coupling, may); std::invalid_argument if called twice.
  void set_energy_weights(ParticleSet &particles, EnergyWeights weights);
  /// Density scaling of the band for quasi-static runs: each weighted free body's inertial mass
  /// and moment of inertia (not its weight, which gravity acts on) are raised from its weight to
  /// that of its stiffest possible contact, so that a band particle's contacts, weighted by up to
  /// 4 x its own weight, no longer set a stable step below the unweighted particles' (measured:
  /// 7.9e-6 s against 1.7e-5 s on a pull-out tank). Statics are unchanged; the band's dynamics
  /// are not the weighted ones (for damped runs to rest; DemSystem::energy() counts its kinetic
  /// energy with the scaled masses). Returns the largest factor. Throws std::logic_error without
  /// weights, or if called twice.
  double scale_band_inertia(ParticleSet &particles);
  /// Multiplies the inertial mass and moment of inertia (not the weight) of `bodies` by `factor`
  /// (>= 1), on top of scale_band_inertia's: the tied particles of a multi-rate coupling, which
  /// move with the continuum through its longer step (coupling/coupled_stepper.h). Throws
  /// std::invalid_argument for a factor below 1, an index out of range or a fixed body.
  void scale_inertia(ParticleSet &particles, const std::vector<std::uint32_t> &bodies, double factor);

  // Read at every step: may change while attached.

  /// Bodies whose translation a coupling's constraint sets (coupling/lagrange_tie.h): local
  /// damping leaves their translation alone (the multipliers are solved for the undamped kick; a
  /// damping force added after them would break the constraint) and damps their rotation. Indices
  /// of bodies; an empty list ends the exemption. Throws std::invalid_argument for an index out
  /// of range or a fixed body.
  void set_constrained_bodies(const ParticleSet &particles, const std::vector<std::uint32_t> &bodies);
  void set_force_hook(ForceHook hook) { force_hook_ = std::move(hook); }
  void set_sheet_force_hook(SheetForceHook hook) { sheet_force_hook_ = std::move(hook); }

  // What the system reads.

  /// nullptr without weights.
  const EnergyWeights *energy_weights() const { return weighted_ ? &energy_weights_ : nullptr; }
  bool band_inertia_scaled() const { return !inertia_scale_.empty(); }
  /// Body b's inertial over gravitational mass: 1 unless the band's inertia is scaled.
  double inertia_scale(std::size_t b) const { return inertia_scale_.empty() ? 1.0 : inertia_scale_[b]; }
  /// Per body 1, or 0 if constrained; empty without constrained bodies.
  const SoaVector<double> &damping_scale() const { return damping_scale_; }
  /// The largest weight a particle-particle contact of body b can carry (weights set;
  /// `largest_radius`: the largest disc's).
  double largest_contact_weight(const ParticleSet &particles, std::size_t b, double largest_radius) const;
  const ForceHook &force_hook() const { return force_hook_; }
  const SheetForceHook &sheet_force_hook() const { return sheet_force_hook_; }

private:
  friend class DemSystem; // marks it attached, so that the masses stay those its step was set for
  void refuse_when_attached(const char *what) const;

  EnergyWeights energy_weights_;
  bool weighted_ = false;
  SoaVector<double> inertia_scale_; ///< per body inertial / gravitational mass; empty: none
  SoaVector<double> damping_scale_;
  ForceHook force_hook_;
  SheetForceHook sheet_force_hook_;
  bool attached_ = false;
};
} // namespace geohybrid::dem
