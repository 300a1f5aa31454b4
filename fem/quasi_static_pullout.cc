#include "quasi_static_pullout.h"

#include "fem/constitutive/parameter_check.h"
#include "fem/tank_mesh.h"

#include <algorithm>
#include <cmath>

namespace geohybrid::fem
{
void QuasiStaticPulloutParameters::validate(const std::string &where) const
{
  pullout.validate(where);
  require_parameter(displacement_increment > 0.0 && displacement_increment <= pullout.output_interval, where,
                    "displacement increment", displacement_increment, "must lie in (0, output interval] [m]");
  require_parameter(minimum_increment > 0.0 && minimum_increment <= displacement_increment, where,
                    "minimum displacement increment", minimum_increment,
                    "must be positive and at most the displacement increment [m]");
}

QuasiStaticPullout::QuasiStaticPullout(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                                       const QuasiStaticPulloutParameters &parameters, const std::string &where)
  : parameters_(parameters)
{
  parameters_.validate(where);
  const PulloutProblemParameters &p = parameters_.pullout;
  const SoilModel soil(p.soil, where + ": soil");

  const PulloutTankExtent tank = pullout_tank_extent(mesh, p, where);
  tank_length_ = tank.length;
  tank_height_ = tank.height;
  x_front_ = tank.x_front;
  y_top_ = tank.y_top;
  const BoundaryConditions bc = pullout_boundary_conditions(p.surcharge);

  QuasiStaticSettings settings;
  settings.element_degree = p.element_degree;
  settings.density = p.soil_density;
  settings.gravity = dealii::Tensor<1, dim>({0.0, -p.gravity});
  settings.newton = parameters_.newton;
  settings.linear_solver = parameters_.linear_solver;
  settings.stepping.increment = parameters_.displacement_increment;
  settings.stepping.minimum_increment = parameters_.minimum_increment;
  solver_ = std::make_unique<QuasiStaticSolver>(mesh, soil, bc, settings);

  geostatic_.surface_elevation = y_top_;
  geostatic_.unit_weight = p.soil_density * p.gravity;
  geostatic_.k0 = p.k0 > 0.0 ? p.k0 : soil.default_k0();
  geostatic_.surcharge = p.surcharge;
  geostatic_.validate(where + ": geostatic stress");
  solver_->set_initial_stress(geostatic_);

  // The sheet as PulloutProblem lays it: from the front wall (node 0, the clamp) back over L.
  const double y_sheet = y_top_ - p.sheet_depth;
  const auto n_segments =
    static_cast<unsigned int>(std::max(1.0, std::ceil(p.sheet_length / p.sheet_node_spacing * (1.0 - 1e-12))));
  std::vector<dealii::Point<dim>> nodes;
  for (unsigned int k = 0; k <= n_segments; ++k)
    nodes.emplace_back(x_front_ - p.sheet_length * k / n_segments, y_sheet);
  clamp_node_ = 0;
  arc_lengths_.assign(1, 0.0);
  for (std::size_t k = 1; k < nodes.size(); ++k)
    arc_lengths_.push_back(arc_lengths_.back() + nodes[k].distance(nodes[k - 1]));
  const double sigma_v = -geostatic_.stress_at(dealii::Point<dim>(x_front_, y_sheet))[1][1];
  geostatic_limit_ = 2.0 *
                     (p.sheet.interface.cohesion + sigma_v * std::tan(degrees_to_radians(p.sheet.interface.friction_angle_deg))) *
                     p.sheet_length;
  n_cells_ = mesh.n_global_active_cells();
  // The pseudo-time is the head displacement.
  solver_->attach_sheet(TrussSheet(nodes, p.sheet, where + ": sheet"),
                        {{clamp_node_, [](double t) { return dealii::Tensor<1, dim>({t, 0.0}); }}});
}

PulloutResult QuasiStaticPullout::run(const CurveObserver &observer)
{
  const PulloutProblemParameters &p = parameters_.pullout;
  result_ = PulloutResult();
  PulloutResult &result = result_;
  result.tank_length = tank_length_;
  result.tank_height = tank_height_;
  result.vertical_stress_at_sheet = -geostatic_.stress_at(dealii::Point<dim>(x_front_, y_top_ - p.sheet_depth))[1][1];
  result.geostatic_interface_limit = geostatic_limit_;
  result.n_cells = n_cells_;
  const auto record = [&]() {
    result.curve.push_back({solver_->sheet_displacements()[clamp_node_][0], solver_->sheet_node_reaction(clamp_node_)[0]});
    if (observer)
      observer(result.curve.back());
  };
  const auto write_snapshot = [&]() {
    const std::string name = solver_->write_vtu(p.snapshot_directory, "pullout", result.snapshots.size());
    result.snapshots.push_back(p.snapshot_directory + "/" + name);
  };
  // The state before the pull: the solver has assembled nothing yet, so the clamp's reaction is
  // that of the unloaded sheet, zero.
  result.curve.push_back({0.0, 0.0});
  if (observer)
    observer(result.curve.back());
  const bool snapshots = !p.snapshot_directory.empty();
  if (snapshots)
    write_snapshot();

  report_ = LoadSteppingReport();
  const double end = p.final_displacement, tolerance = 1e-9 * p.output_interval;
  double next_output = std::min(p.output_interval, end);
  double next_snapshot = snapshots ? std::min(p.snapshot_interval, end) : 2.0 * end;
  while (solver_->time() < end - tolerance)
    {
      const double target = std::min(next_output, next_snapshot);
      const LoadSteppingReport stage = solver_->advance_to(target);
      report_.steps.insert(report_.steps.end(), stage.steps.begin(), stage.steps.end());
      report_.cutbacks.insert(report_.cutbacks.end(), stage.cutbacks.begin(), stage.cutbacks.end());
      result.n_steps = report_.steps.size();
      if (std::abs(solver_->time() - next_output) <= tolerance)
        {
          record();
          result.max_head_tension = std::max(result.max_head_tension, result.curve.back().head_tension);
          next_output = std::min(next_output + p.output_interval, end);
        }
      if (snapshots && std::abs(solver_->time() - next_snapshot) <= tolerance)
        {
          write_snapshot();
          next_snapshot = std::min(next_snapshot + p.snapshot_interval, end);
        }
      // At the end both targets stay at `end`; the loop condition stops.
    }
  return result;
}
} // namespace geohybrid::fem
