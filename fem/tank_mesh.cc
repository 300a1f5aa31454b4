#include "tank_mesh.h"

#include <deal.II/grid/grid_in.h>

#include <algorithm>
#include <fstream>
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
  try
    {
      grid_in.read_msh(input);
    }
  catch (const std::exception &e)
    {
      throw std::invalid_argument("tank mesh: cannot read '" + file +
                                  "' as a gmsh 2.2 ASCII mesh of quadrilaterals: " + e.what());
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
