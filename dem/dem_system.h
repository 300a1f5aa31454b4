#pragma once
// DemSystem: the orchestrator of a 2D DEM simulation. It owns the particles, the walls and the
// contact lists as values, and advances them with the velocity-Verlet scheme (the central
// difference scheme of PFC2D written with full-step velocities):
//
//   v(t + dt/2) = v(t) + dt/2 F(t)/m          (half kick)
//   x(t + dt)   = x(t) + dt v(t + dt/2)       (drift; walls move too)
//   F(t + dt)   = contacts + walls + gravity + local damping, with velocities v(t + dt/2)
//   v(t + dt)   = v(t + dt/2) + dt/2 F(t + dt)/m
//
// The local non-viscous damping of PFC (Cundall 1987) opposes each velocity component with a
// force alpha |F| sign(v); it is meant for quasi-static problems and is zero for dynamics.
// Every loop visits bodies and contacts in a fixed order and each result is written by exactly
// one thread, so a run gives the same numbers, bit for bit, on any number of threads.
//
// Threads: a step is two parallel regions (without sheets). The first is one pass over the
// bodies (half kick, drift, forces restarted from gravity, single centred discs placed, the
// largest move since the last rebuild); each thread owns a fixed contiguous range of bodies.
// Then, serially, the walls move and the lists are rebuilt if needed. The second region is the
// pair loop (one chunk of pairs per thread, PairContacts), the completion of the bodies shared by
// two chunks, the walls (one thread) and the second half kick (the same body ranges). Each
// fork, join or barrier costs microseconds, and on a loaded machine a scheduler slice.
//
// Geosynthetic sheets (spar_sheet.h) are advanced by the same scheme and local damping; their
// physics (axial forces, disc-sheet and node-wall contacts) lives in spar_sheet.* and
// sheet_contacts.*, called from here. A system without sheets runs exactly as before.
#include "contact_law.h"
#include "contact_list.h"
#include "coupling_attachment.h"
#include "particles.h"
#include "sheet_contacts.h"
#include "spar_sheet.h"
#include "wall.h"

#include <string>
#include <vector>

namespace geohybrid::dem
{
struct DemSettings
{
  Vec2 gravity = Vec2(0.0, -9.81);   ///< [m/s^2]
  double local_damping = 0.7;        ///< PFC local damping coefficient alpha [-]
  double time_step = 0.0;            ///< [s]; 0 = safety factor x critical time step
  /// Fraction of the critical time step used when automatic: of the system as it is, set again
  /// whenever a wall, a sheet or an attached coupling's weights change it. 0.8 for the
  /// pull-out, biaxial and calibrate commands; `geohybrid dem` has its own entry (default 0.5).
  double time_step_safety = 0.8;
  double skin = 0.0;                 ///< Verlet skin [m]; 0 = 0.4 x the smallest radius
  int n_threads = 1;
  bool track_energy = true;          ///< accumulate dissipation every step (energy balance)
};

/// The terms of the energy balance [J/m]. Stored energies are values now; the dissipated terms
/// and the boundary work are accumulated since the start.
struct EnergyBudget
{
  double kinetic = 0.0;
  double gravitational = 0.0;        ///< - sum m g . x
  double elastic = 0.0;              ///< energy stored in contact springs
  double friction_dissipated = 0.0;
  double viscous_dissipated = 0.0;   ///< normal dashpots
  double local_damping_dissipated = 0.0;
  double boundary_work = 0.0;        ///< work done on the particles (and sheets) by moving walls and clamps
  double sheet_kinetic = 0.0;        ///< kinetic energy of the sheets' free nodes (inertial mass)
  double sheet_elastic = 0.0;        ///< axial strain energy of the sheets, sum 0.5 (J / l0) (l - l0)^2
  double interface_friction_dissipated = 0.0; ///< slip work at disc-sheet contacts

  /// Total (stored + dissipated - supplied); constant when the balance closes. (Gravitational,
  /// elastic and the other dissipated terms include the sheets' shares: their nodes' weight,
  /// the interface and node-wall contact springs, dashpots and local damping.)
  double total() const
  {
    return kinetic + gravitational + elastic + friction_dissipated + viscous_dissipated +
           local_damping_dissipated - boundary_work + sheet_kinetic + sheet_elastic +
           interface_friction_dissipated;
  }
};

/// Everything a DemSystem needs beyond its construction inputs to continue a run exactly:
/// what a checkpoint stores. Particles and walls are complete (positions, velocities, forces).
struct DemSystemState
{
  ParticleSet particles;
  ContactParameters particle_contact; ///< the particle-particle law in force
  std::vector<Wall> walls;
  PairContacts pairs;
  std::vector<WallContacts> wall_contacts;
  std::vector<Vec2> wall_force_previous;
  SoaVector<double> disc_x_at_rebuild, disc_y_at_rebuild;
  std::vector<Vec2> wall_start_at_rebuild;
  SoaVector<double> damping_fx, damping_fy, damping_torque;
  std::vector<SparSheet> sheets;               ///< complete: nodes, forces, reactions, damping
  std::vector<SheetContacts> sheet_contacts;   ///< with their node positions at the last rebuild
  EnergyBudget accumulated;
  double time_step = 0.0, time = 0.0, skin = 0.0;
  double radius_growth_since_rebuild = 0.0;
  std::uint64_t step_count = 0, n_rebuilds = 0, n_broken_bonds = 0;
  bool rebuild_needed = true;
};

class DemSystem
{
public:
  DemSystem(ParticleSet particles, const LinearContactLaw &particle_law, const DemSettings &settings);

  std::size_t add_wall(const Wall &wall);

  /// Adds a geosynthetic sheet; returns its index. Its nodes start with their weight as force.
  /// Added during a run (e.g. laid while a tank is filled), its energy counts as boundary work.
  /// The sheet's interface stiffness and node dynamics enter the critical time step: an automatic
  /// step is lowered if needed, a step the user chose is re-checked (throws
  /// std::invalid_argument if it is now unstable: raise the sheet's mass scaling, see
  /// SparSheet::required_mass_scaling).
  std::size_t add_sheet(const SparSheet &sheet);

  /// Stable step of the explicit scheme for a dense packing, dt = 2 / omega_max: every disc may
  /// have up to max_contacts_per_disc contacts (6: hexagonal packing of equal discs), each with
  /// the stiffest law of the system (kn, ks). With neighbours moving in opposition, the highest
  /// frequencies are omega^2 = N (kn + ks) / m in translation (the springs of a ring of N
  /// contacts average to N (kn + ks) / 2 in any direction, doubled by the opposing neighbour)
  /// and omega^2 = 2 k_rot / I in rotation, with k_rot the rotational stiffness of 6 contacts
  /// spread evenly round each disc: 6 (ks (r^2 + d^2 / 2) + kn d^2 / 2) per disc of radius r at
  /// a distance d from the centre of mass (for a disc, 6 ks r^2). Checked without damping
  /// (tests/test_dem_time_step.cc): a hexagonal packing of equal discs is stable at the limit and
  /// unstable 10 % above it; a dense packing of two-disc clusters (coordination ~5) made by REDF
  /// is stable at the limit (measured: still at 1.6 x, not at 2 x). A single-contact estimate sqrt(m / k) is
  /// not a bound: the hexagonal packing blows up at 0.7 sqrt(m / kn). Over the free nodes of the
  /// sheets: sqrt(m / (J / l0_left + J / l0_right + k)) (SparSheet::critical_time_step).
  double critical_time_step() const;
  static constexpr double max_contacts_per_disc = 6.0;
  /// Throws std::invalid_argument if dt exceeds the critical time step.
  void set_time_step(double dt);
  double time_step() const { return time_step_; }
  double time() const { return time_; }
  std::uint64_t step_count() const { return step_count_; }

  /// Advances one time step.
  void step();
  void run_steps(std::uint64_t n);

  /// Scales the size of every particle from `first_body` on by `factor` (radius expansion); the
  /// neighbour lists account for the growth of the radii.
  void scale_particle_sizes(double factor, std::size_t first_body = 0);
  double skin() const { return skin_; }

  /// Replaces the particle-particle law (e.g. REDF lowers the friction while growing radii);
  /// contact histories are kept. Throws if the current time step becomes unstable.
  void set_particle_law(const LinearContactLaw &law);

  /// Evaluates the contact forces of the current configuration if not done yet (the first
  /// step() does it otherwise); contacts, wall forces and stresses are then available.
  void initialise_forces();
  /// Whether the forces of the current configuration have been evaluated (initialise_forces() or
  /// a step since the last change that made them stale).
  bool forces_initialised() const { return forces_initialised_; }

  /// Makes every contact that currently touches a bonded contact (used to glue packings).
  void bond_touching_contacts();

  ParticleSet &particles() { return particles_; }
  const ParticleSet &particles() const { return particles_; }
  std::vector<Wall> &walls() { return walls_; }
  const std::vector<Wall> &walls() const { return walls_; }
  const PairContacts &pair_contacts() const { return pairs_; }
  const std::vector<WallContacts> &wall_contacts() const { return wall_contacts_; }
  const LinearContactLaw &particle_law() const { return particle_law_; }
  /// The sheets: nodes may be given velocities (SparSheet::prescribe_velocity) between steps;
  /// moving nodes by hand needs request_neighbour_rebuild().
  std::vector<SparSheet> &sheets() { return sheets_; }
  /// Cuts sheet `s` after its first `n_kept` nodes (SparSheet::keep_first_nodes): the contacts of
  /// the dropped segments and nodes are forgotten, the others keep their state. For a coupling
  /// that hands the sheet's tail to the continuum. Throws std::invalid_argument as
  /// keep_first_nodes, or std::out_of_range for a sheet that does not exist.
  void cut_sheet(std::size_t s, std::size_t n_kept);
  const std::vector<SparSheet> &sheets() const { return sheets_; }
  const std::vector<SheetContacts> &sheet_contacts() const { return sheet_contacts_; }
  /// The stiffest contact a sheet node can meet (the interfaces' and walls' kn and ks) [N/m/m].
  double sheet_contact_stiffness() const;
  /// The mass scaling `sheet` needs so that adding it does not lower the system's critical time
  /// step (SparSheet::required_mass_scaling for the current critical step and the stiffest
  /// contact its nodes can meet, its own interface included). For quasi-static runs.
  double required_sheet_mass_scaling(const SparSheet &sheet) const;
  const DemSettings &settings() const { return settings_; }
  /// Books the energy budget's dissipated terms and boundary work from the next step on (true) or
  /// stops booking them (DemSettings::track_energy): a tank is filled without them, for speed, and
  /// a coupled pull turns them on to close its balance, whose changes then count from here.
  void set_energy_tracking(bool on) { settings_.track_energy = on; }
  /// Local damping coefficient of the sheets' nodes, by default the bodies' (settings). Local
  /// damping opposes a node's velocity with alpha |F|: on a sheet sliding steadily one way through
  /// grains whose contacts fluctuate, it is a drag that does not vanish with the rate (a pull-out
  /// runs better with the sheet undamped: dem/laboratory/pullout_tank.h). Throws unless in [0, 1).
  void set_sheet_local_damping(double alpha);
  /// The particles' local damping from now on (DemSettings::local_damping); a sheet without its
  /// own keeps following it. Throws unless in [0, 1).
  void set_local_damping(double alpha);
  double sheet_local_damping() const { return sheet_local_damping_; }

  /// Attaches a coupling to a continuum (coupling_attachment.h: energy weights, the band's scaled
  /// inertia, constrained bodies, force hooks), read from the next force evaluation on until
  /// detach(); it must stay alive and in place until then. With energy weights, the forces are
  /// evaluated again at the next step, and an automatic time step is set again from the weighted
  /// system (a step the user chose is re-checked: std::invalid_argument, and nothing attached, if
  /// it is now unstable). Throws std::logic_error if one is attached already.
  void attach(CouplingAttachment &coupling);
  /// The system runs uncoupled again (its particles keep the masses the weights gave them).
  void detach();

  /// While on, a touching contact between two bodies that are fixed and at rest, and were so at
  /// its last evaluation too, is not evaluated again: its force cannot change, and stays stored
  /// (carried over list rebuilds). The fixed bodies' resultants then leave those contacts out:
  /// free them in a system whose forces are initialised again (initialise_forces_at_next_step).
  /// A tank's settled lifts while the next one grows are up to two thirds of its contacts
  /// (dem/laboratory/lift_growth.cc).
  void set_skip_contacts_between_fixed_bodies(bool skip) { skip_fixed_contacts_ = skip; }

  /// The next step starts, as the first one does, by evaluating every force at the present
  /// positions (with gravity and the laws now in force) instead of using those of the last step.
  void initialise_forces_at_next_step() { forces_initialised_ = false; }

  /// Forces the next step to rebuild the neighbour lists (after moving particles or walls by hand).
  void request_neighbour_rebuild() { rebuild_needed_ = true; }
  std::uint64_t n_neighbour_rebuilds() const { return n_rebuilds_; }
  std::uint64_t n_broken_bonds() const { return n_broken_bonds_; }

  EnergyBudget energy() const;

  /// The complete state, for checkpoints; restore_state() continues bit for bit.
  DemSystemState export_state() const;
  /// Replaces the state by a saved one. Throws std::invalid_argument if it does not fit this
  /// system (different numbers of bodies, discs or walls, or an unstable time step).
  void restore_state(DemSystemState state);

  /// Number of touching contacts between bodies, with walls, and between discs and sheets.
  std::size_t n_touching_pairs() const;
  std::size_t n_touching_wall_contacts() const;
  std::size_t n_touching_sheet_contacts() const;

private:
  /// The automatic step (DemSettings::time_step 0) set again to the safety factor times
  /// critical_time_step() of the system as it is now; a step the user chose re-checked.
  void update_time_step();
  void kick_and_drift();
  void move_walls();
  void rebuild_if_needed();
  void start_forces_from_gravity();
  /// Pair and wall forces of the new positions (on top of gravity, set by kick_and_drift()),
  /// then the second half kick: one parallel region on several threads (without sheets).
  void compute_forces_and_kick();
  template <bool track_energy, bool with_dashpot, bool weighted>
  void compute_forces_and_kick_for();
  template <bool track_energy, bool with_dashpot, bool weighted, bool checked>
  std::uint64_t pair_range(std::size_t begin, std::size_t end, std::size_t owner_begin);
  void compute_wall_forces();   ///< forces only; book_wall_work() books their energy terms
  void book_wall_work();
  void final_kick(std::size_t begin, std::size_t end); ///< second half kick of bodies [begin, end)
  void check_finite() const;
  // Sheets (called only when there are sheets).
  bool sheet_contacts_stale(double disc_move, double wall_move) const;
  void kick_and_drift_sheets();
  void compute_sheet_forces_and_kick();

  ParticleSet particles_;
  LinearContactLaw particle_law_;
  DemSettings settings_;
  std::vector<Wall> walls_;
  std::vector<WallContacts> wall_contacts_;
  std::vector<Vec2> wall_force_previous_;
  std::vector<double> wall_friction_work_, wall_viscous_work_; ///< of the last evaluation, per wall
  PairContacts pairs_;
  NeighbourSearch neighbour_search_;
  std::vector<SparSheet> sheets_;
  std::vector<SheetContacts> sheet_contacts_;
  SheetContactSearch sheet_contact_search_;

  double time_step_ = 0.0;
  double time_ = 0.0;
  double skin_ = 0.0;
  std::uint64_t step_count_ = 0;
  bool rebuild_needed_ = true;
  bool forces_initialised_ = false;
  bool single_centred_discs_ = false; ///< ParticleSet::single_centred_discs(), checked at rebuilds
  bool skip_fixed_contacts_ = false;  ///< set_skip_contacts_between_fixed_bodies
  /// With skip_fixed_contacts_: per body, the steps (up to 2) it has been fixed and at rest
  /// (counted in kick_and_drift); a contact between two bodies at 2 was evaluated at rest.
  std::vector<std::uint8_t> steps_at_rest_;
  std::uint64_t n_rebuilds_ = 0;
  std::uint64_t n_broken_bonds_ = 0;

  // Positions at the last rebuild, to decide when the Verlet list is stale.
  SoaVector<double> disc_x_at_rebuild_, disc_y_at_rebuild_;
  std::vector<Vec2> wall_start_at_rebuild_;
  double radius_growth_since_rebuild_ = 0.0;
  double max_disc_move_ = 0.0; ///< largest disc displacement since the last rebuild [m]

  // Local damping force of the last evaluation (applied in both half kicks), per body.
  SoaVector<double> damping_fx_, damping_fy_, damping_torque_;
  // Per-body scratch for the energy balance.
  SoaVector<double> body_scratch_;

  EnergyBudget accumulated_; ///< only the dissipated terms and boundary work are used
  double sheet_local_damping_ = -1.0; ///< negative: settings_.local_damping

  CouplingAttachment *coupling_ = nullptr; ///< attach(); nullptr: uncoupled
  /// Whether a coupling with energy weights is attached (the weighted variants of the loops).
  bool weighted() const { return coupling_ && coupling_->energy_weights(); }
  double first_step_ = 0.0; ///< the step initialise_forces() prepares (its own step length is 0)
};

/// Sum of values in a fixed order of fixed-size blocks: the same result for any thread count.
double deterministic_sum(const SoaVector<double> &values, int n_threads);
} // namespace geohybrid::dem
