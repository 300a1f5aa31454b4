#include "particles.h"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

namespace geohybrid::dem
{
namespace
{
/// Circular segment of a disc of radius R cut by a chord at distance h from the centre
/// (0 <= h <= R): its area, the distance of its centroid from the centre, and its polar moment
/// about the centre. Sector minus triangle, half-angle a = acos(h/R):
///   A = R^2 (a - sin a cos a),  x_c = 2 R sin^3 a / (3 (a - sin a cos a)),
///   J = R^4 a / 2 - h^4 tan a (1 + tan^2 a / 3) / 2.
struct Segment
{
  double area, centroid, polar_moment_about_centre;
};
Segment circular_segment(double R, double h)
{
  h             = std::clamp(h, -R, R);
  const double a = std::acos(h / R);
  const double s = std::sin(a), c = std::cos(a);
  const double area = R * R * (a - s * c);
  const double centroid = area > 0.0 ? 2.0 * R * s * s * s / (3.0 * (a - s * c)) : h;
  // Triangle part: h^4 tan a (1 + tan^2 a / 3) / 2 written without tan to survive a = pi/2.
  const double triangle = 0.5 * h * h * h * h * (s / c) * (1.0 + (s * s) / (3.0 * c * c));
  const double J = 0.5 * R * R * R * R * a - (std::abs(c) > 1e-15 ? triangle : 0.0);
  return {area, centroid, J};
}
} // namespace

TwoDiscGeometry two_disc_geometry(double r1, double r2, double d)
{
  if (r1 <= 0.0 || r2 <= 0.0 || d < 0.0)
    throw std::invalid_argument("two-disc cluster: radii must be positive and spacing non-negative");
  // Disc 1 at 0, disc 2 at d on the x axis.
  double A = pi * (r1 * r1 + r2 * r2);
  double Sx = pi * r2 * r2 * d;                       // first moment about disc 1 centre
  double J0 = 0.5 * pi * (r1 * r1 * r1 * r1 + r2 * r2 * r2 * r2) + pi * r2 * r2 * d * d; // about disc 1
  if (d < r1 + r2)
    {
      if (d + std::min(r1, r2) <= std::max(r1, r2))
        throw std::invalid_argument("two-disc cluster: one disc lies inside the other");
      // The lens is the segment of disc 1 beyond the chord at x = a1 plus the segment of disc 2
      // beyond the chord at distance a2 = d - a1 from its own centre.
      const double a1 = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
      const double a2 = d - a1;
      const Segment s1 = circular_segment(r1, a1); // centroid at +x from disc 1
      const Segment s2 = circular_segment(r2, a2); // centroid at -x from disc 2
      const double lens_area = s1.area + s2.area;
      const double lens_Sx   = s1.area * s1.centroid + s2.area * (d - s2.centroid);
      // Segment 2's polar moment moved from disc 2's centre to disc 1's centre (parallel axis,
      // through the segment centroid).
      const double s2_about_own_centroid = s2.polar_moment_about_centre - s2.area * s2.centroid * s2.centroid;
      const double s2_about_disc1 = s2_about_own_centroid + s2.area * (d - s2.centroid) * (d - s2.centroid);
      const double lens_J = s1.polar_moment_about_centre + s2_about_disc1;
      A -= lens_area;
      Sx -= lens_Sx;
      J0 -= lens_J;
    }
  const double xc = Sx / A;
  return {A, xc, J0 - A * xc * xc};
}

void ParticleSet::reserve(std::size_t nb, std::size_t nd)
{
  for (auto *v : {&x, &y, &rotation, &vx, &vy, &omega, &fx, &fy, &torque, &mass, &inertia,
                  &inverse_mass, &inverse_inertia})
    v->reserve(nb);
  body_id.reserve(nb);
  first_disc.reserve(nb);
  n_discs.reserve(nb);
  for (auto *v : {&disc_radius, &disc_offset_x, &disc_offset_y, &disc_x, &disc_y})
    v->reserve(nd);
  disc_body.reserve(nd);
}

namespace
{
std::size_t push_body(ParticleSet &p, const Vec2 &c, double angle, double m, double I, std::int64_t id)
{
  const std::size_t b = p.x.size();
  p.body_id.push_back(id >= 0 ? id : static_cast<std::int64_t>(b));
  p.x.push_back(c.x());
  p.y.push_back(c.y());
  p.rotation.push_back(angle);
  for (auto *v : {&p.vx, &p.vy, &p.omega, &p.fx, &p.fy, &p.torque})
    v->push_back(0.0);
  p.mass.push_back(m);
  p.inertia.push_back(I);
  p.inverse_mass.push_back(1.0 / m);
  p.inverse_inertia.push_back(1.0 / I);
  p.first_disc.push_back(static_cast<std::uint32_t>(p.disc_radius.size()));
  p.n_discs.push_back(0);
  return b;
}
void push_disc(ParticleSet &p, std::size_t b, double r, const Vec2 &offset)
{
  p.disc_body.push_back(static_cast<std::uint32_t>(b));
  p.disc_radius.push_back(r);
  p.disc_offset_x.push_back(offset.x());
  p.disc_offset_y.push_back(offset.y());
  const double c = std::cos(p.rotation[b]), s = std::sin(p.rotation[b]);
  p.disc_x.push_back(p.x[b] + c * offset.x() - s * offset.y());
  p.disc_y.push_back(p.y[b] + s * offset.x() + c * offset.y());
  ++p.n_discs[b];
}
} // namespace

std::size_t ParticleSet::add_disc(const Vec2 &centre, double radius, double density, std::int64_t id)
{
  if (!(radius > 0.0) || !(density > 0.0))
    throw std::invalid_argument("disc: radius and density must be positive");
  const double m = density * pi * radius * radius;
  const std::size_t b = push_body(*this, centre, 0.0, m, 0.5 * m * radius * radius, id);
  push_disc(*this, b, radius, Vec2::Zero());
  return b;
}

std::size_t ParticleSet::add_two_disc_cluster(const Vec2 &com, double r_large, double r_small,
                                              double spacing, double angle, double density,
                                              std::int64_t id)
{
  if (!(density > 0.0))
    throw std::invalid_argument("cluster: density must be positive");
  const TwoDiscGeometry g = two_disc_geometry(r_large, r_small, spacing);
  const std::size_t b = push_body(*this, com, angle, density * g.area, density * g.polar_moment, id);
  push_disc(*this, b, r_large, Vec2(-g.centroid_from_large, 0.0));
  push_disc(*this, b, r_small, Vec2(spacing - g.centroid_from_large, 0.0));
  return b;
}

void ParticleSet::scale_sizes(double factor, std::size_t first_body)
{
  const double f2 = factor * factor, f4 = f2 * f2;
  for (std::size_t b = first_body; b < n_bodies(); ++b)
    {
      mass[b] *= f2;
      inertia[b] *= f4;
      if (inverse_mass[b] != 0.0)
        {
          inverse_mass[b] = 1.0 / mass[b];
          inverse_inertia[b] = 1.0 / inertia[b];
        }
      for (std::uint32_t d = first_disc[b]; d < first_disc[b] + n_discs[b]; ++d)
        {
          disc_radius[d] *= factor;
          disc_offset_x[d] *= factor;
          disc_offset_y[d] *= factor;
        }
      place_discs(b, nullptr, nullptr);
    }
}

void ParticleSet::fix_body(std::size_t b)
{
  inverse_mass[b] = 0.0;
  inverse_inertia[b] = 0.0;
  vx[b] = vy[b] = omega[b] = 0.0;
}

double ParticleSet::update_disc_positions(int n_threads, const SoaVector<double> *reference_x,
                                          const SoaVector<double> *reference_y)
{
  const std::size_t nb = x.size(), nd = disc_radius.size();
  const bool measure = reference_x && reference_y && reference_x->size() == nd && reference_y->size() == nd;
  const double *reference_x_data = measure ? reference_x->data() : nullptr;
  const double *reference_y_data = measure ? reference_y->data() : nullptr;
  double max_move2 = 0.0;
#pragma omp parallel for schedule(static) num_threads(n_threads) reduction(max : max_move2)
  for (std::size_t b = 0; b < nb; ++b)
    max_move2 = std::max(max_move2, place_discs(b, reference_x_data, reference_y_data));
  return max_move2;
}

bool ParticleSet::single_centred_discs() const
{
  if (n_discs_total() != n_bodies())
    return false;
  for (std::size_t b = 0; b < n_bodies(); ++b)
    if (first_disc[b] != b || n_discs[b] != 1 || disc_offset_x[b] != 0.0 || disc_offset_y[b] != 0.0)
      return false;
  return true;
}

double ParticleSet::body_area(std::size_t b) const
{
  const std::uint32_t d0 = first_disc[b];
  if (n_discs[b] == 1)
    return pi * disc_radius[d0] * disc_radius[d0];
  const double dx = disc_offset_x[d0 + 1] - disc_offset_x[d0];
  const double dy = disc_offset_y[d0 + 1] - disc_offset_y[d0];
  return two_disc_geometry(disc_radius[d0], disc_radius[d0 + 1], std::hypot(dx, dy)).area;
}

namespace
{
/// Interleaves the bits of two 32-bit cell indices: x in the even bits, y in the odd ones.
std::uint64_t morton_key(std::uint32_t ix, std::uint32_t iy)
{
  const auto spread = [](std::uint64_t v) {
    v &= 0xffffffffu;
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
  };
  return spread(ix) | (spread(iy) << 1);
}
} // namespace

ParticleSet spatially_sorted(const ParticleSet &p, double cell_size)
{
  if (!(cell_size > 0.0))
    throw std::invalid_argument("spatially_sorted: the cell size must be positive");
  const std::size_t nb = p.n_bodies();
  if (nb == 0)
    return p;
  const double x_min = *std::min_element(p.x.begin(), p.x.end());
  const double y_min = *std::min_element(p.y.begin(), p.y.end());
  const auto cell = [cell_size](double offset) {
    return static_cast<std::uint32_t>(std::min(offset / cell_size, 4.0e9));
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(nb);
  for (std::size_t b = 0; b < nb; ++b)
    order[b] = {morton_key(cell(p.x[b] - x_min), cell(p.y[b] - y_min)), static_cast<std::uint32_t>(b)};
  std::sort(order.begin(), order.end()); // ties: by the original index

  std::vector<std::uint32_t> bodies(nb);
  for (std::size_t k = 0; k < nb; ++k)
    bodies[k] = order[k].second;
  return bodies_of(p, bodies);
}

ParticleSet bodies_of(const ParticleSet &p, const std::vector<std::uint32_t> &bodies)
{
  std::size_t n_discs = 0;
  for (const std::uint32_t b : bodies)
    n_discs += p.n_discs[b];
  ParticleSet s;
  s.reserve(bodies.size(), n_discs);
  for (const std::uint32_t b : bodies)
    {
      s.body_id.push_back(p.body_id[b]);
      for (auto [to, from] : {std::pair{&s.x, &p.x}, {&s.y, &p.y}, {&s.rotation, &p.rotation}, {&s.vx, &p.vx},
                              {&s.vy, &p.vy}, {&s.omega, &p.omega}, {&s.fx, &p.fx}, {&s.fy, &p.fy},
                              {&s.torque, &p.torque}, {&s.mass, &p.mass}, {&s.inertia, &p.inertia},
                              {&s.inverse_mass, &p.inverse_mass}, {&s.inverse_inertia, &p.inverse_inertia}})
        to->push_back((*from)[b]);
      const std::size_t nb_new = s.first_disc.size();
      s.first_disc.push_back(static_cast<std::uint32_t>(s.disc_radius.size()));
      s.n_discs.push_back(p.n_discs[b]);
      for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
        {
          s.disc_body.push_back(static_cast<std::uint32_t>(nb_new));
          for (auto [to, from] : {std::pair{&s.disc_radius, &p.disc_radius}, {&s.disc_offset_x, &p.disc_offset_x},
                                  {&s.disc_offset_y, &p.disc_offset_y}, {&s.disc_x, &p.disc_x},
                                  {&s.disc_y, &p.disc_y}})
            to->push_back((*from)[d]);
        }
    }
  return s;
}
} // namespace geohybrid::dem
