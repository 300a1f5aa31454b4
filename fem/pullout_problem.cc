#include "pullout_problem.h"

#include "fem/constitutive/parameter_check.h"
#include "fem/tank_mesh.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace geohybrid::fem
{
void PulloutProblemParameters::validate(const std::string &where) const
{
  const auto positive = [&](double value, const char *name, const char *unit) {
    require_parameter(value > 0.0 && std::isfinite(value), where, name, value, std::string("must be positive ") + unit);
  };
  positive(sheet_length, "sheet length L", "[m]");
  positive(sheet_depth, "sheet depth H", "[m]");
  positive(sheet_node_spacing, "sheet node spacing", "[m]");
  if (wrap_around)
    {
      positive(return_height, "return height D1", "[m]");
      require_parameter(return_height < sheet_depth, where, "return height D1", return_height,
                        "must be less than the sheet depth H = " + std::to_string(sheet_depth) +
                          " m: the upper part would be at or above the soil's surface [m]");
      positive(upper_length, "upper length B", "[m]");
      require_parameter(wrap_corner_radius >= 0.0 && 2.0 * corner_radius() <= return_height &&
                          corner_radius() < upper_length,
                        where, "wrap corner radius", wrap_corner_radius,
                        "must be zero (automatic: twice the sheet node spacing, " +
                          std::to_string(2.0 * sheet_node_spacing) +
                          " m) or positive, and leave the radius at most D1 / 2 and less than B [m]");
      require_parameter(upper_length < sheet_length, where, "upper length B", upper_length,
                        "must be shorter than L = " + std::to_string(sheet_length) +
                          " m: the upper part runs back from the return towards the front wall and would leave "
                          "the tank [m]");
    }
  require_parameter(element_degree == 1 || element_degree == 2, where, "element degree", element_degree,
                    "must be 1 (Q1) or 2 (Q2)");
  positive(soil_density, "soil density", "[kg/m^3]");
  require_parameter(gravity >= 0.0 && std::isfinite(gravity), where, "gravity", gravity,
                    "must be zero or positive [m/s^2]");
  require_parameter(k0 >= 0.0 && std::isfinite(k0), where, "K0", k0,
                    "must be positive, or 0 for the soil's default (1 - sin phi) [-]");
  require_parameter(surcharge >= 0.0 && std::isfinite(surcharge), where, "surcharge", surcharge,
                    "must be zero or positive [Pa]");
  positive(pull_rate, "pull rate", "[m/s]");
  positive(final_displacement, "final displacement", "[m]");
  require_parameter(ramp_displacement >= 0.0 && ramp_displacement < final_displacement, where,
                    "ramp displacement", ramp_displacement, "must lie in [0, final displacement) [m]");
  require_parameter(output_interval > 0.0 && output_interval <= final_displacement, where, "output interval",
                    output_interval, "must lie in (0, final displacement] [m]");
  require_parameter(local_damping >= 0.0 && local_damping < 1.0, where, "local damping", local_damping,
                    "must lie in [0, 1) [-]");
  require_parameter(safety_factor > 0.0 && safety_factor <= 1.0, where, "safety factor", safety_factor,
                    "must lie in (0, 1] [-]");
  if (!snapshot_directory.empty())
    positive(snapshot_interval, "snapshot interval", "when a snapshot directory is given [m]");
  sheet.validate(where + ": sheet");
}

namespace
{
/// The sheet from the clamp through `corners`: straight parts divided into segments of at most
/// `spacing`, and every interior corner rounded by an arc of radius `radius` (divided likewise,
/// into at least two segments) that meets the straight parts tangentially, inside the corner;
/// returns the nodes, and sets `lower_part_end` to the node where the first straight part ends.
std::vector<dealii::Point<dim>> sheet_nodes(const std::vector<dealii::Point<dim>> &corners, double spacing,
                                            double radius, std::size_t &lower_part_end)
{
  std::vector<dealii::Point<dim>> nodes{corners.front()};
  const auto straight_to = [&](const dealii::Point<dim> &to) {
    const dealii::Point<dim> from = nodes.back();
    const auto n = static_cast<unsigned int>(std::max(1.0, std::ceil(from.distance(to) / spacing * (1.0 - 1e-12))));
    for (unsigned int k = 1; k <= n; ++k)
      nodes.push_back(from + (to - from) * (static_cast<double>(k) / n));
  };
  for (std::size_t c = 1; c + 1 < corners.size(); ++c)
    {
      const dealii::Tensor<1, dim> in = (corners[c] - corners[c - 1]) / corners[c].distance(corners[c - 1]);
      const dealii::Tensor<1, dim> out = (corners[c + 1] - corners[c]) / corners[c + 1].distance(corners[c]);
      const double turn = std::atan2(in[0] * out[1] - in[1] * out[0], in * out); // signed, left positive
      const double setback = radius * std::tan(0.5 * std::abs(turn));
      straight_to(corners[c] - setback * in);
      if (c == 1)
        lower_part_end = nodes.size() - 1;
      if (radius > 0.0 && turn != 0.0)
        {
          const dealii::Tensor<1, dim> left({-in[1], in[0]});
          const dealii::Point<dim> centre = nodes.back() + (turn > 0.0 ? radius : -radius) * left;
          const dealii::Tensor<1, dim> arm = nodes.back() - centre;
          const auto n = static_cast<unsigned int>(
            std::max(2.0, std::ceil(radius * std::abs(turn) / spacing * (1.0 - 1e-12))));
          for (unsigned int k = 1; k <= n; ++k)
            {
              const double a = turn * k / n;
              nodes.push_back(centre + dealii::Tensor<1, dim>({std::cos(a) * arm[0] - std::sin(a) * arm[1],
                                                               std::sin(a) * arm[0] + std::cos(a) * arm[1]}));
            }
        }
    }
  straight_to(corners.back());
  if (corners.size() == 2)
    lower_part_end = nodes.size() - 1;
  return nodes;
}
} // namespace

double PulloutProblemParameters::corner_radius() const
{
  if (!wrap_around)
    return 0.0;
  return wrap_corner_radius > 0.0 ? wrap_corner_radius : 2.0 * sheet_node_spacing;
}

PulloutTankExtent pullout_tank_extent(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                                      const PulloutProblemParameters &parameters, const std::string &where)
{
  const auto [lo, hi] = mesh_extent(mesh);
  const PulloutTankExtent tank{hi[0] - lo[0], hi[1] - lo[1], hi[0], hi[1]};
  const double tolerance = 1e-9 * std::max(tank.length, tank.height);
  if (parameters.sheet_length > tank.length + tolerance)
    {
      std::ostringstream message;
      message << where << ": parameter 'sheet length L' = " << parameters.sheet_length
              << " m is longer than the tank (" << tank.length << " m, from the mesh)";
      throw std::invalid_argument(message.str());
    }
  if (parameters.sheet_depth >= tank.height - tolerance)
    {
      std::ostringstream message;
      message << where << ": parameter 'sheet depth H' = " << parameters.sheet_depth
              << " m puts the sheet at or below the tank's bottom (the soil is " << tank.height
              << " m high, from the mesh)";
      throw std::invalid_argument(message.str());
    }
  return tank;
}

BoundaryConditions pullout_boundary_conditions(double surcharge)
{
  // Bottom fixed, smooth walls, the surcharge on top: the geostatic state is then in equilibrium.
  BoundaryConditions bc;
  bc.displacements = {{tank_boundary::bottom, true, true, nullptr},
                      {tank_boundary::back_wall, true, false, nullptr},
                      {tank_boundary::front_wall, true, false, nullptr}};
  if (surcharge > 0.0)
    bc.pressures = {{tank_boundary::top, std::make_shared<dealii::Functions::ConstantFunction<dim>>(surcharge)}};
  return bc;
}

PulloutProblem::PulloutProblem(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                               const PulloutProblemParameters &parameters, const std::string &where)
  : parameters_(parameters)
{
  parameters_.validate(where);
  const SoilModel soil(parameters_.soil, where + ": soil");

  const PulloutTankExtent tank = pullout_tank_extent(mesh, parameters_, where);
  tank_length_ = tank.length;
  tank_height_ = tank.height;
  x_front_ = tank.x_front;
  y_top_ = tank.y_top;
  const BoundaryConditions bc = pullout_boundary_conditions(parameters_.surcharge);

  ExplicitSettings settings;
  settings.element_degree = parameters_.element_degree;
  settings.density = parameters_.soil_density;
  settings.gravity[1] = -parameters_.gravity;
  settings.safety_factor = parameters_.safety_factor;
  settings.damping.local = parameters_.local_damping;
  solver_ = std::make_unique<ExplicitSolver>(mesh, soil, bc, settings);

  geostatic_.surface_elevation = y_top_;
  geostatic_.unit_weight = parameters_.soil_density * parameters_.gravity;
  geostatic_.k0 = parameters_.k0 > 0.0 ? parameters_.k0 : soil.default_k0();
  geostatic_.surcharge = parameters_.surcharge;
  geostatic_.validate(where + ": geostatic stress");
  solver_->set_initial_stress(geostatic_);

  // The sheet from the front wall (node 0, the clamp) back over L at depth H; a wrap-around goes on
  // up D1 and forward over B at depth H - D1, as the DEM's (dem/laboratory/pullout_tank.cc,
  // sheet_corners).
  const double y_sheet = y_top_ - parameters_.sheet_depth, x_end = x_front_ - parameters_.sheet_length;
  std::vector<dealii::Point<dim>> corners{dealii::Point<dim>(x_front_, y_sheet), dealii::Point<dim>(x_end, y_sheet)};
  if (parameters_.wrap_around)
    {
      const double y_upper = y_sheet + parameters_.return_height;
      corners.emplace_back(x_end, y_upper);
      corners.emplace_back(x_end + parameters_.upper_length, y_upper);
    }
  const std::vector<dealii::Point<dim>> nodes = sheet_nodes(corners, parameters_.sheet_node_spacing, parameters_.corner_radius(), lower_part_end_);
  arc_lengths_.assign(1, 0.0);
  for (std::size_t k = 1; k < nodes.size(); ++k)
    arc_lengths_.push_back(arc_lengths_.back() + nodes[k].distance(nodes[k - 1]));

  // What the interface would hold if the whole sheet slid with the soil at rest.
  const auto &interface = parameters_.sheet.interface;
  const double tan_delta = std::tan(degrees_to_radians(interface.friction_angle_deg));
  // Per segment of the sheet as laid, the geostatic normal stress at its middle (exact on the
  // straight parts, where it is linear; the arcs' chords to O(spacing^2)).
  geostatic_limit_ = 0.0;
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k)
    {
      const double length = nodes[k].distance(nodes[k + 1]);
      const dealii::Tensor<1, dim> along = (nodes[k + 1] - nodes[k]) / length;
      const dealii::Tensor<1, dim> normal({-along[1], along[0]});
      const StressTensor stress = geostatic_.stress_at(0.5 * (nodes[k] + nodes[k + 1]));
      double sigma_n = 0.0; // compressive positive
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          sigma_n -= normal[i] * stress[i][j] * normal[j];
      geostatic_limit_ += 2.0 * (interface.cohesion + sigma_n * tan_delta) * length;
    }
  n_cells_ = mesh.n_global_active_cells();

  TrussSheetParameters sheet_parameters = parameters_.sheet;
  if (parameters_.automatic_mass_scaling)
    {
      // omega of a node scales as 1/sqrt(m): the mass must grow by (dt / dt_sheet)^2; 8 times that
      // (see the header). The sheet's inertia does not matter in a quasi-static pull (the rate
      // check in the tests shows it).
      sheet_parameters.mass_scaling = 1.0;
      const EmbeddedSheet unscaled(solver_->space(), TrussSheet(nodes, sheet_parameters, where + ": sheet"), {},
                                   where + ": sheet");
      sheet_parameters.mass_scaling =
        std::max(1.0, 8.0 * std::pow(solver_->time_step() / unscaled.stable_time_step(), 2));
    }
  clamp_node_ = 0;
  solver_->attach_sheet(TrussSheet(nodes, sheet_parameters, where + ": sheet"),
                        {{clamp_node_, [this](double t) { return dealii::Tensor<1, dim>({head_displacement_at(t), 0.0}); }}});
}

double PulloutProblem::head_displacement_at(double time) const
{
  // Over the ramp the speed rises linearly from 0 to the rate: d = v t^2 / (2 t_ramp).
  const double v = parameters_.pull_rate, d_ramp = parameters_.ramp_displacement, t_ramp = 2.0 * d_ramp / v;
  if (time < t_ramp)
    return 0.5 * v * time * time / t_ramp;
  return d_ramp + v * (time - t_ramp);
}

double PulloutProblem::time_of_head_displacement(double d) const
{
  const double v = parameters_.pull_rate, d_ramp = parameters_.ramp_displacement, t_ramp = 2.0 * d_ramp / v;
  if (d < d_ramp)
    return std::sqrt(2.0 * d * t_ramp / v);
  return t_ramp + (d - d_ramp) / v;
}

PulloutResult PulloutProblem::run(const CurveObserver &observer)
{
  PulloutResult result;
  result.tank_length = tank_length_;
  result.tank_height = tank_height_;
  result.time_step = solver_->time_step();
  result.vertical_stress_at_sheet = -geostatic_.stress_at(dealii::Point<dim>(x_front_, y_top_ - parameters_.sheet_depth))[1][1];
  const EmbeddedSheet &sheet = *solver_->sheet();
  result.sheet_mass_scaling = sheet.sheet().parameters().mass_scaling;
  result.geostatic_interface_limit = geostatic_limit_;
  result.n_cells = n_cells_;

  // The sheet is laid unstretched with an unloaded interface: the first point is the state before
  // the pull, as computed (zero up to round-off).
  result.curve.push_back({sheet.displacements()[clamp_node_][0], sheet.clamp_force(0)[0]});
  if (observer)
    observer(result.curve.back(), sheet);

  const double end_time = time_of_head_displacement(parameters_.final_displacement);
  const double interval = parameters_.output_interval;
  double next_output = interval, next_snapshot = parameters_.snapshot_interval;
  double sum_displacement = 0.0, sum_tension = 0.0;
  unsigned int n_summed = 0, n_snapshots = 0;
  const auto write_snapshot = [&]() {
    const std::string record = solver_->write_vtu(parameters_.snapshot_directory, "pullout", n_snapshots++);
    result.snapshots.push_back(parameters_.snapshot_directory + "/" + record);
  };
  if (!parameters_.snapshot_directory.empty())
    write_snapshot();

  while (solver_->time() < end_time * (1.0 - 1e-12))
    {
      solver_->advance_to(std::min(solver_->time() + solver_->time_step(), end_time));
      const double head = sheet.displacements()[clamp_node_][0];
      sum_displacement += head;
      sum_tension += sheet.clamp_force(0)[0];
      ++n_summed;
      const bool last = solver_->time() >= end_time * (1.0 - 1e-12);
      if (head >= next_output * (1.0 - 1e-9) || last)
        {
          result.curve.push_back({sum_displacement / n_summed, sum_tension / n_summed});
          if (observer)
            observer(result.curve.back(), sheet);
          sum_displacement = sum_tension = 0.0;
          n_summed = 0;
          next_output += interval;
        }
      if (!parameters_.snapshot_directory.empty() && (head >= next_snapshot * (1.0 - 1e-9) || last))
        {
          write_snapshot();
          next_snapshot += parameters_.snapshot_interval;
        }
    }
  result.n_steps = solver_->n_steps();
  for (const auto &p : result.curve)
    result.max_head_tension = std::max(result.max_head_tension, p.head_tension);
  return result;
}

void make_pullout_tank_mesh(dealii::parallel::distributed::Triangulation<dim> &mesh, double length, double height,
                            double cell_size, const PulloutProblemParameters &p, const std::string &where)
{
  if (!p.wrap_around)
    make_tank_mesh(mesh, length, height, cell_size, {}, {height - p.sheet_depth}, where);
  else
    make_tank_mesh(mesh, length, height, cell_size, {length - p.sheet_length},
                   {height - p.sheet_depth, height - p.sheet_depth + p.return_height}, where);
}

void make_rectangular_tank(dealii::parallel::distributed::Triangulation<dim> &mesh, double length, double height,
                           unsigned int nx, unsigned int ny)
{
  dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {nx, ny}, dealii::Point<dim>(0, 0),
                                                    dealii::Point<dim>(length, height), true);
  set_tank_boundary_ids_of_colorized_rectangle(mesh);
}
} // namespace geohybrid::fem
