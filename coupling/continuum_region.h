#pragma once
// The continuum's mesh of a coupled model whose DEM core is a region inside the tank (issue 6: a
// polygon round the anchorage, the FE mesh over the rest of the tank): the tank's mesh with the
// cells that lie entirely in the core removed. The cells of the overlap band and those that cross
// the core's sides stay (the continuum carries w > 0 of their energy somewhere).
//
// The core's sides should lie on mesh lines. A cell that a side crosses keeps its part inside the
// core, where w = 0: only a thin partial band then carries its mass and stiffness, and if that part
// misses all of a node's quadrature points the node is massless and ExplicitSolver::
// set_energy_weight refuses it.
#include "coupling/overlap_band.h"
#include "fem/conventions.h"

#include <deal.II/base/types.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/tria.h>

#include <memory>

namespace geohybrid::coupling
{
/// The boundary id of the faces where the continuum meets the DEM core (the hole's boundary).
/// The tank's own boundary faces keep theirs (GridGenerator's 0 to 3 with colorize).
inline constexpr dealii::types::boundary_id dem_core_boundary_id = 10;

/// The continuum's mesh: the cells of `tank` (all on one level, not adaptively refined) with at
/// least one vertex at band coordinate s > 0; a cell whose every vertex has s <= 0 lies entirely in
/// the convex core (s is convex) and is removed (s <= 1e-10 of the cell's diameter: a vertex on a
/// side up to the round-off of the mesh's coordinates). Boundary ids: the tank's kept, dem_core_boundary_id
/// on the faces the removed cells leave. Throws std::invalid_argument naming 'DEM region' if the
/// core covers the whole tank, or if `tank` already has a face with dem_core_boundary_id (the two
/// boundaries would be one).
/// The mesh lives on `communicator` (a coupled model runs on one rank: MPI_COMM_SELF lets several
/// such runs share an MPI job, an ensemble).
std::unique_ptr<dealii::parallel::distributed::Triangulation<fem::dim>>
continuum_region_mesh(const dealii::Triangulation<fem::dim> &tank, const OverlapBand &band,
                      MPI_Comm communicator = MPI_COMM_WORLD);
} // namespace geohybrid::coupling
