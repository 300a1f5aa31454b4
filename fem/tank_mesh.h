#pragma once
// Reading a tank mesh (meshes/*.msh, gmsh format 2.2 ASCII, quadrilaterals only) into the
// distributed mesh of the continuum, with the checks a user needs: the file must exist, and the
// boundary ids that the boundary conditions will name must be on it.
//
// The tank meshes of meshes/ tag their walls with gmsh physical lines 1 to 4 (gmsh has no physical
// tag 0, and a boundary face without a tag would come in with id 0, so id 0 on a tank mesh means a
// wall was left untagged, and is refused): 1 the bottom, 2 the front wall (x = tank length) that
// the sheet passes through, 3 the top surface, 4 the back wall (x = 0).
#include "fem/conventions.h"

#include <deal.II/base/point.h>
#include <deal.II/distributed/tria.h>

#include <string>
#include <vector>

namespace geohybrid::fem
{
namespace tank_boundary
{
constexpr dealii::types::boundary_id bottom = 1;     ///< y = 0
constexpr dealii::types::boundary_id front_wall = 2; ///< x = tank length, where the sheet leaves
constexpr dealii::types::boundary_id top = 3;        ///< the soil's surface
constexpr dealii::types::boundary_id back_wall = 4;  ///< x = 0
} // namespace tank_boundary

/// Reads `file` into the empty `mesh`, then refines it `n_global_refinements` times. Throws
/// std::invalid_argument naming the file if it is missing or unreadable or has untagged boundary
/// faces (id 0), and naming the file and the id if one of `required_boundary_ids` is not on the
/// mesh. Collective.
void read_tank_mesh(dealii::parallel::distributed::Triangulation<dim> &mesh, const std::string &file,
                    const std::vector<dealii::types::boundary_id> &required_boundary_ids = {tank_boundary::back_wall,
                                                                                             tank_boundary::front_wall,
                                                                                             tank_boundary::bottom,
                                                                                             tank_boundary::top},
                    unsigned int n_global_refinements = 0);

/// The lower-left and upper-right corners of the mesh's bounding box, the same on every rank.
/// Collective.
std::pair<dealii::Point<dim>, dealii::Point<dim>> mesh_extent(const dealii::parallel::distributed::Triangulation<dim> &mesh);

/// Gives the boundary faces of a rectangle made by GridGenerator with colorize = true (ids 0 left,
/// 1 right, 2 bottom, 3 top) the tank's ids (back wall, front wall, bottom, top).
void set_tank_boundary_ids_of_colorized_rectangle(dealii::parallel::distributed::Triangulation<dim> &mesh);

/// A rectangular tank [0, length] x [0, height] with the tank meshes' boundary ids, of cells of
/// about `cell_size`, whose columns are centred on the abscissae `x_centres` and whose rows on the
/// ordinates `y_centres`: a sheet laid along those lines then runs through the middle of its cells
/// rather than on their edges, so the interface reads the soil's stress at the sheet's level (the
/// mean over a cell's Gauss points is the centre value of a linear field) and not that of the
/// cells on one side. Each centred cell is cell_size wide; the gaps between them are divided into
/// cells of between 1/2 and 3/2 of cell_size. Throws std::invalid_argument naming `where` and
/// 'cell size' if a line lies closer than cell_size / 2 to the tank's side or two lines closer
/// than cell_size to each other, or if a gap between them would need a cell thinner than cell_size / 2.
/// Collective.
void make_tank_mesh(dealii::parallel::distributed::Triangulation<dim> &mesh, double length, double height,
                    double cell_size, std::vector<double> x_centres, std::vector<double> y_centres,
                    const std::string &where);
} // namespace geohybrid::fem
