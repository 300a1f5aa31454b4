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
#include "contact_law.h"
#include "contact_list.h"
#include "particles.h"
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
  double time_step_safety = 0.5;     ///< fraction of the critical time step used when automatic
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
  double boundary_work = 0.0;        ///< work done on the particles by moving walls

  /// Total (stored + dissipated - supplied); constant when the balance closes.
  double total() const
  {
    return kinetic + gravitational + elastic + friction_dissipated + viscous_dissipated +
           local_damping_dissipated - boundary_work;
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

  /// PFC-style estimate of the stable step: the smallest sqrt(m / k) over translation and
  /// sqrt(I / (k_s l^2)) over rotation (l: the body's largest lever arm), with k the largest
  /// stiffness any contact of the system can have.
  double critical_time_step() const;
  /// Throws std::invalid_argument if dt exceeds the critical time step.
  void set_time_step(double dt);
  double time_step() const { return time_step_; }
  double time() const { return time_; }
  std::uint64_t step_count() const { return step_count_; }

  /// Advances one time step.
  void step();
  void run_steps(std::uint64_t n);

  /// Scales every particle's size by `factor` (radius expansion); the neighbour lists account for
  /// the growth of the radii.
  void scale_particle_sizes(double factor);
  double skin() const { return skin_; }

  /// Replaces the particle-particle law (e.g. REDF lowers the friction while growing radii);
  /// contact histories are kept. Throws if the current time step becomes unstable.
  void set_particle_law(const LinearContactLaw &law);

  /// Evaluates the contact forces of the current configuration if not done yet (the first
  /// step() does it otherwise); contacts, wall forces and stresses are then available.
  void initialise_forces();

  /// Makes every contact that currently touches a bonded contact (used to glue packings).
  void bond_touching_contacts();

  ParticleSet &particles() { return particles_; }
  const ParticleSet &particles() const { return particles_; }
  std::vector<Wall> &walls() { return walls_; }
  const std::vector<Wall> &walls() const { return walls_; }
  const PairContacts &pair_contacts() const { return pairs_; }
  const std::vector<WallContacts> &wall_contacts() const { return wall_contacts_; }
  const LinearContactLaw &particle_law() const { return particle_law_; }
  const DemSettings &settings() const { return settings_; }

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

  /// Number of touching contacts between bodies, and with walls.
  std::size_t n_touching_pairs() const;
  std::size_t n_touching_wall_contacts() const;

private:
  void kick_and_drift();
  void move_walls();
  void rebuild_if_needed();
  void compute_pair_forces();
  void compute_wall_forces();
  void gather_forces_and_kick();
  void check_finite() const;

  ParticleSet particles_;
  LinearContactLaw particle_law_;
  DemSettings settings_;
  std::vector<Wall> walls_;
  std::vector<WallContacts> wall_contacts_;
  std::vector<Vec2> wall_force_previous_;
  PairContacts pairs_;
  NeighbourSearch neighbour_search_;

  double time_step_ = 0.0;
  double time_ = 0.0;
  double skin_ = 0.0;
  std::uint64_t step_count_ = 0;
  bool rebuild_needed_ = true;
  bool forces_initialised_ = false;
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
};

/// Sum of values in a fixed order of fixed-size blocks: the same result for any thread count.
double deterministic_sum(const SoaVector<double> &values, int n_threads);
} // namespace geohybrid::dem
