#pragma once
// The coupled DEM-FEM stepper: one DemSystem and one explicit continuum advanced in lockstep at
// one time step, the smaller of the two stable steps (and of the penalty springs' bound), tied in
// the overlap band by the method the input chose (coupling_method.h).
//
// Both integrators are the same leapfrog (central differences): the continuum's velocities live at
// half steps, the DEM's velocity Verlet is the same scheme written with full-step velocities. One
// coupled step n -> n+1 is:
//   1. the continuum steps (its forces at t_n include the coupling's force at t_n);
//   2. the DEM steps: half kick, drift to x_{n+1}, contact forces at t_{n+1}; then, through its
//      force hook and before its second half kick, the coupling's forces at t_{n+1} are computed
//      from both sides at t_{n+1} (the continuum is already there) and added to the particles'
//      forces and to the continuum's external force, which its next step applies.
// Methods 1 and 2 (an overlap band): set-up applies the energy weights to both sides (Xiao & Belytschko 2004), gathers the band's
// particles (tied, and driven past the band: band_particles.h), and evaluates the forces at t = 0
// with the coupling. Before the DEM steps, the driven particles are given the velocity that takes
// them to the continuum's new displacement.
// Method 3 (the non-overlapping interface, interface_wall.h) has no band, no weights and no driven
// particles: the force hook evaluates the disc-edge contacts at t_{n+1}, both sides being there.
//
// Multi-rate (method 1 only; MultiRate): the continuum's stable step is tens of the particles'
// (its cells are larger, its wave speed alike), so it may take one step of `ratio` particle steps
// (a window): it steps at a window's start to the window's end, and the particles then step
// `ratio` times with the tied ones held at its (constant) half-step velocity (stepped, so, at the
// window's length: their inertia is raised by (window / particles' stable step)^2 where the
// window is longer, tied_inertia_factor()), the driven ones
// moved along its displacement, linear in time over the window. The multipliers at a window's
// start pass the continuum the impulse the tied particles are predicted to pass over the window
// (LagrangeTie::apply_window_start); the driven particles' forces reach it averaged over the
// window, one window late. Both sides are at one time only between windows (window_phase() == 0):
// diagnostics() and checkpoints are meant for those times. Ratio 1 is the lockstep above, bit for bit.
//
// Gravity and damping (quasi-static runs, the geostatic column): both sides keep their own
// gravity (on the weighted masses: the band's weight is counted once) and their own damping. With
// the multipliers (method 1), the tied particles and the nodes they interpolate from are exempt
// from damping (dem::CouplingAttachment::set_constrained_bodies,
// ExplicitSolver::set_undamped_dofs): the multipliers make their half-step velocities equal for
// the undamped update, and a damping force added afterwards would open a velocity gap every step.
// They are damped through the rest of both models (their rotation, which no constraint sets, stays
// damped). Penalty springs and interface contacts are forces like the others: damped everywhere.
// Limits (checked, std::invalid_argument): one MPI rank; set up before the continuum steps (the
// particles may have run before).
// The diagnostics' total() is the conserved energy of an undamped run without body force: the
// continuum elastic energy 1/2 u . f_int assumes a linear elastic soil without initial stress,
// body force or loads on the continuum. With gravity, damping, plasticity or an initial stress
// (a pull-out), ledger_total() is the one that stays constant: the particles' budget (stored +
// dissipated - supplied by walls and clamps) plus the continuum's work ledger (internal work +
// damping work - gravity and load work: fem::ExplicitEnergyLedger; with its full-step kinetic
// energy continuum_kinetic, at the particles' time; with a sheet crossing into the continuum, its
// part there: fem::SheetEnergyLedger) plus the coupling's stored energy. The coupling forces' work is left out on both sides (the particles'
// budget does not book it, the ledger keeps it apart as added_force_work): being equal and
// opposite, it cancels but for the coupling's stored energy and the two integrators' O(dt^2)
// difference; energy_balance_error() measures what is left.
#include "coupling/band_particles.h"
#include "coupling/coupling_method.h"
#include "coupling/coupling_tie.h"
#include "coupling/sheet_crossing.h"
#include "dem/coupling_attachment.h"
#include "dem/dem_system.h"
#include "fem/explicit_solver.h"

#include <array>
#include <optional>
#include <variant>
#include <vector>

namespace geohybrid::coupling
{
/// Energies [J/m] and the coupling's force balance [N/m] at the current time.
struct CouplingDiagnostics
{
  double particle_energy = 0.0;    ///< DemSystem::energy().total() (weighted masses and contacts)
  double particle_kinetic = 0.0;   ///< its kinetic part
  double continuum_kinetic = 0.0;  ///< 1/2 v_n . M v_n, v_n the full-step velocity
  double continuum_elastic = 0.0;  ///< 1/2 u . f_int (weighted)
  double coupling_energy = 0.0;    ///< penalty springs; interface contacts' springs and their dissipation; 0 for the multipliers
  double total() const { return particle_energy + continuum_kinetic + continuum_elastic + coupling_energy; }
  CouplingForceSums forces;        ///< the last coupling forces on each side
  dem::EnergyBudget particle_budget;        ///< the particles' terms (particle_energy is its total())
  fem::ExplicitEnergyLedger continuum_ledger; ///< the continuum's work since its first step
  /// The continuum's embedded sheet's (a sheet crossing into the continuum); zero without one.
  fem::SheetEnergyLedger continuum_sheet_ledger;
  /// Constant when the coupled system's energy balance closes (see above) [J/m]. The sheet's
  /// load work is the crossing's force on the continuum's part: a coupling force, left out as
  /// the continuum's added_force_work is (the crossing's stored energy is in coupling_energy).
  double ledger_total() const
  {
    const fem::ExplicitEnergyLedger &c = continuum_ledger;
    const fem::SheetEnergyLedger &s = continuum_sheet_ledger;
    return particle_energy + continuum_kinetic + c.internal_work + c.damping_work - c.gravity_work - c.load_work +
           s.kinetic + s.truss_work + s.interface_work + s.damping_work - s.clamp_work + coupling_energy;
  }
};

/// The balance's error between two diagnostics of one run: the change of ledger_total() over the
/// largest change of the terms it sums (Abaqus's measure of an explicit run's energy balance:
/// against the largest of the work supplied, the energy stored and the energy dissipated; the
/// particles' gravitational, elastic and kinetic energies, their dissipation and boundary work,
/// the continuum's internal, gravity, load and damping work and the work passed to it through the
/// coupling) [-]. Zero when nothing changed.
double energy_balance_error(const CouplingDiagnostics &start, const CouplingDiagnostics &now);

/// Where the coupled steps' wall time went, summed over the steps since the stepper was made (or
/// since reset_step_times()) [s]: issue 26's "per part of a coupled step". `particles` is the
/// DEM's step without the coupling forces it asks for through its hook (`coupling`: the ties or
/// multipliers, the interface contacts, the sheet crossing); `band_drive` the driven particles'
/// velocities set from the continuum before the particles step.
struct CoupledStepTimes
{
  double continuum = 0.0, band_drive = 0.0, particles = 0.0, coupling = 0.0;
  double total() const { return continuum + band_drive + particles + coupling; }
};

/// How the band's particles are treated (methods 1 and 2).
struct BandTreatment
{
  /// The band's particles lighter than this are driven by the continuum, not tied to it
  /// (OverlapBand::driven_from; 0: only those past the band) [-].
  double driven_below_weight = 0.0;
  /// Quasi-static runs only: the band's inertia scaled so that its light particles do not lower
  /// the stable step (dem::CouplingAttachment::scale_band_inertia; statics unchanged, the band's
  /// dynamics not the weighted ones).
  bool scale_inertia = false;
};

/// The continuum's step as a number of particle steps (multi-rate stepping, method 1 only).
struct MultiRate
{
  /// 1: both at one step; 0: automatic, the largest stable ratio up to largest_automatic_ratio [-].
  unsigned int continuum_step_ratio = 1;
  /// The automatic ratio's cap. The tied grains' inertia grows as the ratio squared: at 4 (x 16)
  /// the largest tank's mean tension fell 7-8 % below lockstep's, at 2 (x 4) it was lockstep's
  /// (VALIDATION.md 6.4), for 1-4 % more cost, since the particles keep their step.
  static constexpr unsigned int largest_automatic_ratio = 2;
};

class CoupledStepper
{
public:
  /// Ties `particles` and `continuum` (both must outlive the stepper, which must not move: it owns
  /// the dem::CouplingAttachment the particles are attached to, and detaches them when destroyed).
  /// Throws std::invalid_argument as described above, or from the band (no particle in it, a
  /// particle outside the mesh, a particle in the continuum-only region).
  /// Methods 1 and 2 (`method` must not be an InterfaceCoupling: that one has no band).
  /// `treatment`: which of the band's particles are driven, and whether its inertia is scaled.
  /// `rate`: the continuum's step; a ratio above 1 needs method 1 and a continuum stable at ratio
  /// particle steps (std::invalid_argument otherwise, naming 'continuum step ratio').
  CoupledStepper(dem::DemSystem &particles, fem::ExplicitSolver &continuum, const OverlapBand &band,
                 const CouplingMethod &method, const BandTreatment &treatment = {}, const MultiRate &rate = {});
  /// Method 3: the particles touch the continuum's boundary `method.boundary_id` (no overlap).
  /// Throws std::invalid_argument as above, or from InterfaceWall.
  CoupledStepper(dem::DemSystem &particles, fem::ExplicitSolver &continuum, const InterfaceCoupling &method);
  CoupledStepper(const CoupledStepper &) = delete;
  CoupledStepper &operator=(const CoupledStepper &) = delete;
  ~CoupledStepper();

  void step();
  void run_steps(unsigned int n);
  double time_step() const { return time_step_; } ///< the particles' [s]
  /// The continuum's clock at the particles' time (within a window the continuum is at its end).
  double time() const
  {
    return phase_ == 0 ? continuum_.time() : continuum_.time() - (ratio_ - phase_) * time_step_;
  }
  /// The continuum's step over the particles' (1 in lockstep).
  unsigned int continuum_step_ratio() const { return ratio_; }
  /// Multi-rate: the factor the tied particles' inertia was raised by (1: none was needed).
  double tied_inertia_factor() const { return tied_inertia_factor_; }
  /// Particle steps taken in the present window (0: both sides at time()).
  unsigned int window_phase() const { return phase_; }
  /// A resumed run's window_phase() (saved with the same set-up). Throws std::invalid_argument
  /// if it does not fit the ratio.
  void restore_window_phase(unsigned int phase);

  /// The sheet as one chain across both models (sheet_crossing.h): DEM sheet `dem_sheet_index`,
  /// whose last node lies in the particles' core, is joined to the continuum's sheet
  /// (ExplicitSolver::attach_sheet, its node 0 the next of the chain) by a segment of rest length
  /// `rest_length` [m], evaluated from now on at every force evaluation of the particles. Its
  /// forces at the current time are applied at once (the next half kick and continuum step use
  /// them). Throws std::invalid_argument if the continuum has no sheet, or from SheetCrossing;
  /// std::logic_error if called twice.
  void cross_sheet(std::size_t dem_sheet_index, double rest_length);
  /// nullptr unless cross_sheet() was called.
  const SheetCrossing *sheet_crossing() const { return crossing_ ? &*crossing_ : nullptr; }

  /// Methods 1 and 2; throws std::logic_error for method 3 (no band).
  const BandParticles &band_particles() const;
  /// Method 3's interface; nullptr for methods 1 and 2.
  const InterfaceWall *interface_wall() const { return std::get_if<InterfaceWall>(&tie_); }
  CouplingDiagnostics diagnostics() const;
  /// The last coupling forces' sums on each side (what diagnostics() reports, without its energies).
  const CouplingForceSums &coupling_forces() const { return forces_; }
  /// Method 1: the velocity gap left by the last correction (round-off) [m/s]; 0 for method 2.
  double largest_velocity_gap() const;

  const CoupledStepTimes &step_times() const { return times_; }
  /// From zero again (or from `earlier`, a resumed run's times so far).
  void reset_step_times(const CoupledStepTimes &earlier = {}) { times_ = earlier; }

private:
  void apply_coupling(dem::ParticleSet &particles, double impulse_time);
  /// Methods 1 and 2: the driven particles' contact forces passed to the continuum's nodes.
  void pass_driven_forces(const dem::ParticleSet &particles);
  /// What both constructors end with: the particles attached, then start_attached(): the common
  /// time step, the hook, the forces at t = 0.
  void start(unsigned int requested_ratio = 1);
  /// Multi-rate: sets ratio_ (0: automatic), throws if the continuum cannot take it; returns the
  /// particles' step.
  double choose_ratio(unsigned int requested_ratio);
  /// Multi-rate: the particles' stable step with the band as it is (no margin for its scaled inertia).
  double particle_stable_step() const;
  /// `multi_rate_step`: the particles' step when ratio_ > 1.
  void start_attached(double multi_rate_step);
  /// The multi-rate step (ratio_ > 1).
  void step_in_window();

  dem::DemSystem &particles_;
  fem::ExplicitSolver &continuum_;
  /// The weights, the band's inertia, the tied bodies and the hooks: the particles read them while
  /// the stepper lives. Made before band_, which needs the weighted masses.
  dem::CouplingAttachment attachment_;
  // Methods 1 and 2 only: method 3 has no band, and every step that only the band needs (the
  // weights, the driven particles) tests band_.
  std::optional<OverlapBand> band_geometry_;
  std::optional<BandParticles> band_;
  CouplingTie tie_; ///< the band's ties read band_: declared after it
  CouplingForceSums forces_;
  std::optional<SheetCrossing> crossing_;
  std::vector<Vec2> driven_tied_displacement_; ///< u(X) of each driven particle when tied [m]
  double time_step_ = 0.0;
  unsigned int ratio_ = 1, phase_ = 0;
  double tied_inertia_factor_ = 1.0; ///< multi-rate: the tied particles' inertia raised by this
  bool hook_starts_window_ = true; ///< multi-rate: whether the next coupling evaluation is a window's start
  CoupledStepTimes times_;
  /// The fraction of the estimated stable step lockstep takes with the band's inertia scaled.
  static constexpr double scaled_band_step_fraction = 0.8;
};
} // namespace geohybrid::coupling
