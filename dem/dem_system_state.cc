// The complete state of a system, for checkpoints: exported as is, restored after checking that
// it fits, so that a resumed run continues bit for bit.
#include "dem_system.h"

#include <stdexcept>
#include <string>

namespace geohybrid::dem
{
DemSystemState DemSystem::export_state() const
{
  DemSystemState s;
  s.particles = particles_;
  s.particle_contact = particle_law_.parameters();
  s.walls = walls_;
  s.pairs = pairs_;
  s.wall_contacts = wall_contacts_;
  s.wall_force_previous = wall_force_previous_;
  s.disc_x_at_rebuild = disc_x_at_rebuild_;
  s.disc_y_at_rebuild = disc_y_at_rebuild_;
  s.wall_start_at_rebuild = wall_start_at_rebuild_;
  s.damping_fx = damping_fx_;
  s.damping_fy = damping_fy_;
  s.damping_torque = damping_torque_;
  s.sheets = sheets_;
  s.sheet_contacts = sheet_contacts_;
  s.accumulated = accumulated_;
  s.time_step = time_step_;
  s.time = time_;
  s.skin = skin_;
  s.radius_growth_since_rebuild = radius_growth_since_rebuild_;
  s.step_count = step_count_;
  s.n_rebuilds = n_rebuilds_;
  s.n_broken_bonds = n_broken_bonds_;
  s.rebuild_needed = rebuild_needed_;
  return s;
}

void DemSystem::restore_state(DemSystemState s)
{
  const auto fail = [](const std::string &what) {
    throw std::invalid_argument("restoring a DEM state: " + what);
  };
  if (s.particles.n_bodies() != particles_.n_bodies() || s.particles.n_discs_total() != particles_.n_discs_total())
    fail("the saved state has " + std::to_string(s.particles.n_bodies()) + " bodies and " +
         std::to_string(s.particles.n_discs_total()) + " discs, this system " +
         std::to_string(particles_.n_bodies()) + " and " + std::to_string(particles_.n_discs_total()));
  if (s.walls.size() != walls_.size() || s.wall_contacts.size() != walls_.size())
    fail("the saved state has " + std::to_string(s.walls.size()) + " walls, this system " +
         std::to_string(walls_.size()));
  const std::size_t nb = particles_.n_bodies(), nd = particles_.n_discs_total();
  if (s.damping_fx.size() != nb || s.damping_fy.size() != nb || s.damping_torque.size() != nb ||
      (!s.rebuild_needed && (s.disc_x_at_rebuild.size() != nd || s.disc_y_at_rebuild.size() != nd)) ||
      s.pairs.state.size() != s.pairs.disc_i.size() || s.pairs.disc_j.size() != s.pairs.disc_i.size())
    fail("inconsistent array sizes");
  // The sheets are stored whole: the saved ones replace those of this system (a sheet laid
  // during the run is restored too).
  if (s.sheet_contacts.size() != s.sheets.size())
    fail("the saved state has " + std::to_string(s.sheets.size()) + " sheets but contact lists for " +
         std::to_string(s.sheet_contacts.size()));
  for (std::size_t k = 0; k < s.sheets.size(); ++k)
    {
      const SheetContacts &c = s.sheet_contacts[k];
      const std::size_t n_nodes = s.sheets[k].n_nodes();
      if ((!s.rebuild_needed && (c.node_x_at_rebuild.size() != n_nodes || c.node_y_at_rebuild.size() != n_nodes ||
                                 c.walls.size() != s.walls.size())) ||
          c.segment.size() != c.disc.size() || c.state.size() != c.disc.size())
        fail("inconsistent array sizes of sheet '" + s.sheets[k].name() + "'");
    }
  particles_ = std::move(s.particles);
  particle_law_ = LinearContactLaw(s.particle_contact);
  walls_ = std::move(s.walls);
  pairs_ = std::move(s.pairs);
  wall_contacts_ = std::move(s.wall_contacts);
  wall_force_previous_ = std::move(s.wall_force_previous);
  disc_x_at_rebuild_ = std::move(s.disc_x_at_rebuild);
  disc_y_at_rebuild_ = std::move(s.disc_y_at_rebuild);
  wall_start_at_rebuild_ = std::move(s.wall_start_at_rebuild);
  damping_fx_ = std::move(s.damping_fx);
  damping_fy_ = std::move(s.damping_fy);
  damping_torque_ = std::move(s.damping_torque);
  sheets_ = std::move(s.sheets);
  sheet_contacts_ = std::move(s.sheet_contacts);
  for (SheetContacts &c : sheet_contacts_)
    if (c.force_x.size() != c.size())
      c.resize_results();
  accumulated_ = s.accumulated;
  skin_ = s.skin;
  radius_growth_since_rebuild_ = s.radius_growth_since_rebuild;
  set_time_step(s.time_step);
  time_ = s.time;
  step_count_ = s.step_count;
  n_rebuilds_ = s.n_rebuilds;
  n_broken_bonds_ = s.n_broken_bonds;
  rebuild_needed_ = s.rebuild_needed;
  forces_initialised_ = s.step_count > 0;
  // The body adjacency is derived from the pair list; result arrays may be absent in a file.
  if (pairs_.force_x.size() != pairs_.size())
    pairs_.resize_results();
  build_body_adjacency(particles_, pairs_, static_cast<std::size_t>(settings_.n_threads));
  body_scratch_.assign(nb, 0.0);
  single_centred_discs_ = particles_.single_centred_discs();
}
} // namespace geohybrid::dem
