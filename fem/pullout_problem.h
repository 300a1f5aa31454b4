#pragma once
// The pull-out test of a geosynthetic sheet in continuum soil (issue 5, "pure-FEM pull-out"): the
// INSA tank of the DEM pull-out (issue 4) with the soil as a deal.II continuum, run with the
// explicit solver because that is the one the sheet's frictional interface lives in.
//
// The set-up, in the tank's frame (fem/tank_mesh.h: x from the back wall to the front wall, y up,
// boundary ids 1 bottom, 2 front wall, 3 top, 4 back wall):
// - the soil starts at its geostatic stress (fem/geostatic_stress.h: sigma_v = q + gamma (y_top - y),
//   sigma_h = K0 sigma_v) under gravity, so nothing moves before the pull;
// - the bottom is fixed, the back and front walls are smooth rollers (u_x = 0), the top is free or
//   carries the surcharge q as a pressure;
// - the sheet (fem/truss_sheet.h) lies at depth H below the top, from the front wall back into the
//   tank over its length L, tied to the soil by the Mohr-Coulomb interface of
//   fem/sheet_interface.h; its node at the front wall is the clamp. A wrap-around (as the DEM's,
//   dem/laboratory/pullout_tank.cc, PullOutGeometry::sheet_corners) goes on from the lower part's
//   end up a vertical return of D1 and back towards the front wall over an upper part of B at depth
//   H - D1 (= D2); the interface follows each node's slip along that path, round the corners
//   (fem/sheet_interface.h);
// - the clamp moves in +x at a constant rate, reached over a ramp (the pull), the soil and sheet are integrated by
//   central differences with local damping (a quasi-static run: the rate and the damping are
//   chosen so that halving the rate leaves the curve unchanged, tests/test_fem_pullout.cc);
//   the default local damping is 0.3, not PFC's 0.7: local damping also acts on the sheet's nodes,
//   and on a sheet that slides while its nodes oscillate it adds a drag the clamp has to pull
//   (measured on the small tank of the test: plateau +2.6 % over the interface's own resistance at
//   0.7 with the sheet's mass scaled 2 times its stability limit, +1.4 % at 0.7 and 8 times,
//   +0.2 to +0.3 % at 0.3 and 8 times);
// - the head tension T is the force that holds the clamp [N/m of width], recorded against the
//   clamp's displacement as the mean over each output interval (the mass-scaled sheet makes the
//   force at a single step oscillate by about 1-2 %, fem/README.md).
//
// What the continuum leaves out, on purpose: the walls are frictionless (the DEM tank's walls have
// 28 degrees of friction), the strain is small, and the sheet outside the tank (clamp to front
// wall) is not modelled.
#include "fem/constitutive/soil_model.h"
#include "fem/explicit_solver.h"
#include "fem/truss_sheet.h"

#include <deal.II/distributed/tria.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace geohybrid::fem
{
struct PulloutProblemParameters
{
  // Geometry: the tank's size comes from the mesh.
  double sheet_length = 1.0;         ///< L, from the front wall into the tank, in (0, tank length] [m]
  double sheet_depth = 0.4;          ///< H, below the top surface, in (0, tank height) [m]
  double sheet_node_spacing = 0.0125; ///< the truss segments' length at most, > 0 [m]
  /// A wrap-around anchorage: from the lower part's far end, a vertical return of D1 upwards and
  /// an upper part of B back towards the front wall, at depth H - D1.
  bool wrap_around = false;
  double return_height = 0.0; ///< D1, wrap-around only, in (0, H) [m]
  double upper_length = 0.0;  ///< B, wrap-around only, in (0, L) [m]
  /// The wrap-around's two corners are laid as arcs of this radius inside the sharp corners of
  /// L, D1, B (each straight part ends r short of its corner; the sheet is (4 - pi) r shorter
  /// than L + D1 + B), at most D1 / 2; 0 takes twice the node spacing, an arc of four segments.
  /// Why: at a sharp corner the segments on either side of it cut across the corner, and the
  /// nodes beside it, each held along the normal of its own part, balance their tension only by
  /// the component along that part: the L-shaped sheet of test_fem_sheet.cc held +57 % over its
  /// interface limit with a sharp corner, +9.2 % rounded over 4 segments (fem/README.md). [m]
  double wrap_corner_radius = 0.0;
  /// The corners' radius used: wrap_corner_radius, or twice the node spacing if it is 0 (0 for
  /// a run-out) [m].
  double corner_radius() const;

  // Soil.
  SoilParameters soil;
  unsigned int element_degree = 1; ///< 1 (Q1) or 2 (Q2)
  double soil_density = 1549.0;    ///< bulk density, > 0 (15.2 kN/m^3 over 9.81 m/s^2) [kg/m^3]
  double gravity = 9.81;           ///< g >= 0 [m/s^2]
  double k0 = 0.0;                 ///< sigma_h / sigma_v at rest; 0 takes the soil's default (1 - sin phi) [-]
  double surcharge = 0.0;          ///< q >= 0 on the top surface [Pa]

  // Sheet: J, areal mass, the interface (delta, c_i, k_n, k_s). Its `mass_scaling` is used as
  // given unless `automatic_mass_scaling` is set, which takes the smallest factor that keeps the
  // sheet's nodes stable at the soil's step, times 8 (a lighter sheet oscillates more and drags
  // more through the local damping, a heavier one sloshes: 2 and 32 times both gave a plateau
  // 2.5 % above the interface's resistance on the test's tank, 8 times 1.4 %, at damping 0.7).
  TrussSheetParameters sheet;
  bool automatic_mass_scaling = true;

  // Pull.
  double pull_rate = 0.004;          ///< clamp velocity, > 0 [m/s]
  /// The clamp's speed rises linearly from 0 to the rate over this head displacement, in
  /// [0, final displacement) (as the DEM pull, dem/laboratory/pullout_tank.h) [m].
  double ramp_displacement = 0.0;
  double final_displacement = 0.06;  ///< head displacement at the end, > 0 [m]
  double output_interval = 0.5e-3;   ///< head displacement between curve points, in (0, final] [m]
  double local_damping = 0.3;        ///< alpha_l of the explicit solver, in [0, 1) (see above) [-]
  double safety_factor = 0.8;        ///< on the soil's critical step, in (0, 1] [-]

  // Snapshots (VTU of the soil): none when the directory is empty.
  std::string snapshot_directory;
  double snapshot_interval = 0.0; ///< head displacement between snapshots, > 0 if a directory is given [m]

  /// Throws std::invalid_argument naming `where` and the parameter.
  void validate(const std::string &where) const;
};

struct PulloutCurvePoint
{
  double head_displacement = 0.0; ///< the clamp's displacement along the pull [m]
  double head_tension = 0.0;      ///< the force holding the clamp [N/m]
};

struct PulloutResult
{
  std::vector<PulloutCurvePoint> curve; ///< starts at the unloaded sheet (0, 0)
  double max_head_tension = 0.0;        ///< T_max over the curve [N/m]
  double vertical_stress_at_sheet = 0.0; ///< geostatic sigma_v = q + gamma H, compressive positive [Pa]
  /// 2 (c_i + sigma_v tan(delta)) L with the geostatic sigma_v at the sheet: the head tension
  /// if the whole sheet slid with the soil at rest [N/m]. For a wrap-around, the sum over the
  /// sheet's segments as laid of 2 (c_i + sigma_n tan(delta)) times their length, sigma_n the
  /// geostatic normal stress on the segment at its middle (sigma_v on the lower and upper parts,
  /// K0 sigma_v on the return, in between on the arcs); no term for the corners' own normal
  /// force, which the interface law does not add to their strength (fem/sheet_interface.h).
  double geostatic_interface_limit = 0.0;
  unsigned int n_cells = 0;             ///< of the soil mesh, on all ranks
  double tank_length = 0.0, tank_height = 0.0; ///< from the mesh [m]
  double time_step = 0.0;               ///< [s]
  double sheet_mass_scaling = 0.0;      ///< the factor used [-]
  unsigned int n_steps = 0;
  std::vector<std::string> snapshots;   ///< PVTU records written (snapshot directory/pullout_NNNN.pvtu)
};

class PulloutProblem
{
public:
  /// `mesh` is the tank (boundary ids 1 to 4, fem/tank_mesh.h) and must outlive the problem.
  /// Throws std::invalid_argument naming `where` and the parameter for bad input or a sheet that
  /// does not fit the tank. Collective.
  PulloutProblem(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                 const PulloutProblemParameters &parameters, const std::string &where = "pull-out");

  // The clamp's motion refers to this object: it stays where it was built.
  PulloutProblem(const PulloutProblem &) = delete;
  PulloutProblem &operator=(const PulloutProblem &) = delete;

  /// Called at every point of the curve with the point and the sheet as it is then.
  using CurveObserver = std::function<void(const PulloutCurvePoint &, const EmbeddedSheet &)>;

  /// Pulls the clamp to the final displacement. Collective; every rank returns the same curve
  /// (and calls `observer` alike).
  PulloutResult run(const CurveObserver &observer = {});

  const ExplicitSolver &solver() const { return *solver_; }
  double tank_length() const { return tank_length_; } ///< from the mesh [m]
  double tank_height() const { return tank_height_; } ///< from the mesh [m]
  /// Sheet node 0 is the clamp at the front wall; this one is the far end of the lower part (for a
  /// wrap-around, the lower corner).
  std::size_t lower_part_end() const { return lower_part_end_; }
  /// Distance of each sheet node from the clamp along the sheet, as laid [m].
  const std::vector<double> &arc_lengths() const { return arc_lengths_; }
  /// The clamp's displacement along the pull at `time`, the ramp included [m].
  double head_displacement_at(double time) const;
  /// The time at which the clamp reaches head displacement `d` [s].
  double time_of_head_displacement(double d) const;

private:
  PulloutProblemParameters parameters_;
  double tank_length_ = 0.0, tank_height_ = 0.0, x_front_ = 0.0, y_top_ = 0.0;
  GeostaticStress geostatic_;
  std::unique_ptr<ExplicitSolver> solver_;
  double geostatic_limit_ = 0.0;
  unsigned int n_cells_ = 0;
  std::size_t clamp_node_ = 0, lower_part_end_ = 0;
  std::vector<double> arc_lengths_;
};

/// The generated tank for `parameters` (fem/tank_mesh.h, make_tank_mesh): [0, length] x
/// [0, height] of cells of about `cell_size`, a row of them centred on the sheet (for a
/// wrap-around, a row on each of its lower and upper parts and a column on its return). Throws std::invalid_argument naming `where` and 'cell
/// size' if the sheet lies too close to the bottom or the top for it. Collective.
void make_pullout_tank_mesh(dealii::parallel::distributed::Triangulation<dim> &mesh, double length, double height,
                            double cell_size, const PulloutProblemParameters &parameters, const std::string &where);

/// The tank a pull-out mesh describes (its bounding box, the same on every rank).
struct PulloutTankExtent
{
  double length = 0.0, height = 0.0; ///< [m]
  double x_front = 0.0, y_top = 0.0; ///< the front wall's abscissa and the soil surface's ordinate [m]
};

/// The tank of `mesh`; throws std::invalid_argument naming `where` and the parameter if the sheet
/// of `parameters` (L, H; a wrap-around's D1 and B) does not fit in it. Both pull-outs (explicit and implicit) use it. Collective.
PulloutTankExtent pullout_tank_extent(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                                      const PulloutProblemParameters &parameters, const std::string &where);

/// The tank's supports: the bottom fixed, the back and front walls smooth rollers (u_x = 0), and the
/// surcharge q >= 0 as a pressure on the top.
BoundaryConditions pullout_boundary_conditions(double surcharge);

/// A rectangular tank [0, length] x [0, height] of nx x ny cells with the tank meshes' boundary
/// ids (1 bottom, 2 front wall at x = length, 3 top, 4 back wall at x = 0), for tests and quick
/// studies without a .msh file. Collective.
void make_rectangular_tank(dealii::parallel::distributed::Triangulation<dim> &mesh, double length, double height,
                           unsigned int nx, unsigned int ny);
} // namespace geohybrid::fem
