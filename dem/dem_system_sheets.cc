// Geosynthetic sheets in the system: adding and cutting one, their stiffness for the time step,
// and their part of a step (kick and drift, axial and disc-sheet forces, damping). Their physics
// is in spar_sheet.* and sheet_contacts.*.
#include "dem_system.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
std::size_t DemSystem::add_sheet(const SparSheet &sheet)
{
  sheets_.push_back(sheet);
  sheet_contacts_.emplace_back();
  if (settings_.time_step > 0.0 && time_step_ > critical_time_step())
    {
      // A step the user chose that the sheet cannot follow: refuse the sheet, keep the system.
      std::string message;
      try
        {
          set_time_step(time_step_);
        }
      catch (const std::invalid_argument &e)
        {
          message = e.what();
        }
      sheets_.pop_back();
      sheet_contacts_.pop_back();
      throw std::invalid_argument("sheet '" + sheet.name() + "': " + message);
    }
  update_time_step();
  SparSheet &added = sheets_.back();
  added.start_forces(settings_.gravity); // the first half kick sees the weight
  skin_ = std::max(skin_, 1.05 * added.interface_law().max_bonded_gap());
  rebuild_needed_ = true;
  // A sheet laid during a run brings its energy with it: booked as work supplied, so that the
  // energy balance stays continuous.
  if (forces_initialised_ && settings_.track_energy)
    accumulated_.boundary_work += added.kinetic_energy() + added.elastic_energy() +
                                  added.gravitational_energy(settings_.gravity);
  return sheets_.size() - 1;
}

double DemSystem::sheet_contact_stiffness() const
{
  double k = 0.0;
  for (const SparSheet &sheet : sheets_)
    k = std::max({k, sheet.interface_law().normal_stiffness(), sheet.interface_law().shear_stiffness()});
  for (const Wall &w : walls_)
    k = std::max({k, w.law.normal_stiffness(), w.law.shear_stiffness()});
  return k;
}

double DemSystem::required_sheet_mass_scaling(const SparSheet &sheet) const
{
  const double contact_stiffness = std::max({sheet_contact_stiffness(), sheet.interface_law().normal_stiffness(),
                                             sheet.interface_law().shear_stiffness()});
  const double dt = critical_time_step();
  if (!std::isfinite(dt))
    throw std::invalid_argument("sheet '" + sheet.name() + "': no movable particle sets a time step to scale "
                                "the sheet's masses to");
  return sheet.required_mass_scaling(dt, contact_stiffness);
}

bool DemSystem::sheet_contacts_stale(double disc_move, double wall_move) const
{
  // A point of a segment moves at most as far as the farther of its two nodes, so a disc and a
  // segment approach by at most disc_move + node_move, a node and a wall by node_move + wall_move.
  for (std::size_t s = 0; s < sheets_.size(); ++s)
    {
      const double node_move = largest_node_move(sheets_[s], sheet_contacts_[s]);
      if (disc_move + node_move > skin_ || node_move + wall_move > skin_)
        return true;
    }
  return false;
}

namespace
{
/// Keeps the entries of the equally long arrays `arrays` where keep[q] is true, in order.
template <typename... Arrays>
void keep_entries(const std::vector<bool> &keep, Arrays &...arrays)
{
  const auto filter = [&keep](auto &array) {
    std::size_t kept = 0;
    for (std::size_t q = 0; q < keep.size(); ++q)
      if (keep[q])
        array[kept++] = array[q];
    array.resize(kept);
  };
  (filter(arrays), ...);
}
} // namespace

void DemSystem::cut_sheet(std::size_t s, std::size_t n_kept)
{
  SparSheet &sheet = sheets_.at(s);
  sheet.keep_first_nodes(n_kept);
  SheetContacts &c = sheet_contacts_.at(s);
  std::vector<bool> keep(c.size());
  for (std::size_t q = 0; q < c.size(); ++q)
    keep[q] = c.segment[q] + 1 < n_kept;
  keep_entries(keep, c.disc, c.segment, c.state);
  c.resize_results();
  for (SheetWallContacts &w : c.walls)
    {
      std::vector<bool> keep_node(w.size());
      for (std::size_t q = 0; q < w.size(); ++q)
        keep_node[q] = w.node[q] < n_kept;
      keep_entries(keep_node, w.node, w.state);
      w.resize_results();
    }
  c.node_x_at_rebuild.resize(n_kept);
  c.node_y_at_rebuild.resize(n_kept);
  request_neighbour_rebuild();
}

void DemSystem::kick_and_drift_sheets()
{
  for (SparSheet &sheet : sheets_)
    {
      const SparSheet::StepWork work = sheet.kick_and_drift(time_step_);
      if (settings_.track_energy)
        {
          accumulated_.local_damping_dissipated -= work.damping;
          accumulated_.boundary_work += work.boundary;
        }
    }
}

void DemSystem::compute_sheet_forces_and_kick()
{
  const double dt = time_step_;
  const bool book = settings_.track_energy && dt > 0.0;
  for (std::size_t s = 0; s < sheets_.size(); ++s)
    {
      SparSheet &sheet = sheets_[s];
      sheet.add_axial_forces();
      const SheetContactWork work = evaluate_sheet_contacts(particles_, sheet, sheet_contacts_[s], dt, book);
      n_broken_bonds_ += work.broken_bonds;
      const SparSheet::StepWork step = sheet.damp_and_kick(
        dt, sheet_local_damping_ >= 0.0 ? sheet_local_damping_ : settings_.local_damping, settings_.gravity);
      if (book)
        {
          accumulated_.interface_friction_dissipated += work.friction;
          accumulated_.viscous_dissipated += work.viscous;
          accumulated_.local_damping_dissipated -= step.damping;
          accumulated_.boundary_work += step.boundary;
        }
    }
}

std::size_t DemSystem::n_touching_sheet_contacts() const
{
  std::size_t n = 0;
  for (const SheetContacts &c : sheet_contacts_)
    n += static_cast<std::size_t>(
      std::count_if(c.state.begin(), c.state.end(), [](const ContactState &s) { return s.touching; }));
  return n;
}

void DemSystem::set_sheet_local_damping(double alpha)
{
  if (!(alpha >= 0.0 && alpha < 1.0))
    throw std::invalid_argument("sheet local damping " + std::to_string(alpha) + " must lie in [0, 1)");
  sheet_local_damping_ = alpha;
}
} // namespace geohybrid::dem
