#include "hybrid_continuum.h"

#include "coupling/continuum_region.h"
#include "coupling/hybrid_pullout.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

namespace geohybrid::coupling
{
namespace
{
/// Mesh steps over [a, b]: `cell` [m] at most, growing by `growth` per cell away from the fine end(s)
/// up to `far_cell`, scaled to fit exactly. `fine_at_start`, `fine_at_end`: where the band is.
std::vector<double> graded_steps(double a, double b, double cell, double far_cell, bool fine_at_start, bool fine_at_end)
{
  const double length = b - a;
  if (length <= 1e-12)
    return {};
  constexpr double growth = 1.3;
  std::vector<double> steps;
  if (!fine_at_start && !fine_at_end)
    {
      const auto n = static_cast<unsigned int>(std::ceil(length / far_cell - 1e-9));
      return std::vector<double>(n, length / n);
    }
  if (fine_at_start && fine_at_end)
    {
      std::vector<double> half = graded_steps(a, a + 0.5 * length, cell, far_cell, true, false);
      steps = half;
      steps.insert(steps.end(), half.rbegin(), half.rend());
      return steps;
    }
  // From the fine end: cell, cell g, cell g^2, ... capped at far_cell, until the interval is
  // covered; then all scaled down to fit (none grows past its cap).
  double covered = 0.0, h = cell;
  while (covered < length - 1e-12)
    {
      steps.push_back(h);
      covered += h;
      h = std::min(far_cell, h * growth);
    }
  for (double &step : steps)
    step *= length / covered;
  if (fine_at_end)
    std::reverse(steps.begin(), steps.end());
  return steps;
}
} // namespace

std::unique_ptr<dealii::parallel::distributed::Triangulation<fem::dim>>
hybrid_continuum_mesh(const ParticleBox &box, const dem::PullOutGeometry &tank, const DemCore &core,
                      const OverlapBand &band, double band_width, double cell, double far_cell)
{
  const double tank_x0 = -box.x0, tank_x1 = tank.tank_length - box.x0;
  const double tank_y0 = -box.y0, tank_y1 = tank.fill_height - box.y0;
  std::vector<double> x_steps, y_steps;
  const auto append = [](std::vector<double> &to, const std::vector<double> &steps) {
    to.insert(to.end(), steps.begin(), steps.end());
  };
  // Uniform cells over the band and the core (each interval divided evenly, so that the band's
  // and the core's edges lie on mesh lines), graded outside them.
  const auto uniform = [&](std::vector<double> &to, const std::vector<double> &breakpoints) {
    for (std::size_t k = 1; k < breakpoints.size(); ++k)
      append(to, graded_steps(breakpoints[k - 1], breakpoints[k], cell, cell, false, false));
  };
  if (box.left_shared)
    {
      append(x_steps, graded_steps(tank_x0, core.x0 - band_width, cell, far_cell, false, true));
      uniform(x_steps, {core.x0 - band_width, core.x0, tank_x1});
    }
  else
    uniform(x_steps, {tank_x0, tank_x1});
  std::vector<double> core_lines;
  if (box.bottom_shared)
    {
      append(y_steps, graded_steps(tank_y0, core.y0 - band_width, cell, far_cell, false, true));
      core_lines = {core.y0 - band_width, core.y0};
    }
  else
    core_lines = {tank_y0};
  if (box.top_shared)
    core_lines.insert(core_lines.end(), {core.y1, core.y1 + band_width});
  else
    core_lines.push_back(tank_y1);
  uniform(y_steps, core_lines);
  if (box.top_shared)
    append(y_steps, graded_steps(core.y1 + band_width, tank_y1, cell, far_cell, true, false));
  dealii::Triangulation<fem::dim> tank_mesh;
  dealii::GridGenerator::subdivided_hyper_rectangle(tank_mesh, {x_steps, y_steps},
                                                    dealii::Point<fem::dim>(tank_x0, tank_y0),
                                                    dealii::Point<fem::dim>(tank_x1, tank_y1), true);
  // One rank: the continuum on MPI_COMM_SELF (several runs may share an MPI job, one a rank).
  return continuum_region_mesh(tank_mesh, band, MPI_COMM_SELF);
}

std::unique_ptr<fem::ExplicitSolver>
hybrid_continuum_solver(const dealii::parallel::distributed::Triangulation<fem::dim> &mesh,
                        const HybridPullOutSpec &spec, const ParticleBox &box)
{
  // The continuum: smooth back and front walls (ids 0 and 1 of the colorized rectangle), fixed
  // base (2), free top (3); only the walls it reaches.
  std::set<dealii::types::boundary_id> ids;
  for (const auto &face : mesh.active_face_iterators())
    if (face->at_boundary())
      ids.insert(face->boundary_id());
  fem::BoundaryConditions conditions;
  if (ids.count(0))
    conditions.displacements.push_back({0, true, false, nullptr});
  if (ids.count(1))
    conditions.displacements.push_back({1, true, false, nullptr});
  if (ids.count(2))
    conditions.displacements.push_back({2, true, true, nullptr});
  const double gravity = spec.tank.filling.gravity;
  fem::ExplicitSettings settings;
  settings.element_degree = 1;
  settings.density = spec.tank.unit_weight / gravity;
  settings.gravity[1] = -gravity;
  settings.damping.local = spec.continuum.local_damping;
  settings.n_threads = static_cast<unsigned int>(std::max(1, spec.tank.filling.n_threads)); // the particles' threads
  const fem::SoilModel soil(spec.continuum.soil);
  auto continuum = std::make_unique<fem::ExplicitSolver>(mesh, soil, conditions, settings);
  fem::GeostaticStress geostatic;
  geostatic.surface_elevation = spec.tank.geometry.fill_height - box.y0; // the fill's top, in the box's frame
  geostatic.unit_weight = spec.tank.unit_weight;
  geostatic.k0 = spec.continuum.k0 > 0.0 ? spec.continuum.k0 : soil.default_k0();
  continuum->set_initial_stress(geostatic);
  return continuum;
}
} // namespace geohybrid::coupling
