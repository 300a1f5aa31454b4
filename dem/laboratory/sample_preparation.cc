#include "sample_preparation.h"

#include "dem/measurements.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

/// Largest extent of a particle whose large disc has radius 1.
double unit_extent(const RedfSpec &s)
{
  return s.shape == ParticleShape::disc ? 2.0 : 1.0 + 2.0 * s.cluster_spacing + s.cluster_diameter_ratio;
}

/// Narrowest width of a convex polygon: the smallest, over its sides, of the distance from the
/// side's line to the farthest vertex (the polygon fits between two parallel lines that far apart).
double narrowest_width(const std::vector<Vec2> &v)
{
  double narrowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < v.size(); ++k)
    {
      const Vec2 inward = perp(v[(k + 1) % v.size()] - v[k]).normalized();
      double farthest = 0.0;
      for (const Vec2 &p : v)
        farthest = std::max(farthest, inward.dot(p - v[k]));
      narrowest = std::min(narrowest, farthest);
    }
  return narrowest;
}

void check_spec(const RedfSpec &s)
{
  if (!(s.target_porosity >= 0.05 && s.target_porosity <= 0.8))
    throw std::invalid_argument("REDF: target porosity " + std::to_string(s.target_porosity) +
                                " is outside [0.05, 0.8]");
  if (s.n_particles == 0)
    throw std::invalid_argument("REDF: the sample must hold at least one particle");
  if (!(s.target_stress > 0.0))
    throw std::invalid_argument("REDF: the target stress must be positive");
}

// The walls' stresses, as the growth and the equilibrium stages read them, for the two kinds of
// boundary (a rectangle keeps its own, per pair of opposite walls).
double mean_wall_stress(const DemSystem &system, const RectangularBox &box)
{
  return 0.5 * (box.horizontal_stress(system) + box.vertical_stress(system));
}

double mean_wall_stress(const DemSystem &system, const WallPolygon &polygon) { return polygon.mean_stress(system); }

void servo_to_stress(DemSystem &system, const RectangularBox &box, double stress)
{
  box.servo_sides(system, stress, true, stress, true, 0.05);
}

void servo_to_stress(DemSystem &system, const WallPolygon &polygon, double stress)
{
  polygon.servo_walls(system, stress, 0.05);
}

double stress_error(const DemSystem &system, const RectangularBox &box, double target)
{
  return std::max(std::abs(box.horizontal_stress(system) / target - 1.0),
                  std::abs(box.vertical_stress(system) / target - 1.0));
}

double stress_error(const DemSystem &system, const WallPolygon &polygon, double target)
{
  return polygon.largest_relative_stress_error(system, target);
}

/// The contact time sqrt(m / kn) of the lightest movable body with the particles' normal
/// stiffness: the time scale of the grains' response, against which growth is made slow.
double lightest_contact_time(const DemSystem &system)
{
  const ParticleSet &p = system.particles();
  double lightest = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (p.inverse_mass[b] > 0.0)
      lightest = std::min(lightest, p.mass[b]);
  if (!std::isfinite(lightest))
    throw std::invalid_argument("REDF: no movable particle to grow");
  return std::sqrt(lightest / system.particle_law().normal_stiffness());
}

DemSettings redf_settings(const RedfSpec &s)
{
  DemSettings settings;
  settings.gravity = Vec2::Zero();
  settings.local_damping = 0.7;
  settings.n_threads = s.n_threads;
  settings.track_energy = false;
  return settings;
}

/// REDF on a system whose walls (`boundary`) enclose all its particles: growth to the target
/// porosity, then equilibrium at the target stress with the material friction.
template <class Boundary>
RedfResult grow_and_settle(const RedfSpec &s, DemSystem &system, const Boundary &boundary,
                           const std::function<void(double)> &progress)
{
  const LinearContactLaw material(s.particle_contact);
  const double initial_solid_area = total_solid_area(system.particles());
  double solid_area = initial_solid_area;
  const auto porosity = [&] { return 1.0 - solid_area / boundary.area(system); };

  RedfGrowth growth;
  growth.jam_stress = [&] { return mean_wall_stress(system, boundary); };
  growth.porosity = porosity;
  growth.grow = [&](double factor) {
    system.scale_particle_sizes(factor);
    solid_area *= factor * factor;
  };
  const RedfGrowthResult grown =
    grow_by_redf(system, s, growth, progress ? std::function<void(double)>([&](double f) { progress(0.8 * f); })
                                             : std::function<void(double)>());
  const std::uint64_t steps = grown.n_steps;

  // ---- equilibrium at the target stress with the material friction ----
  system.set_particle_law(material);
  servo_to_stress(system, boundary, s.target_stress);
  std::uint64_t settle_steps = 0;
  const std::uint64_t check_every = 200;
  for (;;)
    {
      boundary.update_loaded_lengths(system);
      system.step();
      ++settle_steps;
      if (settle_steps % check_every != 0)
        continue;
      const double error = stress_error(system, boundary, s.target_stress);
      if (error < s.stress_tolerance && unbalanced_force_ratio(system) < s.equilibrium_unbalanced_ratio)
        break;
      if (steps + settle_steps > s.max_steps)
        throw std::runtime_error("REDF: no equilibrium at the target stress after " + std::to_string(s.max_steps) +
                                 " steps (stress error " + std::to_string(error) + ")");
      if (progress)
        progress(0.8 + 0.2 * std::min(1.0, static_cast<double>(settle_steps) / 50000.0));
    }

  RedfResult result;
  result.porosity = porosity();
  result.mean_stress = mean_wall_stress(system, boundary);
  result.growth_friction_deg = grown.growth_friction_deg;
  result.size_scale = std::sqrt(solid_area / initial_solid_area);
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
  return result;
}
} // namespace

RedfStartingSizes redf_starting_sizes(const RedfSpec &s, double region_area, double region_narrowest_width,
                                      const std::string &region)
{
  check_spec(s);
  if (!(region_area > 0.0 && region_narrowest_width > 0.0))
    throw std::invalid_argument("REDF: " + region + " must have a positive size");
  // Final sizes: the relative sizes u_k scaled so the solids fill (1 - n) of the region.
  UniformRandom random(s.seed ^ 0x5eedULL);
  std::vector<double> u = s.size_distribution.relative_sizes(s.n_particles, random);
  double sum_u2 = 0.0;
  for (double x : u)
    sum_u2 += x * x;
  std::sort(u.begin(), u.end(), std::greater<double>()); // large first: easier random placement
  const double final_scale = std::sqrt((1.0 - s.target_porosity) * region_area / (unit_area(s) * sum_u2));
  // Start at a solid fraction of 0.45 (or less): random placement succeeds easily there.
  const double initial_fraction = std::min(0.45, 0.75 * (1.0 - s.target_porosity));
  const double initial_scale = final_scale * std::sqrt(initial_fraction / (1.0 - s.target_porosity));
  // A sample must be many particles across: refuse one whose largest particle would span more
  // than a fifth of the region's narrowest width.
  const double largest_extent = final_scale * u.front() * unit_extent(s);
  if (largest_extent > 0.2 * region_narrowest_width)
    {
      std::ostringstream message;
      message << "REDF: " << s.n_particles << " particles filling " << region << " at porosity "
              << s.target_porosity << " would be up to " << largest_extent << " m across, more than a fifth of "
              << region_narrowest_width << " m; use more particles or a larger box";
      throw std::invalid_argument(message.str());
    }
  for (double &x : u)
    x *= initial_scale;
  return RedfStartingSizes{std::move(u), largest_extent, final_scale / initial_scale};
}

void place_at_random(const RedfSpec &s, const std::vector<Vec2> &vertices, const std::vector<double> &radii,
                     std::uint64_t seed, ParticleSet &p)
{
  check_convex_polygon(vertices);
  UniformRandom random(seed);
  const std::size_t n_sides = vertices.size();
  // A disc is inside when it is at least its radius from every side's line (inward normals).
  std::vector<Vec2> inward(n_sides);
  double x_min = vertices[0].x(), x_max = x_min, y_min = vertices[0].y(), y_max = y_min;
  for (std::size_t k = 0; k < n_sides; ++k)
    {
      inward[k] = perp(vertices[(k + 1) % n_sides] - vertices[k]).normalized();
      x_min = std::min(x_min, vertices[k].x());
      x_max = std::max(x_max, vertices[k].x());
      y_min = std::min(y_min, vertices[k].y());
      y_max = std::max(y_max, vertices[k].y());
    }
  // Extent of a particle: for a cluster, the distance from its centre of mass to the far edge.
  double reach_max = 0.0, radius_max = 0.0, existing_radius_max = 0.0;
  for (double r : radii)
    {
      reach_max = std::max(reach_max, s.shape == ParticleShape::disc ? r : r * (1.0 + 2.0 * s.cluster_spacing));
      radius_max = std::max(radius_max, r);
    }
  for (double r : p.disc_radius)
    existing_radius_max = std::max(existing_radius_max, r);
  // Cells at least as wide as any two discs that could touch: neighbours are in adjacent cells.
  const double cell = std::max(2.0 * reach_max, radius_max + existing_radius_max);
  const std::size_t nx = static_cast<std::size_t>((x_max - x_min) / cell) + 1,
                    ny = static_cast<std::size_t>((y_max - y_min) / cell) + 1;
  std::vector<std::vector<std::uint32_t>> grid(nx * ny); // disc indices per cell
  // Cells clamp to the grid: a disc outside it lands in a border cell, which keeps every pair
  // closer than a cell in adjacent cells.
  const auto cell_of = [&](double x, double y) {
    const std::size_t cx = std::min(nx - 1, static_cast<std::size_t>(std::max(0.0, x - x_min) / cell));
    const std::size_t cy = std::min(ny - 1, static_cast<std::size_t>(std::max(0.0, y - y_min) / cell));
    return std::make_pair(cx, cy);
  };
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    if (p.disc_x[d] > x_min - cell && p.disc_x[d] < x_max + cell && p.disc_y[d] > y_min - cell &&
        p.disc_y[d] < y_max + cell)
      {
        const auto [gx, gy] = cell_of(p.disc_x[d], p.disc_y[d]);
        grid[gy * nx + gx].push_back(static_cast<std::uint32_t>(d));
      }
  p.reserve(p.n_bodies() + radii.size(), p.n_discs_total() + 2 * radii.size());
  constexpr int max_tries = 5000;
  for (std::size_t k = 0; k < radii.size(); ++k)
    {
      const double r = radii[k];
      bool placed = false;
      for (int attempt = 0; attempt < max_tries && !placed; ++attempt)
        {
          const double angle = random.uniform(0.0, 2.0 * pi);
          const double x = random.uniform(x_min, x_max), y = random.uniform(y_min, y_max);
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
              for (std::size_t side = 0; side < n_sides && fits; ++side)
                if (inward[side].dot(Vec2(cx, cy) - vertices[side]) < cr)
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
}

RedfGrowthResult grow_by_redf(DemSystem &system, const RedfSpec &s, const RedfGrowth &growing,
                              const std::function<void(double)> &progress)
{
  const auto &porosity = growing.porosity;
  // ---- growth with decrease of friction ----
  // Grow while the assembly is loose; once it jams (mean wall stress above the target) above
  // the target porosity, lower the growth friction so the grains rearrange, then grow again.
  // Stop when it is jammed at the target porosity.
  // Rates in time, not per step, so that the sample does not depend on the time step; tau =
  // sqrt(m / kn) is the contact time of the lightest body at its starting size. Relative radius
  // growth: while the assembly is loose (jam stress below a tenth of the target) few grains
  // touch, and growth can be fast, 8e-4 per tau. Once it carries stress, 2e-4 per tau: a step
  // lifts the contact overlaps by about growth x kn / sigma of their value, so the stress
  // overshoots the target and the grains rearrange, which is what densifies the jammed assembly
  // (and, at each drop, lets the friction fall). A quarter of that rate took 2.4 times as many
  // steps to the same porosity and growth friction (4,000 clusters, 10 kPa: 188,000 against
  // 78,000; bench/RESULTS.md), for a final stress closer to the target before the servo stage
  // (10.6 against 13 kPa at 10 kPa). (Rates set with dt = tau / 2, i.e. 4e-4 and 1e-4 per step.)
  //
  // The friction is lowered after every 2000 tau that the assembly has spent jammed at it, in
  // all: the jammed steps are counted across the growth steps in between. Once jammed, the wall
  // stress hovers just above the target and dips below it for a step now and then, as the grains
  // creep; each dip is one growth step. Counting only uninterrupted jammed spells (500 tau, as
  // before) let such dips reset the count again and again, so the friction fell every 13,000
  // steps or so instead of every 1,400 and the sample crept to its porosity at each friction:
  // 1,000 clusters, seeds 1-3, 141,000 / 124,000 / 135,000 steps, final growth friction 4.3 /
  // 4.3 / 4.8 degrees, coordination number 4.90 / 4.85 / 4.90. Counted in all over 2000 tau:
  // 76,000 / 77,000 / 68,000 steps, 4.3 / 3.9 / 4.8 degrees, 4.81 / 4.90 / 4.82, the same
  // porosity (bench/RESULTS.md). Over 500 tau the friction falls faster than the assembly
  // densifies (59,000 steps, 3.9 degrees, coordination 4.73 on seed 1).
  const double tau = lightest_contact_time(system);
  const double loose_growth_per_step = 8e-4 * system.time_step() / tau;
  const double loaded_growth_per_step = 2e-4 * system.time_step() / tau;
  const auto growth_per_step = [&] {
    return growing.jam_stress() < 0.1 * s.target_stress ? loose_growth_per_step : loaded_growth_per_step;
  };
  const std::uint64_t jammed_steps_per_friction_drop =
    std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(2000.0 * tau / system.time_step())));
  double friction_deg = s.initial_growth_friction_deg >= 0.0 ? s.initial_growth_friction_deg
                                                            : s.particle_contact.friction_angle_deg;
  const auto use_friction = [&](double degrees) {
    ContactParameters growth = s.particle_contact;
    growth.friction_angle_deg = degrees;
    system.set_particle_law(LinearContactLaw(growth));
  };
  use_friction(friction_deg);
  std::uint64_t steps = 0, steps_jammed = 0; // steps_jammed: at this friction, in all
  const double start_porosity = porosity();
  const double upper = s.target_porosity + 0.5 * s.porosity_tolerance;
  for (;;)
    {
      const bool jammed = growing.jam_stress() > s.target_stress;
      const double n = porosity();
      // Target porosity reached: the assembly is jammed or close to it (the friction is lowered
      // only while it is jammed above the target), so the servo stage below compacts it little.
      if (n <= upper)
        break;
      if (steps++ > s.max_steps)
        throw std::runtime_error("REDF: no convergence after " + std::to_string(s.max_steps) +
                                 " steps (porosity " + std::to_string(n) + ")");
      if (!jammed)
        growing.grow(1.0 + growth_per_step());
      else if (++steps_jammed % jammed_steps_per_friction_drop == 0 && unbalanced_force_ratio(system) < 0.05)
        {
          // Jammed above the target porosity for long at this friction, and near equilibrium:
          // lower the friction so the grains can rearrange into a denser state.
          if (friction_deg <= 0.0)
            {
              std::ostringstream message;
              message << "REDF: the target porosity " << s.target_porosity << " cannot be reached: the assembly "
                      << "jams at porosity " << n << " even without friction (stress "
                      << growing.jam_stress() << " Pa); choose a larger porosity or a lower stress";
              throw std::runtime_error(message.str());
            }
          friction_deg = friction_deg > 0.5 ? redf_friction_drop * friction_deg : 0.0;
          use_friction(friction_deg);
          steps_jammed = 0;
        }
      system.step();
      if (progress && steps % 1000 == 0)
        progress(std::clamp((start_porosity - n) / (start_porosity - s.target_porosity), 0.0, 1.0));
    }
  return RedfGrowthResult{friction_deg, steps};
}

RedfSample make_redf_sample(const RedfSpec &s, const std::function<void(double)> &progress)
{
  if (!(s.width > 0.0 && s.height > 0.0))
    throw std::invalid_argument("REDF: the box must have a positive size");
  std::ostringstream region;
  region << "a " << s.width << " m x " << s.height << " m box";
  const std::vector<double> radii =
    redf_starting_sizes(s, s.width * s.height, std::min(s.width, s.height), region.str()).radii;
  ParticleSet particles;
  place_at_random(s, {Vec2(0.0, 0.0), Vec2(s.width, 0.0), Vec2(s.width, s.height), Vec2(0.0, s.height)}, radii,
                  s.seed, particles);
  // The time step is set for the initial (smallest) sizes' masses: sqrt(m/k) grows with size,
  // so it stays safe throughout the growth.
  DemSystem system(std::move(particles), LinearContactLaw(s.particle_contact), redf_settings(s));
  const double overhang = 0.1 * std::max(s.width, s.height);
  const RectangularBox box = RectangularBox::add_to(system, 0.0, 0.0, s.width, s.height,
                                                    LinearContactLaw(s.wall_contact), overhang);
  const RedfResult result = grow_and_settle(s, system, box, progress);
  return RedfSample{std::move(system), box, result};
}

RedfPolygonSample make_redf_sample_in_polygon(const RedfSpec &s, const std::vector<Vec2> &vertices,
                                              const std::function<void(double)> &progress)
{
  check_convex_polygon(vertices);
  const double width = narrowest_width(vertices);
  std::ostringstream region;
  region << "the polygon of area " << polygon_area(vertices) << " m^2 (narrowest width " << width << " m)";
  const std::vector<double> radii = redf_starting_sizes(s, polygon_area(vertices), width, region.str()).radii;
  ParticleSet particles;
  place_at_random(s, vertices, radii, s.seed, particles);
  DemSystem system(std::move(particles), LinearContactLaw(s.particle_contact), redf_settings(s));
  double extent = 0.0;
  for (const Vec2 &a : vertices)
    for (const Vec2 &b : vertices)
      extent = std::max(extent, (a - b).norm());
  const WallPolygon boundary =
    WallPolygon::add_to(system, vertices, LinearContactLaw(s.wall_contact), 0.1 * extent);
  const RedfResult result = grow_and_settle(s, system, boundary, progress);
  return RedfPolygonSample{std::move(system), boundary, result};
}
} // namespace geohybrid::dem
