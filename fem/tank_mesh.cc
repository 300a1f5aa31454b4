#include "tank_mesh.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::fem
{
void read_tank_mesh(dealii::parallel::distributed::Triangulation<dim> &mesh, const std::string &file,
                    const std::vector<dealii::types::boundary_id> &required_boundary_ids,
                    unsigned int n_global_refinements)
{
  // Every rank reads the (small, coarse) file itself, so every rank reaches the same verdict.
  std::ifstream input(file);
  if (!input)
    throw std::invalid_argument("tank mesh: cannot open the mesh file '" + file +
                                "' (missing? meshes/ holds the .msh files generated from the .geo sources)");
  dealii::GridIn<dim> grid_in;
  grid_in.attach_triangulation(mesh);
  const std::string cannot_read = "tank mesh: cannot read '" + file + "' as a gmsh 2.2 ASCII mesh of quadrilaterals";
  try
    {
      grid_in.read_msh(input);
    }
  catch (const dealii::ExceptionBase &e)
    {
      // deal.II's what() holds the source line and a stack trace: only its own explanation, on one line.
      std::ostringstream info;
      e.print_info(info);
      std::string reason;
      std::istringstream words(info.str());
      for (std::string word; words >> word;)
        reason += (reason.empty() ? "" : " ") + word;
      // It may quote the file: a damaged one's bytes are not printed.
      for (char &c : reason)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f)
          c = '?';
      if (reason.size() > 300)
        reason = reason.substr(0, 300) + "...";
      throw std::invalid_argument(cannot_read + (reason.empty() ? std::string() : ": " + reason));
    }
  catch (const std::exception &e)
    {
      throw std::invalid_argument(cannot_read + ": " + e.what());
    }
  const std::vector<dealii::types::boundary_id> ids = mesh.get_boundary_ids();
  if (std::find(ids.begin(), ids.end(), 0) != ids.end())
    throw std::invalid_argument("tank mesh '" + file +
                                "': some boundary faces carry no gmsh physical line (boundary id 0); tag every wall "
                                "of the .geo with a Physical Line 1 to 4");
  for (const auto id : required_boundary_ids)
    if (std::find(ids.begin(), ids.end(), id) == ids.end())
      {
        std::ostringstream message;
        message << "tank mesh '" << file << "': boundary id " << static_cast<unsigned int>(id)
                << " is not on the mesh (its boundary ids:";
        for (const auto i : ids)
          message << " " << static_cast<unsigned int>(i);
        message << "; they are the gmsh physical lines of the .geo)";
        throw std::invalid_argument(message.str());
      }
  if (n_global_refinements > 0)
    mesh.refine_global(n_global_refinements);
}
} // namespace geohybrid::fem

namespace geohybrid::fem
{
std::pair<dealii::Point<dim>, dealii::Point<dim>> mesh_extent(const dealii::parallel::distributed::Triangulation<dim> &mesh)
{
  double lo[dim], hi[dim];
  for (unsigned int d = 0; d < dim; ++d)
    {
      lo[d] = std::numeric_limits<double>::max();
      hi[d] = -std::numeric_limits<double>::max();
    }
  for (const auto &cell : mesh.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = std::min(lo[d], cell->vertex(v)[d]);
            hi[d] = std::max(hi[d], cell->vertex(v)[d]);
          }
  const MPI_Comm comm = mesh.get_communicator();
  dealii::Point<dim> p_lo, p_hi;
  for (unsigned int d = 0; d < dim; ++d)
    {
      p_lo[d] = dealii::Utilities::MPI::min(lo[d], comm);
      p_hi[d] = dealii::Utilities::MPI::max(hi[d], comm);
    }
  return {p_lo, p_hi};
}

namespace
{
/// The cell sizes along [0, extent] with a cell of `h` centred on every one of `centres`.
std::vector<double> cell_sizes_around(double extent, double h, std::vector<double> centres, const char *axis,
                                      const std::string &where)
{
  std::sort(centres.begin(), centres.end());
  const double tolerance = 1e-9 * std::max(extent, h);
  const auto refuse = [&](const std::string &why) {
    std::ostringstream message;
    message << where << ": parameter 'cell size' = " << h << " m: " << why
            << "; choose a smaller cell size [m]";
    throw std::invalid_argument(message.str());
  };
  std::vector<double> sizes;
  // Fills [from, to] with cells of about h: a gap shorter than h / 2 cannot be meshed without a
  // sliver cell, which would cut the explicit solver's stable step.
  const auto fill = [&](double from, double to) {
    const double gap = to - from;
    if (gap < -tolerance)
      refuse(std::string("the sheet's lines along ") + axis + " are closer than one cell to each other or to the tank's side");
    const auto n = static_cast<unsigned int>(std::lround(std::max(0.0, gap) / h));
    if (n == 0)
      {
        if (gap > tolerance)
          refuse(std::string("a gap of ") + std::to_string(gap) + " m along " + axis +
                 " between the sheet's lines and the tank's sides is thinner than half a cell");
        return;
      }
    for (unsigned int k = 0; k < n; ++k)
      sizes.push_back(gap / n);
  };
  double edge = 0.0;
  for (const double c : centres)
    {
      fill(edge, c - 0.5 * h);
      sizes.push_back(h);
      edge = c + 0.5 * h;
    }
  fill(edge, extent);
  return sizes;
}
} // namespace

void make_tank_mesh(dealii::parallel::distributed::Triangulation<dim> &mesh, double length, double height,
                    double cell_size, std::vector<double> x_centres, std::vector<double> y_centres,
                    const std::string &where)
{
  if (!(cell_size > 0.0) || !(cell_size <= std::min(length, height)))
    {
      std::ostringstream message;
      message << where << ": parameter 'cell size' = " << cell_size << " m must be positive and at most the tank's "
              << "length and height (" << length << " m, " << height << " m) [m]";
      throw std::invalid_argument(message.str());
    }
  const std::vector<std::vector<double>> steps{cell_sizes_around(length, cell_size, std::move(x_centres), "x", where),
                                               cell_sizes_around(height, cell_size, std::move(y_centres), "y", where)};
  dealii::GridGenerator::subdivided_hyper_rectangle(mesh, steps, dealii::Point<dim>(0, 0),
                                                    dealii::Point<dim>(length, height), true);
  set_tank_boundary_ids_of_colorized_rectangle(mesh);
}

void set_tank_boundary_ids_of_colorized_rectangle(dealii::parallel::distributed::Triangulation<dim> &mesh)
{
  for (const auto &cell : mesh.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
        {
          const auto id = face->boundary_id();
          face->set_boundary_id(id == 0   ? tank_boundary::back_wall
                                : id == 1 ? tank_boundary::front_wall
                                : id == 2 ? tank_boundary::bottom
                                          : tank_boundary::top);
        }
}
} // namespace geohybrid::fem
