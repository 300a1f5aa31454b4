// The patch test along the lattice's rows (coupling_benchmarks.h): the layout in which the energy
// weights are exact, and the lattice's own stress for the continuum.
#include "coupling_benchmarks.h"

#include "apps/coupling_benchmarks/hexagonal_lattice.h"
#include "dem/measurements.h"

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <cmath>
#include <algorithm>
#include <map>
#include <string>
#include <stdexcept>

namespace geohybrid::coupling::benchmarks
{
namespace
{
/// x -> (I + eps) x.
Vec2 strained(const PlaneStrain &eps, const Vec2 &x)
{
  return Vec2(x.x() + eps.xx * x.x() + eps.xy * x.y(), x.y() + eps.xy * x.x() + eps.yy * x.y());
}

double norm(const fem::StressTensor &s)
{
  return std::sqrt(s[0][0] * s[0][0] + s[1][1] * s[1][1] + 2.0 * s[0][1] * s[0][1]);
}
} // namespace

fem::StressTensor lattice_stress(const dem::DemSystem &lattice, std::size_t body, const PatchGeometry &g,
                                 const PlaneStrain &eps, const Vec2 &normal)
{
  const dem::ParticleSet &p = lattice.particles();
  // A window round the disc's centre holding no other centre: love_weber_stress sums the disc's
  // contacts and divides by the window's area, which is replaced by the disc's strained cell.
  const double half = 0.25 * g.spacing();
  const dem::Region window{p.x[body] - half, p.y[body] - half, p.x[body] + half, p.y[body] + half};
  const double cell = g.spacing() * g.row_height() * ((1.0 + eps.xx) * (1.0 + eps.yy) - eps.xy * eps.xy);
  const std::array<double, 3> symmetric = dem::love_weber_stress(lattice, window);
  const double scale = window.area() / cell;
  // love_weber_stress keeps the symmetric part of (1/A) sum f (x) lever; the skew part is the
  // disc's moment over its cell: the moment about the centre, sum (l_x f_y - l_y f_x), is
  // A (sigma_yx - sigma_xy).
  const double skew = -0.5 * p.torque[body] / cell; // (sigma_xy - sigma_yx) / 2
  const double sxx = symmetric[0] * scale, syy = symmetric[1] * scale;
  const double sxy = symmetric[2] * scale + skew, syx = symmetric[2] * scale - skew; // f_x l_y, f_y l_x
  // The traction t = sigma n on the band's planes, and the symmetric stress with that traction:
  // sigma = t_n n n + t_t (n t + t n) + sigma_tt t t, sigma_tt from the lattice's t . sigma t.
  const Vec2 n = normal / normal.norm(), t(-n.y(), n.x());
  const Vec2 traction(sxx * n.x() + sxy * n.y(), syx * n.x() + syy * n.y());
  const double t_n = traction.dot(n), t_t = traction.dot(t);
  const double s_tt = t.x() * (sxx * t.x() + sxy * t.y()) + t.y() * (syx * t.x() + syy * t.y());
  fem::StressTensor stress;
  stress[0][0] = t_n * n.x() * n.x() + 2.0 * t_t * n.x() * t.x() + s_tt * t.x() * t.x();
  stress[1][1] = t_n * n.y() * n.y() + 2.0 * t_t * n.y() * t.y() + s_tt * t.y() * t.y();
  stress[0][1] = t_n * n.x() * n.y() + t_t * (n.x() * t.y() + t.x() * n.y()) + s_tt * t.x() * t.y();
  stress[2][2] = matching_soil(g).elasticity().poisson_ratio() * (stress[0][0] + stress[1][1]);
  return stress;
}

RowPatchLayout commensurate_row_patch(double band_width, double cell_size)
{
  if (!(band_width > 0.0) || !std::isfinite(band_width))
    throw std::invalid_argument("row patch: 'band width' must be positive, not " + std::to_string(band_width));
  if (!(cell_size > 0.0) || !std::isfinite(cell_size))
    throw std::invalid_argument("row patch: 'cell size' must be positive, not " + std::to_string(cell_size));
  const double h = std::sqrt(3.0) / 2.0;
  const long band_rows = 2 * std::max(1L, std::lround(band_width / (2.0 * h)));
  const long cell_columns = std::max(1L, std::lround(cell_size));
  RowPatchLayout layout;
  layout.band_start = 6.0 * h;
  layout.band_width = band_rows * h;
  layout.mesh_top = layout.band_start + layout.band_width + 8.0 * h;
  layout.cells_y = static_cast<unsigned int>(band_rows / 2 + 4);
  layout.mesh_left = -0.5;
  layout.cells_x = static_cast<unsigned int>((16 + cell_columns - 1) / cell_columns);
  layout.mesh_right = layout.mesh_left + layout.cells_x * cell_columns;
  return layout;
}

RowPatchTestResult row_patch_test(const CouplingMethod &method, const PlaneStrain &eps, PatchContinuumStress stress,
                                  const PatchGeometry &g, const RowPatchLayout &layout)
{
  if (!has_band(method))
    throw std::invalid_argument("row patch test: the non-overlapping interface has no band (its patch test is "
                                "interface_patch_test)");
  const double d = g.spacing(), h = g.row_height();
  const unsigned int n_rows = static_cast<unsigned int>(std::floor((layout.band_start + layout.band_width + 1.0) * d / h)) + 1;
  dem::ParticleSet discs;
  for (unsigned int j = 0; j < n_rows; ++j)
    for (unsigned int i = 0; i < layout.columns; ++i)
      discs.add_disc(Vec2(i * d + (j % 2) * 0.5 * d, j * h), g.radius, g.density, lattice_id(i, j));
  const auto particles = strained_lattice(std::move(discs), g, eps);
  const dem::ParticleSet &p = particles->particles();

  PatchMesh mesh(MPI_COMM_WORLD);
  dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {layout.cells_x, layout.cells_y},
                                                    dealii::Point<2>(layout.mesh_left * d, layout.band_start * d),
                                                    dealii::Point<2>(layout.mesh_right * d, layout.mesh_top * d), true);
  // The band in the configuration the continuum starts from: for the lattice's stress, the
  // strained one (the mesh and the band strained with the discs: the same layout, affinely
  // mapped); for the closed-form moduli, the unstrained one, strained by u = eps x.
  Vec2 origin(0.0, layout.band_start * d), normal(0.0, 1.0);
  double width = layout.band_width * d;
  if (stress == PatchContinuumStress::lattice)
    {
      dealii::GridTools::transform(
        [&](const dealii::Point<2> &x) {
          const Vec2 y = strained(eps, Vec2(x[0], x[1]));
          return dealii::Point<2>(y.x(), y.y());
        },
        mesh);
      // The band's normal is F^-T e_y, normalised; s scales by 1 / |F^-T e_y| (so s / w is the
      // unstrained one).
      const double det = (1.0 + eps.xx) * (1.0 + eps.yy) - eps.xy * eps.xy;
      const Vec2 cotangent(-eps.xy / det, (1.0 + eps.xx) / det);
      origin = strained(eps, origin);
      normal = cotangent / cotangent.norm();
      width /= cotangent.norm();
    }
  // The stress both models carry: the lattice's, from a disc in the middle of the particle-only rows.
  const std::size_t middle = (n_rows / 4) * layout.columns + layout.columns / 2;
  const fem::StressTensor carried = lattice_stress(*particles, middle, g, eps, normal);
  fem::ExplicitSolver continuum(mesh, matching_soil(g), fem::BoundaryConditions{}, patch_continuum_settings(g));
  if (stress == PatchContinuumStress::lattice)
    continuum.set_initial_stress([&](const dealii::Point<2> &) { return carried; }, "the strained lattice's stress");
  else
    strain_continuum(continuum, g, eps);
  // The band's continuum edge lies on a row: that row's discs have a weight of round-off and
  // are driven (a tied disc of no mass would have no stable step).
  const CoupledStepper stepper(*particles, continuum, OverlapBand(origin, normal, width), method,
                               BandTreatment{0.01, false});

  // Measured: discs and nodes whose neighbourhood stays in the lattice (a node's cell width and
  // half a spacing from its ends, a disc one spacing), above its two free bottom rows and below
  // the mesh's free top. Judged in the unstrained coordinates.
  const double x_first = 0.0, x_last = (layout.columns - 0.5) * d;
  const double cell_x = (layout.mesh_right - layout.mesh_left) * d / layout.cells_x;
  const double cell_y = (layout.mesh_top - layout.band_start) * d / layout.cells_y;
  const auto unstrained = [&](double x, double y) {
    if (stress == PatchContinuumStress::matching_moduli)
      return Vec2(x, y);
    const double det = (1.0 + eps.xx) * (1.0 + eps.yy) - eps.xy * eps.xy;
    return Vec2(((1.0 + eps.yy) * x - eps.xy * y) / det, (-eps.xy * x + (1.0 + eps.xx) * y) / det);
  };
  const auto interior_disc = [&](std::size_t b) {
    const Vec2 X = unstrained(p.x[b], p.y[b]);
    return X.x() > x_first + 0.9 * d && X.x() < x_last - 0.9 * d && X.y() > 1.5 * h;
  };
  const auto interior_node = [&](const dealii::Point<2> &x) {
    const Vec2 X = unstrained(x[0], x[1]);
    return X.x() > x_first + cell_x + 0.4 * d && X.x() < x_last - cell_x - 0.4 * d &&
           X.y() < layout.mesh_top * d - 0.5 * cell_y;
  };
  const double stress_norm = norm(carried);
  const BandParticles &band = stepper.band_particles();
  const GhostForceMeasure measure =
    measure_ghost_forces(p, continuum, band, stress_norm, d, cell_y, interior_disc, interior_node);
  RowPatchTestResult result;
  result.ghost = measure.ghost;
  result.n_discs = measure.n_discs;
  result.n_nodes = measure.n_nodes;
  result.n_tied = band.size();
  result.n_driven = band.driven_body.size();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (interior_disc(b) && p.inverse_mass[b] > 0.0)
      result.disc_moments = std::max(result.disc_moments, std::abs(p.torque[b]) / (stress_norm * d * d));
  return result;
}
} // namespace geohybrid::coupling::benchmarks
