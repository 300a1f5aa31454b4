#include "dem_system.h"

#include "contact_frame.h"

#include <omp.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace geohybrid::dem
{
double deterministic_sum(const SoaVector<double> &values, int n_threads)
{
  // At most 64 blocks whose size depends only on the number of values, never on the threads:
  // the partial sums and their order are the same on any number of threads, and the partial
  // sums live on the stack (no allocation in the step loop).
  constexpr std::size_t max_blocks = 64, min_block = 4096;
  const std::size_t n = values.size();
  const std::size_t block = std::max(min_block, (n + max_blocks - 1) / max_blocks);
  const std::size_t n_blocks = (n + block - 1) / block;
  double partial[max_blocks];
#pragma omp parallel for schedule(static) num_threads(n_threads) if (n_blocks > 1)
  for (std::size_t k = 0; k < n_blocks; ++k)
    {
      double s = 0.0;
      const std::size_t end = std::min(n, (k + 1) * block);
      for (std::size_t q = k * block; q < end; ++q)
        s += values[q];
      partial[k] = s;
    }
  double total = 0.0;
  for (std::size_t k = 0; k < n_blocks; ++k)
    total += partial[k];
  return total;
}

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

std::size_t DemSystem::add_wall(const Wall &wall)
{
  if ((wall.end - wall.start).norm() <= 0.0)
    throw std::invalid_argument("wall '" + wall.name + "': start and end points coincide");
  walls_.push_back(wall);
  wall_contacts_.emplace_back();
  wall_force_previous_.push_back(Vec2::Zero());
  wall_friction_work_.push_back(0.0);
  wall_viscous_work_.push_back(0.0);
  skin_ = std::max(skin_, 1.05 * wall.law.max_bonded_gap());
  rebuild_needed_ = true;
  // A stiffer wall lowers the stable step: the automatic step follows it, a step the user chose is
  // re-checked (throws if it is now unstable).
  update_time_step();
  return walls_.size() - 1;
}

void DemSystem::update_time_step()
{
  // One definition: the automatic step is the safety factor times the critical step of the
  // system as it is now (walls, sheets, weights included), never of an earlier one; a step fixed
  // when the particles alone were known and kept while it stayed below the new limit gave 0.84 of
  // the critical step for the 0.5 asked on a scene of stiffer walls.
  set_time_step(settings_.time_step > 0.0 ? time_step_ : settings_.time_step_safety * critical_time_step());
}

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

namespace
{
double largest_disc_radius(const ParticleSet &p)
{
  double largest = 0.0;
  for (const double r : p.disc_radius)
    largest = std::max(largest, r);
  return largest;
}
} // namespace

double DemSystem::critical_time_step() const
{
  // The stiffest law any contact of the system can have.
  double kn_max = particle_law_.normal_stiffness(), ks_max = particle_law_.shear_stiffness();
  for (const Wall &w : walls_)
    {
      kn_max = std::max(kn_max, w.law.normal_stiffness());
      ks_max = std::max(ks_max, w.law.shear_stiffness());
    }
  for (const SparSheet &sheet : sheets_)
    {
      const LinearContactLaw &law = sheet.interface_law();
      kn_max = std::max(kn_max, law.normal_stiffness());
      ks_max = std::max(ks_max, law.shear_stiffness());
    }
  const ParticleSet &p = particles_;
  const double largest_radius = weighted_ ? largest_disc_radius(p) : 0.0;
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      if (p.inverse_mass[b] == 0.0)
        continue;
      const double n_contacts = max_contacts_per_disc * p.n_discs[b];
      // Rotational stiffness of the contacts about the centre of mass, for contacts spread evenly
      // round each disc (d: the disc's offset from the centre of mass, r its radius): the shear
      // spring acts at a lever r + d cos(theta), the normal spring at d sin(theta), whose squares
      // average to r^2 + d^2 / 2 and d^2 / 2.
      double rotational_stiffness = 0.0;
      for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
        {
          const double offset2 = p.disc_offset_x[d] * p.disc_offset_x[d] + p.disc_offset_y[d] * p.disc_offset_y[d];
          const double radius2 = p.disc_radius[d] * p.disc_radius[d];
          rotational_stiffness +=
            max_contacts_per_disc * (ks_max * (radius2 + 0.5 * offset2) + kn_max * 0.5 * offset2);
        }
      // With energy weights the mass is already weighted (and perhaps scaled: scale_band_inertia);
      // the contacts' springs are weighted by at most largest_contact_weight.
      const double stiffness_weight = weighted_ ? largest_contact_weight(b, largest_radius) : 1.0;
      const double omega2_translation = stiffness_weight * n_contacts * (kn_max + ks_max) * p.inverse_mass[b];
      const double omega2_rotation = stiffness_weight * 2.0 * rotational_stiffness * p.inverse_inertia[b];
      dt = std::min(dt, 2.0 / std::sqrt(std::max(omega2_translation, omega2_rotation)));
    }
  if (!sheets_.empty())
    {
      const double contact_stiffness = sheet_contact_stiffness();
      for (const SparSheet &sheet : sheets_)
        dt = std::min(dt, sheet.critical_time_step(contact_stiffness));
    }
  return dt;
}

void DemSystem::set_time_step(double dt)
{
  const double dt_crit = critical_time_step();
  if (!(dt > 0.0) || dt > dt_crit)
    {
      std::ostringstream message;
      message << "time step " << dt << " s is above the stable limit " << dt_crit
              << " s (the bound for a dense packing of these particles and stiffnesses, see "
                 "DemSystem::critical_time_step"
              << (sheets_.empty() ? "" : ", and sqrt(m_node / (2 J / l0 + k)) for the sheet nodes: "
                                         "raise the sheet's mass scaling")
              << "); lower 'time step' or leave it 0 for automatic";
      throw std::invalid_argument(message.str());
    }
  time_step_ = dt;
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

void DemSystem::set_energy_weights(EnergyWeights weights)
{
  const std::string where = "DEM energy weights: ";
  if (weighted_)
    throw std::invalid_argument(where + "the weights are already set");
  if (!(weights.band_width > 0.0) || !std::isfinite(weights.band_width))
    throw std::invalid_argument(where + "parameter 'band width' = " + std::to_string(weights.band_width) +
                                " m must be positive");
  ParticleSet &p = particles_;
  if (weights.body_band_coordinate.size() != p.n_bodies())
    throw std::invalid_argument(where + std::to_string(weights.body_band_coordinate.size()) +
                                " band coordinates for " + std::to_string(p.n_bodies()) + " bodies");
  // A body in the continuum-only region has no mass left; it may only be a fixed body (one the
  // coupling moves with the continuum, whose contacts with the band's bodies still carry weight).
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (!(weights.body_weight(b) > 0.0) && p.inverse_mass[b] != 0.0)
      throw std::invalid_argument(where + "body " + std::to_string(p.body_id[b]) +
                                  " lies in the continuum-only region (band coordinate " +
                                  std::to_string(weights.body_band_coordinate[b]) + " m >= band width " +
                                  std::to_string(weights.band_width) + " m) and is free: it has no energy to carry");
  // The particles' share of the kinetic energy (and of gravity, which acts on the mass).
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      const double weight = weights.body_weight(b);
      p.mass[b] *= weight;
      p.inertia[b] *= weight;
      if (p.inverse_mass[b] != 0.0)
        {
          p.inverse_mass[b] /= weight;
          p.inverse_inertia[b] /= weight;
        }
    }
  energy_weights_ = std::move(weights);
  weighted_ = true;
  forces_initialised_ = false; // the forces of the unweighted contacts are stale
  update_time_step();
}

double DemSystem::largest_contact_weight(std::size_t b, double largest_radius) const
{
  // The weight at the far end of the longest branch: twice the largest disc radius beyond the
  // body's farthest disc.
  const ParticleSet &p = particles_;
  double reach = 0.0;
  for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
    reach = std::max(reach, std::hypot(p.disc_offset_x[d], p.disc_offset_y[d]) + 2.0 * largest_radius);
  return energy_weights_.largest_contact_weight(b, reach);
}

double DemSystem::scale_band_inertia()
{
  if (!weighted_)
    throw std::logic_error("DEM: scale_band_inertia needs the energy weights (set_energy_weights)");
  if (!inertia_scale_.empty())
    throw std::logic_error("DEM: the band's inertia is already scaled");
  ParticleSet &p = particles_;
  inertia_scale_.assign(p.n_bodies(), 1.0);
  const double largest_radius = largest_disc_radius(p);
  double largest = 1.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (p.inverse_mass[b] != 0.0)
      {
        const double factor = std::max(1.0, largest_contact_weight(b, largest_radius) / energy_weights_.body_weight(b));
        inertia_scale_[b] = factor;
        p.inverse_mass[b] /= factor;
        p.inverse_inertia[b] /= factor;
        largest = std::max(largest, factor);
      }
  update_time_step();
  return largest;
}

void DemSystem::set_constrained_bodies(const std::vector<std::uint32_t> &bodies)
{
  ParticleSet &p = particles_;
  const std::size_t nb = p.n_bodies();
  if (bodies.empty())
    damping_scale_ = SoaVector<double>();
  else
    {
      SoaVector<double> scale;
      scale.assign(nb, 1.0);
      for (const std::uint32_t b : bodies)
        {
          if (b >= nb)
            throw std::invalid_argument("DEM: constrained body index " + std::to_string(b) + " is out of range (" +
                                        std::to_string(nb) + " bodies)");
          if (p.inverse_mass[b] == 0.0)
            throw std::invalid_argument("DEM: constrained body " + std::to_string(p.body_id[b]) + " is fixed");
          scale[b] = 0.0;
        }
      damping_scale_ = std::move(scale);
    }
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

namespace
{
/// The bodies of the calling thread in every body loop of a step: a fixed split of [0, nb) into
/// one contiguous range per thread of the team (all of it outside a parallel region).
std::pair<std::size_t, std::size_t> thread_bodies(std::size_t nb)
{
  const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
  const std::size_t n = static_cast<std::size_t>(omp_get_num_threads());
  return {nb * t / n, nb * (t + 1) / n};
}

/// What the body loops of a step read besides the particles.
struct BodyLoopInput
{
  double dt = 0.0, alpha = 0.0, gx = 0.0, gy = 0.0;
  double *damping_fx = nullptr, *damping_fy = nullptr, *damping_torque = nullptr, *scratch = nullptr;
  const double *damping_scale = nullptr; ///< per body 1 or 0 (set_constrained_bodies), or none
  const double *reference_x = nullptr, *reference_y = nullptr; ///< disc positions at the last rebuild
};

/// Bodies [begin, end) of the first half of a step: half kick, drift, the forces restarted from
/// gravity (+ 0.0 turns a -0.0 into +0.0: see compute_forces_and_kick_for), and the discs placed
/// (here for single centred discs, `discs` 1, or 2 to measure their move too; after the body
/// loop for clusters, `discs` 0). With local damping (`damped`), the damping force of the last
/// evaluation enters the kick, and with `book` its work goes to the scratch array. Every value
/// is computed by the same expression whatever the range: each body gets the same bits on any
/// number of threads (vectorised or not, IEEE operations on one body are the same). Returns the
/// largest squared disc move from the reference positions (0 without them).
template <bool damped, bool book, int discs>
double kick_and_drift_range(ParticleSet &p, const BodyLoopInput &in, std::size_t begin, std::size_t end)
{
  double *const x = p.x.data(), *const y = p.y.data(), *const rotation = p.rotation.data();
  double *const vx = p.vx.data(), *const vy = p.vy.data(), *const omega = p.omega.data();
  double *const fx = p.fx.data(), *const fy = p.fy.data(), *const torque = p.torque.data();
  const double *const mass = p.mass.data(), *const inverse_mass = p.inverse_mass.data(),
                      *const inverse_inertia = p.inverse_inertia.data();
  double *const disc_x = p.disc_x.data(), *const disc_y = p.disc_y.data();
  const double *const damping_fx = in.damping_fx, *const damping_fy = in.damping_fy,
                      *const damping_torque = in.damping_torque;
  double *const scratch = in.scratch;
  const double *const reference_x = in.reference_x, *const reference_y = in.reference_y;
  const double dt = in.dt, half = 0.5 * dt, gx = in.gx, gy = in.gy;
  double max_move2 = 0.0;
#pragma omp simd reduction(max : max_move2)
  for (std::size_t b = begin; b < end; ++b)
    {
      if constexpr (damped)
        {
          const double vx0 = vx[b], vy0 = vy[b], w0 = omega[b];
          vx[b] += half * (fx[b] + damping_fx[b]) * inverse_mass[b];
          vy[b] += half * (fy[b] + damping_fy[b]) * inverse_mass[b];
          omega[b] += half * (torque[b] + damping_torque[b]) * inverse_inertia[b];
          if constexpr (book) // work of the damping force during this half kick (exact for a constant force)
            scratch[b] = 0.5 * half *
                         (damping_fx[b] * (vx0 + vx[b]) + damping_fy[b] * (vy0 + vy[b]) +
                          damping_torque[b] * (w0 + omega[b]));
        }
      else
        {
          // No local damping: damping_* are zero (adding them would change no bit), so this
          // loop does not stream them.
          vx[b] += half * (fx[b] + 0.0) * inverse_mass[b];
          vy[b] += half * (fy[b] + 0.0) * inverse_mass[b];
          omega[b] += half * (torque[b] + 0.0) * inverse_inertia[b];
        }
      x[b] += dt * vx[b];
      y[b] += dt * vy[b];
      rotation[b] += dt * omega[b];
      fx[b] = mass[b] * gx + 0.0;
      fy[b] = mass[b] * gy + 0.0;
      torque[b] = 0.0;
      if constexpr (discs > 0)
        {
          disc_x[b] = x[b];
          disc_y[b] = y[b];
          if constexpr (discs == 2)
            {
              const double dx = x[b] - reference_x[b], dy = y[b] - reference_y[b];
              max_move2 = std::max(max_move2, dx * dx + dy * dy);
            }
        }
    }
  if constexpr (discs == 0)
    for (std::size_t b = begin; b < end; ++b)
      {
        // A fixed body at rest (a tank's settled lift while the next one grows: up to two thirds
        // of the bodies) has not moved: its discs stand where they were placed, and turning its
        // rotation into cos and sin again would give the same bits at the price of a sincos.
        const bool at_rest = inverse_mass[b] == 0.0 && vx[b] == 0.0 && vy[b] == 0.0 && omega[b] == 0.0;
        max_move2 = std::max(max_move2, at_rest ? p.disc_move2(b, reference_x, reference_y)
                                                : p.place_discs(b, reference_x, reference_y));
      }
  return max_move2;
}

/// Bodies [begin, end) of the second half kick, with the forces of the new positions, and the
/// local damping force of this evaluation (`damped`; its work to the scratch array with `book`).
template <bool damped, bool book, bool exempt = false>
void final_kick_range(ParticleSet &p, const BodyLoopInput &in, std::size_t begin, std::size_t end)
{
  const double *const damping_scale = in.damping_scale;
  double *const vx = p.vx.data(), *const vy = p.vy.data(), *const omega = p.omega.data();
  const double *const fx = p.fx.data(), *const fy = p.fy.data(), *const torque = p.torque.data();
  const double *const inverse_mass = p.inverse_mass.data(), *const inverse_inertia = p.inverse_inertia.data();
  double *const damping_fx = in.damping_fx, *const damping_fy = in.damping_fy,
                *const damping_torque = in.damping_torque, *const scratch = in.scratch;
  const double half = 0.5 * in.dt, alpha = in.alpha;
  if constexpr (!damped)
    {
      // No local damping (dynamics): the plain second half kick; damping_* stay zero.
#pragma omp simd
      for (std::size_t b = begin; b < end; ++b)
        {
          vx[b] += half * fx[b] * inverse_mass[b];
          vy[b] += half * fy[b] * inverse_mass[b];
          omega[b] += half * torque[b] * inverse_inertia[b];
        }
    }
  else
    {
      // -alpha |F| sign(v), with sign(0) = 0
      const auto damping = [alpha](double force, double velocity) {
        return -alpha * std::abs(force) * static_cast<double>((velocity > 0.0) - (velocity < 0.0));
      };
#pragma omp simd
      for (std::size_t b = begin; b < end; ++b)
        {
          // A fixed body keeps its velocity and has no damping force; nor has an exempt one.
          const bool fixed = inverse_mass[b] == 0.0;
          double dfx = fixed ? 0.0 : damping(fx[b], vx[b]);
          double dfy = fixed ? 0.0 : damping(fy[b], vy[b]);
          double dt = fixed ? 0.0 : damping(torque[b], omega[b]);
          if constexpr (exempt) // the translation of a constrained body (its rotation is free: damped)
            {
              dfx *= damping_scale[b];
              dfy *= damping_scale[b];
            }
          damping_fx[b] = dfx;
          damping_fy[b] = dfy;
          damping_torque[b] = dt;
          const double vx0 = vx[b], vy0 = vy[b], w0 = omega[b];
          const double vx1 = fixed ? vx0 : vx0 + half * (fx[b] + dfx) * inverse_mass[b];
          const double vy1 = fixed ? vy0 : vy0 + half * (fy[b] + dfy) * inverse_mass[b];
          const double w1 = fixed ? w0 : w0 + half * (torque[b] + dt) * inverse_inertia[b];
          vx[b] = vx1;
          vy[b] = vy1;
          omega[b] = w1;
          if constexpr (book)
            scratch[b] = fixed ? 0.0 : 0.5 * half * (dfx * (vx0 + vx1) + dfy * (vy0 + vy1) + dt * (w0 + w1));
        }
    }
}
} // namespace

void DemSystem::start_forces_from_gravity()
{
  ParticleSet &p = particles_;
  const std::size_t nb = p.n_bodies();
  const double gx = settings_.gravity.x(), gy = settings_.gravity.y();
  // + 0.0 turns a -0.0 into +0.0 (see compute_forces_and_kick_for).
  for (std::size_t b = 0; b < nb; ++b)
    {
      p.fx[b] = p.mass[b] * gx + 0.0;
      p.fy[b] = p.mass[b] * gy + 0.0;
      p.torque[b] = 0.0;
    }
}

void DemSystem::kick_and_drift()
{
  ParticleSet &p = particles_;
  const std::size_t nb = p.n_bodies(), nd = p.n_discs_total();
  const bool damped = settings_.local_damping > 0.0;
  const bool book_damping = settings_.track_energy && damped;
  // The largest disc move since the last neighbour-list rebuild is measured in the same pass.
  const bool measure = !rebuild_needed_ && disc_x_at_rebuild_.size() == nd && disc_y_at_rebuild_.size() == nd;
  BodyLoopInput in;
  in.dt = time_step_;
  in.gx = settings_.gravity.x();
  in.gy = settings_.gravity.y();
  in.damping_fx = damping_fx_.data();
  in.damping_fy = damping_fy_.data();
  in.damping_torque = damping_torque_.data();
  in.scratch = body_scratch_.data();
  in.reference_x = measure ? disc_x_at_rebuild_.data() : nullptr;
  in.reference_y = measure ? disc_y_at_rebuild_.data() : nullptr;
  // Single centred discs are placed in the body loop, clusters (rotated offsets) after it, by
  // the same thread for the same bodies: one parallel region, no barrier inside.
  using Range = double (*)(ParticleSet &, const BodyLoopInput &, std::size_t, std::size_t);
  const int discs = single_centred_discs_ ? (measure ? 2 : 1) : 0;
  static constexpr Range undamped[3] = {kick_and_drift_range<false, false, 0>, kick_and_drift_range<false, false, 1>,
                                        kick_and_drift_range<false, false, 2>};
  static constexpr Range damped_unbooked[3] = {kick_and_drift_range<true, false, 0>,
                                               kick_and_drift_range<true, false, 1>,
                                               kick_and_drift_range<true, false, 2>};
  static constexpr Range damped_booked[3] = {kick_and_drift_range<true, true, 0>, kick_and_drift_range<true, true, 1>,
                                             kick_and_drift_range<true, true, 2>};
  const Range range = (!damped ? undamped : book_damping ? damped_booked : damped_unbooked)[discs];
  double max_move2 = 0.0;
  const int n_threads = settings_.n_threads;
#pragma omp parallel num_threads(n_threads) if (n_threads > 1) reduction(max : max_move2)
  {
    const auto [begin, end] = thread_bodies(nb);
    max_move2 = range(p, in, begin, end);
  }
  if (book_damping)
    accumulated_.local_damping_dissipated -= deterministic_sum(body_scratch_, settings_.n_threads);
  max_disc_move_ = std::sqrt(max_move2);
  if (skip_fixed_contacts_)
    {
      steps_at_rest_.resize(nb, 0);
      for (std::size_t b = 0; b < nb; ++b)
        {
          const bool at_rest = p.inverse_mass[b] == 0.0 && p.vx[b] == 0.0 && p.vy[b] == 0.0 && p.omega[b] == 0.0;
          steps_at_rest_[b] = at_rest ? static_cast<std::uint8_t>(std::min(steps_at_rest_[b] + 1, 2)) : 0;
        }
    }
}

void DemSystem::final_kick(std::size_t begin, std::size_t end)
{
  BodyLoopInput in;
  in.dt = time_step_;
  in.alpha = settings_.local_damping;
  in.damping_fx = damping_fx_.data();
  in.damping_fy = damping_fy_.data();
  in.damping_torque = damping_torque_.data();
  in.scratch = body_scratch_.data();
  in.damping_scale = damping_scale_.data();
  if (in.alpha == 0.0)
    final_kick_range<false, false>(particles_, in, begin, end);
  else if (!damping_scale_.empty())
    {
      if (settings_.track_energy)
        final_kick_range<true, true, true>(particles_, in, begin, end);
      else
        final_kick_range<true, false, true>(particles_, in, begin, end);
    }
  else if (settings_.track_energy)
    final_kick_range<true, true>(particles_, in, begin, end);
  else
    final_kick_range<true, false>(particles_, in, begin, end);
}

void DemSystem::move_walls()
{
  const double dt = time_step_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    {
      Wall &wall = walls_[w];
      if (wall.control == WallControl::servo_stress)
        {
          // PFC's servo: retreat by the distance that would remove a fraction `relaxation` of the
          // stress error, given the contacts' stiffness: v = alpha (sigma - sigma_0) L / (N kn dt),
          // plus an integral term so that a steadily moving wall holds its stress without lag.
          WallServo &servo = wall.servo;
          const double error = wall.normal_stress() - servo.target_stress;
          const double n_contacts = std::max<double>(1.0, static_cast<double>(wall.n_contacts));
          const double kn = wall.law.normal_stiffness();
          double resistance = n_contacts * kn * dt; // the contacts' force change per unit speed over a step
          if (wall.law.has_dashpot() && wall.n_contacts > 0)
            {
              // A wall with dashpots also meets c = 2 zeta sqrt(kn m) per contact at once: left out,
              // the servo overshoots each step and, the dashpots never pulling (contact_law.h),
              // locks into a cycle at its speed cap, the stress jumping by +-50 % (ServoWall test).
              resistance = 0.0;
              const WallContacts &c = wall_contacts_[w];
              for (std::size_t q = 0; q < c.disc.size(); ++q)
                if (c.state[q].touching)
                  {
                    const double inverse_mass = particles_.inverse_mass[particles_.disc_body[c.disc[q]]];
                    resistance += kn * dt; // a fixed body's contact has no dashpot (contact_law.h)
                    if (inverse_mass > 0.0)
                      resistance += 2.0 * wall.law.damping_ratio() * std::sqrt(kn / inverse_mass);
                  }
            }
          const double gain = servo.relaxation * wall.stress_length() / resistance;
          double speed = gain * (error + servo.integral_gain * (servo.integral + error));
          if (std::abs(speed) < servo.max_speed && wall.n_contacts > 0)
            servo.integral += error; // no wind-up while capped or out of contact
          speed = std::clamp(speed, -servo.max_speed, servo.max_speed);
          wall.velocity = -speed * wall.normal();
        }
      wall.translate(dt * wall.velocity);
    }
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

void DemSystem::compute_forces_and_kick()
{
  // The energy bookkeeping and the dashpot are fixed for a run: the loop is compiled for each
  // combination, so that a run without them does none of their work per contact.
  // Energy weights (a coupled region) are a third such switch.
  const bool dashpot = particle_law_.has_dashpot();
  if (weighted_)
    {
      if (settings_.track_energy)
        dashpot ? compute_forces_and_kick_for<true, true, true>() : compute_forces_and_kick_for<true, false, true>();
      else
        dashpot ? compute_forces_and_kick_for<false, true, true>() : compute_forces_and_kick_for<false, false, true>();
    }
  else if (settings_.track_energy)
    dashpot ? compute_forces_and_kick_for<true, true, false>() : compute_forces_and_kick_for<true, false, false>();
  else
    dashpot ? compute_forces_and_kick_for<false, true, false>() : compute_forces_and_kick_for<false, false, false>();
}

// Pairs [begin, end) of a chunk whose pairs start at `owner_begin`: each pair's force on disc i
// is stored, and its force and moments go to both bodies. `checked`: whether a pair may touch a
// body owned by an earlier chunk (PairContacts: only the first pairs of a chunk, up to
// chunk_checked_end); such a body gets its moment stored for its owner to add later. Not inlined,
// so that one thread and each chunk of several run the same machine code. Returns the number of
// bonds broken.
template <bool track_energy, bool with_dashpot, bool weighted, bool checked>
__attribute__((noinline)) std::uint64_t DemSystem::pair_range(std::size_t begin, std::size_t end,
                                                               std::size_t owner_begin)
{
  ParticleSet &p = particles_;
  const LinearContactLaw &law = particle_law_;
  PairContacts &c = pairs_;
  const double dt = time_step_;
  // Contacts between bodies fixed and at rest since their last evaluation are skipped
  // (set_skip_contacts_between_fixed_bodies); none before the first kick has counted them.
  const bool skip_fixed = skip_fixed_contacts_ && steps_at_rest_.size() == p.n_bodies();
  const std::uint8_t *const steps_at_rest = steps_at_rest_.data();

  // One contact: the force on disc i, stored per pair, and the moments on both bodies.
  // Returns false for a pair that is apart (and not bonded): its force is zero.
  const auto evaluate = [&](std::size_t q, std::uint64_t &broken, double &moment_i,
                            double &moment_j) __attribute__((always_inline)) -> bool {
    const std::uint32_t i = c.disc_i[q], j = c.disc_j[q];
    ContactState &state = c.state[q];
    const double dx = p.disc_x[j] - p.disc_x[i], dy = p.disc_y[j] - p.disc_y[i];
    const double radius_sum = p.disc_radius[i] + p.disc_radius[j];
    const double distance2 = dx * dx + dy * dy;
    if (distance2 >= radius_sum * radius_sum && !state.bonded && !state.touching)
      {
        // Apart now and at the last evaluation, which left its force at zero (a separating
        // contact's force is zero, and a rebuild zeroes new pairs): nothing to store. Only the
        // dissipated work of the separating step is cleared.
        if constexpr (track_energy)
          c.friction_work[q] = c.viscous_work[q] = 0.0;
        return false;
      }
    const std::uint32_t bi = p.disc_body[i], bj = p.disc_body[j];
    if (skip_fixed && state.touching && steps_at_rest[bi] == 2 && steps_at_rest[bj] == 2)
      {
        // Its stored force is what an evaluation would give again (set_skip_contacts_between_fixed_bodies).
        if constexpr (track_energy)
          c.friction_work[q] = c.viscous_work[q] = 0.0;
        return false;
      }
    const double distance = std::sqrt(distance2), inverse_distance = 1.0 / distance;
    // ContactFrame's arithmetic on locals (see there: a frame object costs here).
    const Vec2 normal(dx * inverse_distance, dy * inverse_distance);
    const Vec2 tangent = perp(normal);
    const double overlap = radius_sum - distance;
    const Vec2 contact_point = ContactFrame::point_on_disc(p, i, normal, overlap);
    const Vec2 lever_i = contact_point - Vec2(p.x[bi], p.y[bi]);
    const Vec2 lever_j = contact_point - Vec2(p.x[bj], p.y[bj]);
    const Vec2 v_i = ContactFrame::body_velocity_at(p, bi, lever_i);
    const Vec2 v_j = ContactFrame::body_velocity_at(p, bj, lever_j);
    const Vec2 v_rel = v_j - v_i;
    const ContactKinematics k =
      ContactFrame::kinematics(normal, tangent, overlap, v_rel, p.inverse_mass[bi] + p.inverse_mass[bj], dt);
    const ContactForce f = law.evaluate<with_dashpot>(k, state);
    Vec2 force_on_i = ContactFrame::force_on_i(normal, tangent, f);
    // A contact in a coupling band acts with the particles' share of the energy along its
    // branch (energy_weights.h); its state (the springs' forces) stays unweighted.
    [[maybe_unused]] double weight = 1.0;
    if constexpr (weighted)
      {
        weight = energy_weights_.contact_weight(bi, bj);
        force_on_i *= weight;
      }
    c.force_x[q] = force_on_i.x();
    c.force_y[q] = force_on_i.y();
    moment_i = cross(lever_i, force_on_i);
    moment_j = -cross(lever_j, force_on_i);
    c.elastic_normal_force[q] = state.touching ? f.elastic_normal : 0.0;
    if constexpr (track_energy)
      {
        if constexpr (weighted)
          {
            c.friction_work[q] = weight * f.friction_work;
            c.viscous_work[q] = weight * f.viscous_work;
          }
        else
          {
            c.friction_work[q] = f.friction_work;
            c.viscous_work[q] = f.viscous_work;
          }
      }
    broken += f.bond_broke;
    return true;
  };

  std::uint64_t broken = 0;
  double moment_i, moment_j;
  for (std::size_t q = begin; q < end; ++q)
    if (evaluate(q, broken, moment_i, moment_j))
      {
        const std::uint32_t bi = p.disc_body[c.disc_i[q]], bj = p.disc_body[c.disc_j[q]];
        if (!checked || c.body_first_pair[bi] >= owner_begin)
          {
            p.fx[bi] += c.force_x[q];
            p.fy[bi] += c.force_y[q];
            p.torque[bi] += moment_i;
          }
        else
          c.torque_i[q] = moment_i;
        if (!checked || c.body_first_pair[bj] >= owner_begin)
          {
            p.fx[bj] -= c.force_x[q];
            p.fy[bj] -= c.force_y[q];
            p.torque[bj] += moment_j;
          }
        else
          c.torque_j[q] = moment_j;
      }
  return broken;
}

template <bool track_energy, bool with_dashpot, bool weighted>
void DemSystem::compute_forces_and_kick_for()
{
  ParticleSet &p = particles_;
  PairContacts &c = pairs_;
  const double dt = time_step_;
  const std::size_t nb = p.n_bodies();

  // Body resultants start from gravity (kick_and_drift() set them); + 0.0 turned a -0.0 into
  // +0.0. A sum that starts at +0.0 never becomes -0.0 (x + (-x) is +0.0), and adding +-0.0 to
  // anything else changes no bit, so pairs that are apart (zero force) may be skipped and every
  // body still sums exactly the same.
  //
  // Each chunk of pairs (one per thread, see PairContacts) adds each pair's force to the bodies
  // it owns as soon as it is computed; the bodies shared with later chunks are completed after
  // all chunks are done, in pair order. Every body therefore sums the same terms in the same
  // (ascending pair) order on any number of threads, without a separate pass over all bodies.
  const auto run_chunk = [&](std::size_t k) {
    const std::size_t begin = c.chunk_begin(k), checked_end = c.chunk_checked_end[k], end = c.chunk_begin(k + 1);
    return pair_range<track_energy, with_dashpot, weighted, true>(begin, checked_end, begin) +
           pair_range<track_energy, with_dashpot, weighted, false>(checked_end, end, begin);
  };
  const auto complete_shared_body = [&](std::size_t k) {
    const std::uint32_t b = c.shared_body[k];
    double fx = p.fx[b], fy = p.fy[b], t = p.torque[b];
    for (std::uint32_t e = c.shared_first_entry[k]; e < c.body_offset[b + 1]; ++e)
      {
        const std::uint32_t entry = c.body_entry[e], q = entry >> 1;
        if (entry & 1u)
          {
            fx -= c.force_x[q];
            fy -= c.force_y[q];
            t += c.torque_j[q];
          }
        else
          {
            fx += c.force_x[q];
            fy += c.force_y[q];
            t += c.torque_i[q];
          }
      }
    p.fx[b] = fx;
    p.fy[b] = fy;
    p.torque[b] = t;
  };

  // Then the walls (serial: a few hundred contacts, added to the bodies in wall order after
  // their pairs) and the second half kick. With several chunks and no sheets, all of it runs in
  // one parallel region; with sheets, their forces come between the walls and the kick, outside.
  std::uint64_t broken = 0;
  const bool one_region = c.n_chunks > 1 && sheets_.empty() && !force_hook_;
  if (c.n_chunks == 1) // outside a parallel region the compiler optimises the loop better
    broken = pair_range<track_energy, with_dashpot, weighted, false>(0, c.size(), 0);
  else
    {
#pragma omp parallel num_threads(settings_.n_threads) reduction(+ : broken)
      {
        // One chunk per iteration: chunks own disjoint bodies, so they may run in any order.
#pragma omp for schedule(static, 1)
        for (std::size_t k = 0; k < c.n_chunks; ++k)
          broken += run_chunk(k);
#pragma omp for schedule(static)
        for (std::size_t k = 0; k < c.shared_body.size(); ++k)
          complete_shared_body(k);
        if (one_region)
          {
#pragma omp single
            compute_wall_forces();
            const auto [begin, end] = thread_bodies(nb);
            final_kick(begin, end);
          }
      }
    }
  n_broken_bonds_ += broken;
  if (track_energy && dt > 0.0)
    {
      accumulated_.friction_dissipated += deterministic_sum(c.friction_work, settings_.n_threads);
      accumulated_.viscous_dissipated += deterministic_sum(c.viscous_work, settings_.n_threads);
    }
  if (!one_region)
    {
      for (SparSheet &sheet : sheets_)
        sheet.start_forces(settings_.gravity);
      compute_wall_forces();
      book_wall_work();
      if (sheet_force_hook_)
        sheet_force_hook_(sheets_);
      if (!sheets_.empty())
        compute_sheet_forces_and_kick(); // adds the disc-sheet forces to the bodies before their kick
      if (force_hook_)
        force_hook_(particles_, forces_initialised_ ? time_step_ : 0.5 * first_step_);
      const int n_threads = settings_.n_threads;
#pragma omp parallel num_threads(n_threads) if (n_threads > 1)
      {
        const auto [begin, end] = thread_bodies(nb);
        final_kick(begin, end);
      }
    }
  else
    book_wall_work();
  if (settings_.track_energy && settings_.local_damping > 0.0)
    accumulated_.local_damping_dissipated -= deterministic_sum(body_scratch_, settings_.n_threads);
}

void DemSystem::compute_wall_forces()
{
  ParticleSet &p = particles_;
  const double dt = time_step_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    {
      Wall &wall = walls_[w];
      WallContacts &c = wall_contacts_[w];
      Vec2 total = Vec2::Zero();
      std::size_t n_touching = 0;
      double friction = 0.0, viscous = 0.0;
      for (std::size_t q = 0; q < c.disc.size(); ++q)
        {
          const std::uint32_t d = c.disc[q];
          ContactState &state = c.state[q];
          const Vec2 centre(p.disc_x[d], p.disc_y[d]);
          Vec2 closest;
          const double distance = closest_point_on_segment(centre, wall.start, wall.end, closest);
          const double overlap = p.disc_radius[d] - distance;
          if (overlap <= 0.0 && !state.bonded && !state.touching)
            {
              c.force_x[q] = c.force_y[q] = c.elastic_normal_force[q] = 0.0;
              c.friction_work[q] = c.viscous_work[q] = 0.0;
              continue;
            }
          const std::uint32_t b = p.disc_body[d];
          const Vec2 normal =
            ContactFrame::normal_towards(centre, closest, distance, [&]() -> Vec2 { return -wall.normal(); });
          const ContactFrame contact = ContactFrame::of_disc(p, d, normal, overlap);
          const ContactForce f = wall.law.evaluate(contact.kinematics(wall.velocity, p.inverse_mass[b], dt), state);
          const Vec2 force = contact.force_on_i(f);
          c.force_x[q] = force.x();
          c.force_y[q] = force.y();
          c.elastic_normal_force[q] = state.touching ? f.elastic_normal : 0.0;
          c.friction_work[q] = f.friction_work;
          c.viscous_work[q] = f.viscous_work;
          friction += f.friction_work;
          viscous += f.viscous_work;
          n_broken_bonds_ += f.bond_broke;
          p.fx[b] += force.x();
          p.fy[b] += force.y();
          p.torque[b] += cross(contact.lever(), force);
          total -= force;
          n_touching += state.touching;
        }
      // Sheet nodes pressing on the wall (none without sheets): their force is part of the
      // wall's load; n_contacts keeps counting discs (it is the particles' coordination).
      for (std::size_t s = 0; s < sheets_.size(); ++s)
        {
          const SheetWallLoad load = evaluate_sheet_wall_contacts(sheets_[s], wall, sheet_contacts_[s].walls[w], dt);
          total += load.force_on_wall;
          friction += load.work.friction;
          viscous += load.work.viscous;
          n_broken_bonds_ += load.work.broken_bonds;
        }
      wall.force_from_particles = total;
      wall.n_contacts = n_touching;
      wall_friction_work_[w] = friction;
      wall_viscous_work_[w] = viscous;
    }
}

void DemSystem::book_wall_work()
{
  const double dt = time_step_;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    {
      const Vec2 total = walls_[w].force_from_particles;
      if (settings_.track_energy && dt > 0.0)
        {
          accumulated_.friction_dissipated += wall_friction_work_[w];
          accumulated_.viscous_dissipated += wall_viscous_work_[w];
          // Work of the wall on the particles, trapezoidal in time.
          accumulated_.boundary_work -= 0.5 * (total + wall_force_previous_[w]).dot(walls_[w].velocity) * dt;
        }
      wall_force_previous_[w] = total;
    }
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

EnergyBudget DemSystem::energy() const
{
  const ParticleSet &p = particles_;
  EnergyBudget e = accumulated_;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      if (p.inverse_mass[b] == 0.0)
        continue;
      const double scale = inertia_scale_.empty() ? 1.0 : inertia_scale_[b];
      e.kinetic += scale * (0.5 * p.mass[b] * (p.vx[b] * p.vx[b] + p.vy[b] * p.vy[b]) +
                            0.5 * p.inertia[b] * p.omega[b] * p.omega[b]);
      e.gravitational -= p.mass[b] * (settings_.gravity.x() * p.x[b] + settings_.gravity.y() * p.y[b]);
    }
  for (std::size_t q = 0; q < pairs_.size(); ++q)
    if (pairs_.state[q].touching)
      {
        const double stored = particle_law_.elastic_energy(pairs_.elastic_normal_force[q], pairs_.state[q].tangential_force);
        e.elastic += weighted_ ? energy_weights_.contact_weight(p.disc_body[pairs_.disc_i[q]], p.disc_body[pairs_.disc_j[q]]) * stored
                               : stored;
      }
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t q = 0; q < wall_contacts_[w].disc.size(); ++q)
      if (wall_contacts_[w].state[q].touching)
        e.elastic += walls_[w].law.elastic_energy(wall_contacts_[w].elastic_normal_force[q],
                                                  wall_contacts_[w].state[q].tangential_force);
  for (std::size_t s = 0; s < sheets_.size(); ++s)
    {
      const SparSheet &sheet = sheets_[s];
      const SheetContacts &c = sheet_contacts_[s];
      e.sheet_kinetic += sheet.kinetic_energy();
      e.sheet_elastic += sheet.elastic_energy();
      e.gravitational += sheet.gravitational_energy(settings_.gravity);
      for (std::size_t q = 0; q < c.size(); ++q)
        if (c.state[q].touching)
          e.elastic += sheet.interface_law().elastic_energy(c.elastic_normal_force[q], c.state[q].tangential_force);
      for (std::size_t w = 0; w < c.walls.size() && w < walls_.size(); ++w)
        for (std::size_t q = 0; q < c.walls[w].size(); ++q)
          if (c.walls[w].state[q].touching)
            e.elastic += walls_[w].law.elastic_energy(c.walls[w].elastic_normal_force[q],
                                                      c.walls[w].state[q].tangential_force);
    }
  return e;
}

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

std::size_t DemSystem::n_touching_pairs() const
{
  return static_cast<std::size_t>(
    std::count_if(pairs_.state.begin(), pairs_.state.end(), [](const ContactState &s) { return s.touching; }));
}

std::size_t DemSystem::n_touching_wall_contacts() const
{
  std::size_t n = 0;
  for (const Wall &w : walls_)
    n += w.n_contacts;
  return n;
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

void DemSystem::set_local_damping(double alpha)
{
  if (!(alpha >= 0.0 && alpha < 1.0))
    throw std::invalid_argument("local damping " + std::to_string(alpha) + " must lie in [0, 1)");
  settings_.local_damping = alpha;
}
} // namespace geohybrid::dem
