// DemSystem (dem_system.h): construction, the order of one step (step(), initialise_forces()),
// the neighbour lists' rebuild, a coupling attached, and the settings changed between steps. The
// step's parts are beside it, one idea per file: dem_system_time_step.cc (the stable step),
// dem_system_kick_drift.cc (the body loops), dem_system_pair_forces.cc (the pair loop),
// dem_system_walls.cc, dem_system_sheets.cc, dem_system_energy.cc (the energy budget),
// dem_system_state.cc (checkpoint state); a coupling's hooks are coupling_attachment.h's.
#include "dem_system.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
DemSystem::DemSystem(ParticleSet particles, const LinearContactLaw &particle_law, const DemSettings &settings)
  : particles_(std::move(particles)), particle_law_(particle_law), settings_(settings)
{
  if (settings_.n_threads < 1)
    throw std::invalid_argument("DEM settings: 'threads' must be at least 1");
  if (settings_.local_damping < 0.0 || settings_.local_damping >= 1.0)
    throw std::invalid_argument("DEM settings: 'local damping coefficient' must lie in [0, 1)");
  if (!(settings_.time_step_safety > 0.0 && settings_.time_step_safety <= 1.0))
    throw std::invalid_argument("DEM settings: 'time step safety factor' must lie in (0, 1]");
  double r_min = std::numeric_limits<double>::max();
  for (double r : particles_.disc_radius)
    r_min = std::min(r_min, r);
  skin_ = settings_.skin > 0.0 ? settings_.skin : (particles_.n_discs_total() ? 0.4 * r_min : 1e-3);
  // A bond can hold a gap up to a_n / kn; the skin must cover it so no bonded pair leaves the list.
  skin_ = std::max(skin_, 1.05 * particle_law_.max_bonded_gap());
  const std::size_t nb = particles_.n_bodies();
  damping_fx_.assign(nb, 0.0);
  damping_fy_.assign(nb, 0.0);
  damping_torque_.assign(nb, 0.0);
  body_scratch_.assign(nb, 0.0);
  particles_.update_disc_positions();
  single_centred_discs_ = particles_.single_centred_discs();
  if (settings_.time_step <= 0.0 && !std::isfinite(critical_time_step()))
    throw std::invalid_argument("DEM settings: no movable particle to set an automatic time step from; "
                                "give 'time step' explicitly");
  set_time_step(settings_.time_step > 0.0 ? settings_.time_step : settings_.time_step_safety * critical_time_step());
}

void DemSystem::scale_particle_sizes(double factor, std::size_t first_body)
{
  if (!(factor > 0.0))
    throw std::invalid_argument("scale_particle_sizes: the factor must be positive");
  double r_max = 0.0;
  for (double r : particles_.disc_radius)
    r_max = std::max(r_max, r);
  particles_.scale_sizes(factor, first_body);
  radius_growth_since_rebuild_ += std::max(0.0, (factor - 1.0) * r_max);
}

void DemSystem::set_particle_law(const LinearContactLaw &law)
{
  const LinearContactLaw previous = particle_law_;
  particle_law_ = law;
  if (time_step_ > critical_time_step())
    {
      particle_law_ = previous;
      throw std::invalid_argument("the new contact law makes the time step unstable");
    }
  skin_ = std::max(skin_, 1.05 * particle_law_.max_bonded_gap());
}

void DemSystem::set_local_damping(double alpha)
{
  if (!(alpha >= 0.0 && alpha < 1.0))
    throw std::invalid_argument("local damping " + std::to_string(alpha) + " must lie in [0, 1)");
  settings_.local_damping = alpha;
}

void DemSystem::bond_touching_contacts()
{
  initialise_forces(); // the contacts touching now are known only after a force evaluation
  for (ContactState &s : pairs_.state)
    if (s.touching)
      s.bonded = true;
  for (WallContacts &wc : wall_contacts_)
    for (ContactState &s : wc.state)
      if (s.touching)
        s.bonded = true;
  for (SheetContacts &sc : sheet_contacts_)
    {
      for (ContactState &s : sc.state)
        if (s.touching)
          s.bonded = true;
      for (SheetWallContacts &wc : sc.walls)
        for (ContactState &s : wc.state)
          if (s.touching)
            s.bonded = true;
    }
}

void DemSystem::run_steps(std::uint64_t n)
{
  for (std::uint64_t k = 0; k < n; ++k)
    step();
}

void DemSystem::initialise_forces()
{
  if (forces_initialised_)
    return;
  // Forces at t = 0, so that the first half kick sees gravity and initial overlaps.
  // A zero step length keeps the tangential springs and dissipation untouched.
  const double dt = time_step_;
  first_step_ = dt;
  time_step_ = 0.0;
  rebuild_if_needed();
  start_forces_from_gravity();
  compute_forces_and_kick();
  time_step_ = dt;
  forces_initialised_ = true;
}

void DemSystem::attach(CouplingAttachment &coupling)
{
  if (coupling_)
    throw std::logic_error("DEM: a coupling is already attached (detach() it first)");
  coupling_ = &coupling;
  coupling.attached_ = true;
  if (!coupling.energy_weights())
    return;
  forces_initialised_ = false; // the forces of the unweighted contacts are stale
  try
    {
      update_time_step(); // the weighted (and perhaps scaled) masses' critical step
    }
  catch (...)
    {
      detach();
      throw;
    }
}

void DemSystem::detach()
{
  if (coupling_)
    coupling_->attached_ = false;
  coupling_ = nullptr;
}

void DemSystem::step()
{
  initialise_forces();
  kick_and_drift(); // also restarts the bodies' forces from gravity
  if (!sheets_.empty())
    kick_and_drift_sheets();
  move_walls();
  rebuild_if_needed();
  compute_forces_and_kick();
  time_ += time_step_;
  ++step_count_;
  if (step_count_ % 64 == 0)
    check_finite();
}

void DemSystem::rebuild_if_needed()
{
  const ParticleSet &p = particles_;
  if (!rebuild_needed_)
    {
      const double max_move = max_disc_move_; // measured by kick_and_drift()
      double wall_move = 0.0;
      for (std::size_t w = 0; w < walls_.size(); ++w)
        wall_move = std::max(wall_move, (walls_[w].start - wall_start_at_rebuild_[w]).norm());
      // Two discs approach by at most 2 (move + radius growth); a disc and a wall by
      // move + growth + wall move. The skin must cover it.
      const double growth = radius_growth_since_rebuild_;
      rebuild_needed_ = 2.0 * (max_move + growth) > skin_ || max_move + growth + wall_move > skin_;
      if (!rebuild_needed_ && !sheets_.empty())
        rebuild_needed_ = sheet_contacts_stale(max_move + growth, wall_move);
    }
  if (!rebuild_needed_)
    return;
  single_centred_discs_ = p.single_centred_discs();
  neighbour_search_.rebuild_pairs(p, skin_, settings_.n_threads, pairs_, skip_fixed_contacts_);
  for (std::size_t w = 0; w < walls_.size(); ++w)
    neighbour_search_.rebuild_wall(p, walls_[w], skin_, wall_contacts_[w]);
  for (std::size_t s = 0; s < sheets_.size(); ++s)
    sheet_contact_search_.rebuild(p, neighbour_search_, sheets_[s], walls_, skin_, sheet_contacts_[s]);
  disc_x_at_rebuild_ = p.disc_x;
  disc_y_at_rebuild_ = p.disc_y;
  wall_start_at_rebuild_.resize(walls_.size());
  for (std::size_t w = 0; w < walls_.size(); ++w)
    wall_start_at_rebuild_[w] = walls_[w].start;
  rebuild_needed_ = false;
  radius_growth_since_rebuild_ = 0.0;
  ++n_rebuilds_;
}

void DemSystem::check_finite() const
{
  for (const SparSheet &sheet : sheets_)
    for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
      if (!std::isfinite(sheet.x[k]) || !std::isfinite(sheet.y[k]) || !std::isfinite(sheet.vx[k]) ||
          !std::isfinite(sheet.vy[k]))
        {
          std::ostringstream message;
          message << "DEM: node " << k << " of sheet '" << sheet.name()
                  << "' has a non-finite position or velocity at t = " << time_ << " s (step " << step_count_
                  << "); likely causes: a time step above the sheet's stable limit (mass scaling too low) "
                     "or a clamp moving far too fast";
          throw std::runtime_error(message.str());
        }
  const ParticleSet &p = particles_;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (!std::isfinite(p.x[b]) || !std::isfinite(p.y[b]) || !std::isfinite(p.vx[b]) ||
        !std::isfinite(p.vy[b]) || !std::isfinite(p.omega[b]))
      {
        std::ostringstream message;
        message << "DEM: body " << p.body_id[b] << " has a non-finite position or velocity at t = "
                << time_ << " s (step " << step_count_
                << "); likely causes: a time step too close to the stable limit, particles created "
                   "overlapping deeply, or a wall moving through the sample";
        throw std::runtime_error(message.str());
      }
}

std::size_t DemSystem::n_touching_pairs() const
{
  return static_cast<std::size_t>(
    std::count_if(pairs_.state.begin(), pairs_.state.end(), [](const ContactState &s) { return s.touching; }));
}
} // namespace geohybrid::dem
