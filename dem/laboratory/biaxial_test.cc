#include "biaxial_test.h"

#include "dem/measurements.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

namespace geohybrid::dem
{
std::uint64_t consolidate_isotropically(DemSystem &system, const RectangularBox &box, const ConsolidationSpec &spec)
{
  if (!(spec.stress > 0.0))
    throw std::invalid_argument("consolidation: the stress must be positive");
  box.servo_sides(system, spec.stress, true, spec.stress, true, spec.servo_max_speed);
  constexpr std::uint64_t check_every = 200;
  for (std::uint64_t steps = 0;; ++steps)
    {
      if (steps % check_every == 0)
        {
          const double stress_error = std::max(std::abs(box.horizontal_stress(system) / spec.stress - 1.0),
                                               std::abs(box.vertical_stress(system) / spec.stress - 1.0));
          if (stress_error < spec.stress_tolerance && unbalanced_force_ratio(system) < spec.unbalanced_ratio)
            return steps;
          if (steps >= spec.max_steps)
            throw std::runtime_error("consolidation to " + std::to_string(spec.stress) + " Pa: no equilibrium after " +
                                     std::to_string(steps) + " steps (stress error " + std::to_string(stress_error) +
                                     ")");
        }
      box.update_loaded_lengths(system);
      system.step();
    }
}

void move_to_threads(DemSystem &system, int n_threads)
{
  if (n_threads < 1)
    throw std::invalid_argument("move_to_threads: at least one thread");
  if (system.settings().n_threads == n_threads)
    return;
  DemSettings settings = system.settings();
  settings.n_threads = n_threads;
  DemSystemState state = system.export_state();
  // On several threads the system stores each pair's moments, and reads those of a pair that
  // stays apart as the zero written when it came apart. On one thread it stores none: a pair that
  // came apart then still holds the moment of its last contact on several threads (1 -> 2 -> 1
  // -> 2 threads gave another curve). Apart pairs get the zero a straight run leaves them.
  PairContacts &pairs = state.pairs;
  for (std::size_t q = 0; q < pairs.size(); ++q)
    if (!pairs.state[q].touching && !pairs.state[q].bonded)
      pairs.torque_i[q] = pairs.torque_j[q] = 0.0;
  // Built like a system resumed from a checkpoint: its particles and walls, then the whole state
  // (contact histories, servo integrals, Verlet list, time step).
  DemSystem moved(state.particles, LinearContactLaw(state.particle_contact), settings);
  for (const Wall &wall : state.walls)
    moved.add_wall(wall);
  if (system.sheet_local_damping() >= 0.0) // negative: the settings' (not part of the state)
    moved.set_sheet_local_damping(system.sheet_local_damping());
  moved.restore_state(std::move(state));
  system = std::move(moved);
}

BiaxialCurve run_biaxial_test(DemSystem &system, const RectangularBox &box, const BiaxialSpec &spec,
                              double mean_diameter, double density, const std::function<void(double)> &progress,
                              const std::function<int()> &thread_budget)
{
  if (!(spec.confining_stress > 0.0))
    throw std::invalid_argument("biaxial test: the confining stress must be positive");
  if (!(spec.final_axial_strain > 0.0 && spec.final_axial_strain < 0.5))
    throw std::invalid_argument("biaxial test: the final axial strain must lie in (0, 0.5)");
  if (spec.top_wall_speed < 0.0 || (spec.top_wall_speed == 0.0 && !(spec.target_inertial_number > 0.0)))
    throw std::invalid_argument("biaxial test: the top wall speed must be positive (or set an inertial number)");
  if (!(spec.ramp_strain >= 0.0 && spec.ramp_strain < spec.final_axial_strain))
    throw std::invalid_argument("biaxial test: the speed ramp's strain must lie in [0, final axial strain)");

  ConsolidationSpec consolidation;
  consolidation.stress = spec.confining_stress;
  consolidation.stress_tolerance = spec.consolidation_stress_tolerance;
  consolidation.unbalanced_ratio = spec.consolidation_unbalanced_ratio;
  consolidation.servo_max_speed = spec.servo_max_speed;
  const std::uint64_t consolidation_steps = consolidate_isotropically(system, box, consolidation);

  const double H0 = box.height(system), W0 = box.width(system);
  // Inertial number I = (V / H) d sqrt(rho / sigma_0): below ~1e-3 the test is quasi-static.
  const double speed = spec.top_wall_speed > 0.0
                         ? spec.top_wall_speed
                         : spec.target_inertial_number * H0 / (mean_diameter * std::sqrt(density / spec.confining_stress));
  BiaxialCurve curve;
  curve.confining_stress = spec.confining_stress;
  curve.top_wall_speed = speed;
  curve.inertial_number = speed / H0 * mean_diameter * std::sqrt(density / spec.confining_stress);
  curve.initial_porosity = 1.0 - total_solid_area(system.particles()) / (H0 * W0);
  curve.consolidation_steps = consolidation_steps;

  // The lateral walls must be able to follow the sample's dilation: allow them ten times V.
  box.servo_sides(system, spec.confining_stress, true, 0.0, false, std::max(spec.servo_max_speed, 10.0 * speed));
  system.walls()[box.bottom].control = WallControl::prescribed_velocity;
  system.walls()[box.bottom].velocity = Vec2::Zero();
  system.walls()[box.top].control = WallControl::prescribed_velocity;
  // The top wall accelerates uniformly from rest to V over the first ramp_strain of axial strain:
  // started at V at once, it would send a stress wave through the sample (a jump of about
  // rho c V, some 10 kPa at V = 9 cm/s) that spoils the first points, where the modulus is read.
  const double ramp_time = spec.ramp_strain > 0.0 ? 2.0 * spec.ramp_strain * H0 / speed : 0.0;
  const double dt = system.time_step();

  // Stresses are averaged over each recording interval, as a load cell would: the force on a
  // wall touched by a few dozen grains fluctuates from step to step.
  double sum_axial = 0.0, sum_lateral = 0.0;
  std::size_t n_summed = 0;
  const auto record = [&] {
    BiaxialPoint p;
    p.axial_strain = (H0 - box.height(system)) / H0;
    p.lateral_strain = (W0 - box.width(system)) / W0;
    p.volumetric_strain = p.axial_strain + p.lateral_strain;
    p.axial_stress = n_summed ? sum_axial / n_summed : box.vertical_stress(system);
    p.lateral_stress = n_summed ? sum_lateral / n_summed : box.horizontal_stress(system);
    p.deviatoric_stress = p.axial_stress - p.lateral_stress;
    curve.points.push_back(p);
    sum_axial = sum_lateral = 0.0;
    n_summed = 0;
  };
  record();
  double next_record = spec.record_interval;
  for (;;)
    {
      if (thread_budget)
        move_to_threads(system, thread_budget());
      const double elapsed = dt * static_cast<double>(curve.compression_steps);
      system.walls()[box.top].velocity = Vec2(0.0, -speed * (elapsed < ramp_time ? elapsed / ramp_time : 1.0));
      box.update_loaded_lengths(system);
      system.step();
      ++curve.compression_steps;
      sum_axial += box.vertical_stress(system);
      sum_lateral += box.horizontal_stress(system);
      ++n_summed;
      const double strain = (H0 - box.height(system)) / H0;
      if (strain >= next_record)
        {
          record();
          next_record += spec.record_interval;
          if (progress)
            progress(std::min(1.0, strain / spec.final_axial_strain));
        }
      if (strain >= spec.final_axial_strain)
        break;
    }
  system.walls()[box.top].velocity = Vec2::Zero();
  curve.final_threads = system.settings().n_threads;
  return curve;
}

std::pair<double, double> fit_mohr_coulomb(const std::vector<double> &sigma_1, const std::vector<double> &sigma_3)
{
  const std::size_t n = sigma_1.size();
  if (n == 0 || sigma_3.size() != n)
    throw std::invalid_argument("Mohr-Coulomb fit: need as many sigma_1 as sigma_3, at least one");
  std::vector<double> s(n), t(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      s[k] = 0.5 * (sigma_1[k] + sigma_3[k]);
      t[k] = 0.5 * (sigma_1[k] - sigma_3[k]);
    }
  if (n == 1)
    return {std::asin(std::clamp(t[0] / s[0], -1.0, 1.0)) * 180.0 / pi, 0.0};
  const double s_mean = std::accumulate(s.begin(), s.end(), 0.0) / n;
  const double t_mean = std::accumulate(t.begin(), t.end(), 0.0) / n;
  double sst = 0.0, ss = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    {
      sst += (s[k] - s_mean) * (t[k] - t_mean);
      ss += (s[k] - s_mean) * (s[k] - s_mean);
    }
  const double slope = std::clamp(sst / ss, -1.0, 1.0);
  const double phi = std::asin(slope);
  const double intercept = t_mean - slope * s_mean;
  return {phi * 180.0 / pi, intercept / std::cos(phi)};
}

namespace
{
/// Least-squares slope of y against x over points [first, last).
double slope(const std::vector<BiaxialPoint> &p, std::size_t first, std::size_t last,
             double BiaxialPoint::*x, double BiaxialPoint::*y)
{
  double xm = 0.0, ym = 0.0;
  const double n = static_cast<double>(last - first);
  for (std::size_t k = first; k < last; ++k)
    {
      xm += p[k].*x;
      ym += p[k].*y;
    }
  xm /= n;
  ym /= n;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t k = first; k < last; ++k)
    {
      sxy += (p[k].*x - xm) * (p[k].*y - ym);
      sxx += (p[k].*x - xm) * (p[k].*x - xm);
    }
  return sxx > 0.0 ? sxy / sxx : 0.0;
}
} // namespace

BiaxialParameters analyse_biaxial_curves(const std::vector<BiaxialCurve> &curves)
{
  if (curves.empty())
    throw std::invalid_argument("biaxial analysis: no curve");
  BiaxialParameters r;
  std::vector<double> peak_1, peak_3, residual_1, residual_3;
  for (const BiaxialCurve &c : curves)
    {
      const std::vector<BiaxialPoint> &p = c.points;
      if (p.size() < 10)
        throw std::invalid_argument("biaxial analysis: a curve has fewer than 10 points");
      const auto peak = std::max_element(p.begin(), p.end(), [](const BiaxialPoint &a, const BiaxialPoint &b) {
        return a.deviatoric_stress < b.deviatoric_stress;
      });
      peak_1.push_back(peak->axial_stress);
      peak_3.push_back(peak->lateral_stress);
      // Residual: mean state over the last 10 % of the axial strain.
      const double last_strain = p.back().axial_strain;
      double s1 = 0.0, s3 = 0.0;
      std::size_t n = 0;
      for (const BiaxialPoint &q : p)
        if (q.axial_strain >= 0.9 * last_strain)
          {
            s1 += q.axial_stress;
            s3 += q.lateral_stress;
            ++n;
          }
      residual_1.push_back(s1 / n);
      residual_3.push_back(s3 / n);

      // Elastic part: points up to 30 % of the peak deviator (at least 3 points).
      const double q_peak = peak->deviatoric_stress;
      std::size_t elastic_end = 1;
      while (elastic_end < p.size() && p[elastic_end].deviatoric_stress < 0.3 * q_peak)
        ++elastic_end;
      elastic_end = std::max<std::size_t>(elastic_end + 1, 3);
      r.young_modulus += slope(p, 0, elastic_end, &BiaxialPoint::axial_strain, &BiaxialPoint::deviatoric_stress);
      r.poisson_ratio += -slope(p, 0, elastic_end, &BiaxialPoint::axial_strain, &BiaxialPoint::lateral_strain);
      // E50: secant to half the peak deviator, interpolated.
      std::size_t k = 1;
      while (k < p.size() && p[k].deviatoric_stress < 0.5 * q_peak)
        ++k;
      const double q0 = p[k - 1].deviatoric_stress, q1 = p[k].deviatoric_stress;
      const double e50 = p[k - 1].axial_strain +
                         (0.5 * q_peak - q0) / (q1 - q0) * (p[k].axial_strain - p[k - 1].axial_strain);
      r.young_modulus_50 += 0.5 * q_peak / e50;
      // Dilatancy: the largest dilation rate, sin psi = -d(ev)/d(ea - el), over a 5-point window.
      double best = 0.0;
      for (std::size_t j = 0; j + 5 < p.size(); ++j)
        {
          const double dev = p[j + 5].volumetric_strain - p[j].volumetric_strain;
          const double dshear = (p[j + 5].axial_strain - p[j + 5].lateral_strain) - (p[j].axial_strain - p[j].lateral_strain);
          if (dshear > 0.0)
            best = std::max(best, -dev / dshear);
        }
      r.dilatancy_angle_deg += std::asin(std::clamp(best, 0.0, 1.0)) * 180.0 / pi;
    }
  const double n = static_cast<double>(curves.size());
  r.young_modulus /= n;
  r.young_modulus_50 /= n;
  r.poisson_ratio /= n;
  r.dilatancy_angle_deg /= n;
  const auto [phi, c] = fit_mohr_coulomb(peak_1, peak_3);
  r.peak_friction_angle_deg = phi;
  r.cohesion = c;
  r.residual_friction_angle_deg = fit_mohr_coulomb(residual_1, residual_3).first;
  return r;
}

ContinuumEquivalent continuum_equivalent(const BiaxialParameters &biaxial)
{
  ContinuumEquivalent c;
  const double nu_2d = biaxial.poisson_ratio, e_2d = biaxial.young_modulus;
  c.poisson_ratio = nu_2d / (1.0 + nu_2d);
  c.young_modulus = e_2d * (1.0 - c.poisson_ratio * c.poisson_ratio);
  c.friction_angle_deg = biaxial.peak_friction_angle_deg;
  c.cohesion = std::max(0.0, biaxial.cohesion);
  c.dilatancy_angle_deg = std::clamp(biaxial.dilatancy_angle_deg, 0.0, c.friction_angle_deg);
  std::ostringstream why;
  if (!(e_2d > 0.0) || !std::isfinite(e_2d))
    why << "the biaxial Young modulus " << e_2d << " Pa is not positive";
  else if (!(nu_2d >= 0.0 && nu_2d < 1.0))
    why << "the biaxial Poisson ratio " << nu_2d
        << " lies outside [0, 1): no isotropic plane-strain continuum has it (nu = nu_2D / (1 + nu_2D) >= 0.5)";
  else if (!(c.friction_angle_deg > 0.0 && c.friction_angle_deg < 90.0))
    why << "the peak friction angle " << c.friction_angle_deg << " deg lies outside (0, 90)";
  c.invalid_reason = why.str();
  return c;
}
} // namespace geohybrid::dem
