#include "slab_porosity.h"

#include <algorithm>
#include <cmath>

namespace geohybrid::dem
{
namespace
{
/// Area of the part of a disc (radius r, centre height yc) below the line y = t.
double disc_area_below(double r, double yc, double t)
{
  const double h = std::clamp(t - yc, -r, r);
  return 0.5 * pi * r * r + h * std::sqrt(std::max(0.0, r * r - h * h)) + r * r * std::asin(h / r);
}
} // namespace

double share_in_slab(const ParticleSet &p, std::size_t b, double y0, double y1)
{
  double inside = 0.0, whole = 0.0;
  for (std::uint32_t d = p.first_disc[b]; d < p.first_disc[b] + p.n_discs[b]; ++d)
    {
      const double r = p.disc_radius[d], y = p.disc_y[d], area = pi * r * r;
      whole += area;
      if (y - r >= y0 && y + r <= y1)
        inside += area;
      else if (y + r > y0 && y - r < y1)
        inside += disc_area_below(r, y, y1) - disc_area_below(r, y, y0);
    }
  return inside / whole;
}

// A sheet is not soil: the slab's porosity is that of the space the grains can fill (a 3.2 mm
// sheet in a 50 mm lift is 6 % of its area, which the grains would otherwise have to make up by
// packing denser).
double sheet_area_in_slab(const std::vector<SparSheet> &sheets, double x_min, double x_max, double y0, double y1)
{
  constexpr int pieces = 32; // per segment: the band's cut at a level is exact for a flat piece
  double area = 0.0;
  for (const SparSheet &sheet : sheets)
    for (std::size_t k = 0; k < sheet.n_segments(); ++k)
      {
        const Vec2 a = sheet.node(k), b = sheet.node(k + 1);
        const double length = (b - a).norm();
        if (!(length > 0.0))
          continue;
        // Half the band's vertical extent across the thickness: t/2 |cos| of the segment's slope.
        const double half = 0.5 * sheet.thickness() * std::abs(b.x() - a.x()) / length;
        for (int i = 0; i < pieces; ++i)
          {
            const Vec2 c = a + (b - a) * ((i + 0.5) / pieces);
            if (c.x() < x_min || c.x() > x_max)
              continue;
            const double inside = half > 0.0 ? std::max(0.0, std::min(y1, c.y() + half) - std::max(y0, c.y() - half)) / (2.0 * half)
                                             : (c.y() >= y0 && c.y() <= y1 ? 1.0 : 0.0);
            area += inside * sheet.thickness() * length / pieces;
          }
      }
  return area;
}

double slab_porosity(const ParticleSet &p, double x_min, double x_max, double y_bottom, double y_top)
{
  double solid = 0.0;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      const double share = share_in_slab(p, b, y_bottom, y_top);
      if (share > 0.0)
        solid += share * p.body_area(b);
    }
  return 1.0 - solid / ((x_max - x_min) * (y_top - y_bottom));
}

double slab_porosity_beside_sheets(const ParticleSet &particles, const std::vector<SparSheet> &sheets, double width,
                                   double y_bottom, double y_top)
{
  double porosity = slab_porosity(particles, 0.0, width, y_bottom, y_top);
  const double sheet_area = sheet_area_in_slab(sheets, 0.0, width, y_bottom, y_top);
  if (sheet_area > 0.0)
    {
      const double area = width * (y_top - y_bottom);
      porosity = 1.0 - (1.0 - porosity) * area / (area - sheet_area);
    }
  return porosity;
}
} // namespace geohybrid::dem
