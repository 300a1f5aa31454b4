// The force evaluation of a step: the pair loop (one chunk of pairs per thread, summed in a
// fixed order), then walls, sheets and hooks, then the second half kick. The loop is compiled
// for each combination of energy booking, dashpot and energy weights.
#include "dem_system.h"

#include "contact_frame.h"
#include "dem_system_detail.h"

#include <omp.h>

namespace geohybrid::dem
{
void DemSystem::compute_forces_and_kick()
{
  // The energy bookkeeping and the dashpot are fixed for a run: the loop is compiled for each
  // combination, so that a run without them does none of their work per contact.
  // Energy weights (a coupled region) are a third such switch.
  const bool dashpot = particle_law_.has_dashpot();
  if (weighted())
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
  [[maybe_unused]] const EnergyWeights *const weights = weighted ? coupling_->energy_weights() : nullptr;

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
        weight = weights->contact_weight(bi, bj);
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
  const bool force_hook = coupling_ && coupling_->force_hook(); // a coupling's forces come before the kick
  const bool one_region = c.n_chunks > 1 && sheets_.empty() && !force_hook;
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
            const auto [begin, end] = detail::thread_bodies(nb);
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
      if (coupling_ && coupling_->sheet_force_hook())
        coupling_->sheet_force_hook()(sheets_);
      if (!sheets_.empty())
        compute_sheet_forces_and_kick(); // adds the disc-sheet forces to the bodies before their kick
      if (force_hook)
        coupling_->force_hook()(particles_, forces_initialised_ ? time_step_ : 0.5 * first_step_);
      const int n_threads = settings_.n_threads;
#pragma omp parallel num_threads(n_threads) if (n_threads > 1)
      {
        const auto [begin, end] = detail::thread_bodies(nb);
        final_kick(begin, end);
      }
    }
  else
    book_wall_work();
  if (settings_.track_energy && settings_.local_damping > 0.0)
    accumulated_.local_damping_dissipated -= deterministic_sum(body_scratch_, settings_.n_threads);
}
} // namespace geohybrid::dem
