// The body loops of a step: the first half kick and the drift, the forces restarted from
// gravity, the second half kick with PFC's local damping. Each is compiled for its switches
// (damping, energy booking, constrained bodies), so that a run pays only for what it uses.
#include "dem_system.h"

#include "dem_system_detail.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace geohybrid::dem
{
namespace
{
/// What the body loops of a step read besides the particles.
struct BodyLoopInput
{
  double dt = 0.0, alpha = 0.0, gx = 0.0, gy = 0.0;
  double *damping_fx = nullptr, *damping_fy = nullptr, *damping_torque = nullptr, *scratch = nullptr;
  const double *damping_scale = nullptr; ///< per body 1 or 0 (constrained bodies: coupling_attachment.h), or none
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
    const auto [begin, end] = detail::thread_bodies(nb);
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
  const SoaVector<double> *constrained = coupling_ ? &coupling_->damping_scale() : nullptr;
  in.damping_scale = constrained ? constrained->data() : nullptr;
  if (in.alpha == 0.0)
    final_kick_range<false, false>(particles_, in, begin, end);
  else if (constrained && !constrained->empty())
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
} // namespace geohybrid::dem
