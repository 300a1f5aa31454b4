#include "continuum_region.h"

#include <deal.II/grid/grid_generator.h>

#include <map>
#include <set>
#include <stdexcept>
#include <utility>

namespace geohybrid::coupling
{
namespace
{
using Tank = dealii::Triangulation<fem::dim>;
/// A face's centre, exactly: the result's vertices are copies of the tank's, and the centre is the
/// same mean of the same two vertices.
using FaceKey = std::pair<double, double>;
FaceKey key_of(const Tank::face_iterator &face)
{
  const dealii::Point<fem::dim> c = face->center();
  return {c[0], c[1]};
}
} // namespace

std::unique_ptr<dealii::parallel::distributed::Triangulation<fem::dim>>
continuum_region_mesh(const Tank &tank, const OverlapBand &band, MPI_Comm communicator)
{
  std::set<Tank::active_cell_iterator> in_core;
  for (const auto &cell : tank.active_cell_iterators())
    {
      // A vertex on a side counts as in the core: the mesh's lines are computed (0.6 / 12 * 6 is
      // 0.30000000000000004), a side on one of them must not keep a row of cells with w ~ 1e-16.
      const double on_side = 1e-10 * cell->diameter();
      bool inside = true;
      for (const unsigned int v : cell->vertex_indices())
        inside = inside && band.coordinate(Vec2(cell->vertex(v)[0], cell->vertex(v)[1])) <= on_side;
      if (inside)
        in_core.insert(cell);
    }
  // Every kept cell has a vertex with s > 0, where w > 0: none is left without the continuum's
  // energy (whether its quadrature points see it is the solver's check, see the header).
  if (in_core.size() == tank.n_active_cells())
    throw std::invalid_argument("continuum region: parameter 'DEM region' covers the whole tank: no continuum is left");

  // The boundary id of each face of the result, found by its centre: the tank's boundary keeps its
  // ids, a face between a kept cell and a removed one becomes the core's boundary (deal.II's
  // function gives every new boundary face id 0, like the tank's own first side).
  std::map<FaceKey, dealii::types::boundary_id> boundary_id;
  for (const auto &cell : tank.active_cell_iterators())
    if (in_core.count(cell) == 0)
      for (const unsigned int f : cell->face_indices())
        {
          if (cell->face(f)->at_boundary())
            {
              if (cell->face(f)->boundary_id() == dem_core_boundary_id)
                throw std::invalid_argument("continuum region: the tank's mesh already has boundary id " +
                                            std::to_string(dem_core_boundary_id) +
                                            ", the id of the 'DEM region' boundary");
              boundary_id[key_of(cell->face(f))] = cell->face(f)->boundary_id();
            }
          else if (in_core.count(cell->neighbor(f)) > 0)
            boundary_id[key_of(cell->face(f))] = dem_core_boundary_id;
        }

  Tank continuum;
  dealii::GridGenerator::create_triangulation_with_removed_cells(tank, in_core, continuum);
  for (const auto &cell : continuum.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
        cell->face(f)->set_boundary_id(boundary_id.at(key_of(cell->face(f))));

  auto mesh = std::make_unique<dealii::parallel::distributed::Triangulation<fem::dim>>(communicator);
  mesh->copy_triangulation(continuum);
  return mesh;
}
} // namespace geohybrid::coupling
