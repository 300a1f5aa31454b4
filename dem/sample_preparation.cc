#include "sample_preparation.h"

#include "measurements.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
namespace
{
/// Solid area of one particle whose large disc has radius 1.
double unit_area(const RedfSpec &s)
{
  if (s.shape == ParticleShape::disc)
    return pi;
  return two_disc_geometry(1.0, s.cluster_diameter_ratio, 2.0 * s.cluster_spacing).area;
}

/// Random sequential placement without overlap, at the given large-disc radii.
ParticleSet place_at_random(const RedfSpec &s, const std::vector<double> &radii)
{
  UniformRandom random(s.seed);
  ParticleSet p;
  p.reserve(radii.size(), 2 * radii.size());
  // Extent of a particle: for a cluster, the distance from its centre of mass to the far edge.
  double reach_max = 0.0;
  for (double r : radii)
    reach_max = std::max(reach_max, s.shape == ParticleShape::disc ? r : r * (1.0 + 2.0 * s.cluster_spacing));
  const double cell = 2.0 * reach_max;
  const std::size_t nx = static_cast<std::size_t>(s.width / cell) + 1, ny = static_cast<std::size_t>(s.height / cell) + 1;
  std::vector<std::vector<std::uint32_t>> grid(nx * ny); // disc indices per cell
  const auto cell_of = [&](double x, double y) {
    const std::size_t cx = std::min(nx - 1, static_cast<std::size_t>(std::max(0.0, x) / cell));
    const std::size_t cy = std::min(ny - 1, static_cast<std::size_t>(std::max(0.0, y) / cell));
    return std::make_pair(cx, cy);
  };
  constexpr int max_tries = 5000;
  for (std::size_t k = 0; k < radii.size(); ++k)
    {
      const double r = radii[k];
      bool placed = false;
      for (int attempt = 0; attempt < max_tries && !placed; ++attempt)
        {
          const double angle = random.uniform(0.0, 2.0 * pi);
          const double x = random.uniform(0.0, s.width), y = random.uniform(0.0, s.height);
          ParticleSet candidate;
          if (s.shape == ParticleShape::disc)
            candidate.add_disc(Vec2(x, y), r, s.density);
          else
            candidate.add_two_disc_cluster(Vec2(x, y), r, s.cluster_diameter_ratio * r, 2.0 * s.cluster_spacing * r,
                                           angle, s.density);
          bool fits = true;
          for (std::size_t d = 0; d < candidate.n_discs_total() && fits; ++d)
            {
              const double cx = candidate.disc_x[d], cy = candidate.disc_y[d], cr = candidate.disc_radius[d];
              if (cx - cr < 0.0 || cx + cr > s.width || cy - cr < 0.0 || cy + cr > s.height)
                fits = false;
              const auto [gx, gy] = cell_of(cx, cy);
              for (std::size_t ix = gx > 0 ? gx - 1 : 0; ix <= std::min(nx - 1, gx + 1) && fits; ++ix)
                for (std::size_t iy = gy > 0 ? gy - 1 : 0; iy <= std::min(ny - 1, gy + 1) && fits; ++iy)
                  for (std::uint32_t other : grid[iy * nx + ix])
                    {
                      const double reach = cr + p.disc_radius[other];
                      const double dx = p.disc_x[other] - cx, dy = p.disc_y[other] - cy;
                      if (dx * dx + dy * dy < reach * reach)
                        {
                          fits = false;
                          break;
                        }
                    }
            }
          if (!fits)
            continue;
          const std::size_t first = p.n_discs_total();
          if (s.shape == ParticleShape::disc)
            p.add_disc(Vec2(x, y), r, s.density);
          else
            p.add_two_disc_cluster(Vec2(x, y), r, s.cluster_diameter_ratio * r, 2.0 * s.cluster_spacing * r, angle,
                                   s.density);
          for (std::size_t d = first; d < p.n_discs_total(); ++d)
            {
              const auto [gx, gy] = cell_of(p.disc_x[d], p.disc_y[d]);
              grid[gy * nx + gx].push_back(static_cast<std::uint32_t>(d));
            }
          placed = true;
        }
      if (!placed)
        throw std::invalid_argument("REDF: could not place particle " + std::to_string(k) + " of " +
                                    std::to_string(radii.size()) +
                                    " at random without overlap; use fewer particles or a larger box");
    }
  return p;
}

double mean_wall_stress(const DemSystem &system, const RectangularBox &box)
{
  return 0.5 * (box.horizontal_stress(system) + box.vertical_stress(system));
}
} // namespace

RedfSample make_redf_sample(const RedfSpec &s, const std::function<void(double)> &progress)
{
  if (!(s.target_porosity >= 0.05 && s.target_porosity <= 0.8))
    throw std::invalid_argument("REDF: target porosity " + std::to_string(s.target_porosity) +
                                " is outside [0.05, 0.8]");
  if (!(s.width > 0.0 && s.height > 0.0) || s.n_particles == 0)
    throw std::invalid_argument("REDF: the box must have a positive size and hold at least one particle");
  if (!(s.size_ratio > 0.0 && s.size_ratio <= 1.0))
    throw std::invalid_argument("REDF: size ratio must lie in (0, 1]");
  if (!(s.target_stress > 0.0))
    throw std::invalid_argument("REDF: the target stress must be positive");

  // Final sizes: the relative sizes u_k scaled so the solids fill (1 - n) of the box.
  UniformRandom random(s.seed ^ 0x5eedULL);
  std::vector<double> u(s.n_particles);
  double sum_u2 = 0.0;
  for (double &x : u)
    {
      x = random.uniform(s.size_ratio, 1.0);
      sum_u2 += x * x;
    }
  std::sort(u.begin(), u.end(), std::greater<double>()); // large first: easier random placement
  const double box_area = s.width * s.height;
  const double final_scale = std::sqrt((1.0 - s.target_porosity) * box_area / (unit_area(s) * sum_u2));
  // Start at a solid fraction of 0.45 (or less): random placement succeeds easily there.
  const double initial_fraction = std::min(0.45, 0.75 * (1.0 - s.target_porosity));
  const double initial_scale = final_scale * std::sqrt(initial_fraction / (1.0 - s.target_porosity));
  // A sample must be many particles across: refuse one whose largest particle would span more
  // than a fifth of the box's smaller side.
  const double largest_extent = final_scale * u.front() *
                                (s.shape == ParticleShape::disc ? 2.0 : 1.0 + 2.0 * s.cluster_spacing + s.cluster_diameter_ratio);
  if (largest_extent > 0.2 * std::min(s.width, s.height))
    {
      std::ostringstream message;
      message << "REDF: " << s.n_particles << " particles filling a " << s.width << " m x " << s.height
              << " m box at porosity " << s.target_porosity << " would be up to " << largest_extent
              << " m across, more than a fifth of the box; use more particles or a larger box";
      throw std::invalid_argument(message.str());
    }
  std::vector<double> radii(u.size());
  for (std::size_t k = 0; k < u.size(); ++k)
    radii[k] = initial_scale * u[k];
  ParticleSet particles = place_at_random(s, radii);

  const LinearContactLaw material(s.particle_contact);
  DemSettings settings;
  settings.gravity = Vec2::Zero();
  settings.local_damping = 0.7;
  settings.n_threads = s.n_threads;
  settings.track_energy = false;
  // The time step is set for the final (largest) sizes' masses: sqrt(m/k) grows with size,
  // so the step of the initial, smaller particles is safe throughout.
  DemSystem system(std::move(particles), material, settings);
  const double overhang = 0.1 * std::max(s.width, s.height);
  const RectangularBox box = RectangularBox::add_to(system, 0.0, 0.0, s.width, s.height,
                                                    LinearContactLaw(s.wall_contact), overhang);
  double solid_area = total_solid_area(system.particles());
  const auto porosity = [&] { return 1.0 - solid_area / box.area(system); };

  // ---- growth with decrease of friction ----
  // Grow while the assembly is loose; once it jams (mean wall stress above the target) above
  // the target porosity, lower the growth friction so the grains rearrange, then grow again.
  // Stop when it is jammed at the target porosity.
  // Relative radius growth per step. While the assembly is loose (mean wall stress below a tenth
  // of the target) few grains touch, and growth can be fast. Once it carries stress, a step lifts
  // the contact overlaps by about growth x kn / sigma of their value (some 70 % at 1e-4, 10 kPa and
  // Table 5's kn): the stress overshoots the target and the grains rearrange, which is what
  // densifies the jammed assembly (and, at each drop, lets the friction fall). 2e-5 per step took
  // 2.4 times as many steps to the same porosity and growth friction (4,000 clusters, 10 kPa:
  // 188,000 against 78,000; bench/RESULTS.md), for a final stress closer to the target before the
  // servo stage below (10.6 against 13 kPa at 10 kPa).
  const auto growth_per_step = [&] { return mean_wall_stress(system, box) < 0.1 * s.target_stress ? 4e-4 : 1e-4; };
  double friction_deg = s.initial_growth_friction_deg >= 0.0 ? s.initial_growth_friction_deg
                                                            : s.particle_contact.friction_angle_deg;
  const auto use_friction = [&](double degrees) {
    ContactParameters growth = s.particle_contact;
    growth.friction_angle_deg = degrees;
    system.set_particle_law(LinearContactLaw(growth));
  };
  use_friction(friction_deg);
  std::uint64_t steps = 0, steps_jammed = 0;
  const std::uint64_t relax_steps_per_friction_drop = 1000;
  const double start_porosity = porosity();
  const double upper = s.target_porosity + 0.5 * s.porosity_tolerance;
  for (;;)
    {
      const bool jammed = mean_wall_stress(system, box) > s.target_stress;
      const double n = porosity();
      // Target porosity reached: the assembly is jammed or close to it (the friction is lowered
      // only while it is jammed above the target), so the servo stage below compacts it little.
      if (n <= upper)
        break;
      if (steps++ > s.max_steps)
        throw std::runtime_error("REDF: no convergence after " + std::to_string(s.max_steps) +
                                 " steps (porosity " + std::to_string(n) + ")");
      if (!jammed)
        {
          steps_jammed = 0;
          const double growth = growth_per_step();
          system.scale_particle_sizes(1.0 + growth);
          solid_area *= (1.0 + growth) * (1.0 + growth);
        }
      else if (++steps_jammed % relax_steps_per_friction_drop == 0 &&
               unbalanced_force_ratio(system) < 0.05)
        {
          // Jammed above the target porosity, and still jammed after relaxing without growth:
          // lower the friction so the grains can rearrange into a denser state.
          if (friction_deg <= 0.0)
            {
              std::ostringstream message;
              message << "REDF: the target porosity " << s.target_porosity << " cannot be reached: the assembly "
                      << "jams at porosity " << n << " even without friction (stress "
                      << mean_wall_stress(system, box) << " Pa); choose a larger porosity or a lower stress";
              throw std::runtime_error(message.str());
            }
          friction_deg = friction_deg > 0.5 ? 0.9 * friction_deg : 0.0;
          use_friction(friction_deg);
        }
      system.step();
      if (progress && steps % 1000 == 0)
        progress(0.8 * std::clamp((start_porosity - n) / (start_porosity - s.target_porosity), 0.0, 1.0));
    }

  // ---- equilibrium at the target stress with the material friction ----
  system.set_particle_law(material);
  box.servo_sides(system, s.target_stress, true, s.target_stress, true, 0.05);
  std::uint64_t settle_steps = 0;
  const std::uint64_t check_every = 200;
  for (;;)
    {
      box.update_loaded_lengths(system);
      system.step();
      ++settle_steps;
      if (settle_steps % check_every != 0)
        continue;
      const double stress_error = std::max(std::abs(box.horizontal_stress(system) / s.target_stress - 1.0),
                                           std::abs(box.vertical_stress(system) / s.target_stress - 1.0));
      if (stress_error < s.stress_tolerance && unbalanced_force_ratio(system) < s.equilibrium_unbalanced_ratio)
        break;
      if (steps + settle_steps > s.max_steps)
        throw std::runtime_error("REDF: no equilibrium at the target stress after " + std::to_string(s.max_steps) +
                                 " steps (stress error " + std::to_string(stress_error) + ")");
      if (progress)
        progress(0.8 + 0.2 * std::min(1.0, static_cast<double>(settle_steps) / 50000.0));
    }

  RedfResult result;
  result.porosity = porosity();
  result.mean_stress = mean_wall_stress(system, box);
  result.growth_friction_deg = friction_deg;
  result.size_scale = std::sqrt(solid_area / (unit_area(s) * sum_u2)) / initial_scale;
  result.n_steps = steps + settle_steps;
  if (std::abs(result.porosity - s.target_porosity) > s.porosity_tolerance)
    {
      std::ostringstream message;
      message << "REDF: the sample settled at porosity " << result.porosity << ", outside the target "
              << s.target_porosity << " +/- " << s.porosity_tolerance
              << (result.porosity < s.target_porosity
                    ? " (the confining stress compacted it: the target is too loose for this friction at this "
                      "stress; raise 'initial growth friction' or lower the target stress)"
                    : "");
      throw std::runtime_error(message.str());
    }
  if (progress)
    progress(1.0);
  return RedfSample{std::move(system), box, result};
}
} // namespace geohybrid::dem
