#include "sheet_interface.h"

#include "fem/sheet_interface_law.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::fem
{
EmbeddedSheet::EmbeddedSheet(const DisplacementSpace &space, const TrussSheet &sheet, std::vector<SheetClamp> clamps,
                             const std::string &where)
  : space_(space), sheet_(sheet), path_([&] {
    std::vector<dealii::Point<dim>> nodes;
    for (std::size_t k = 0; k < sheet.n_nodes(); ++k)
      nodes.push_back(sheet.node(k));
    return nodes;
  }()),
    clamps_(std::move(clamps))
{
  const std::size_t n = sheet_.n_nodes();
  clamped_.assign(n, false);
  for (const auto &c : clamps_)
    {
      if (c.node >= n || !c.displacement)
        throw std::invalid_argument(where + ": a clamp holds node " + std::to_string(c.node) + " of a sheet of " +
                                    std::to_string(n) + " nodes" + (c.displacement ? "" : ", without a displacement"));
      clamped_[c.node] = true;
    }
  displacement_.assign(n, Force());
  velocity_.assign(n, Force());
  truss_force_.assign(n, Force());
  node_load_.assign(n, Force());
  added_mass_.assign(n, 0.0);
  interface_force_.assign(n, Force());
  shear_stress_.assign(n, 0.0);
  shared_.assign(6 * n, 0.0);
  normal_stress_.assign(n, 0.0);

  const auto &fe = space_.fe();
  for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
    components_.push_back(fe.system_to_component_index(i).first);
  soil_points_.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      SlidingSoilPoint &p = soil_points_[k];
      // A node starts at its own point; on a corner, on the segment towards the clamp, where a
      // pull takes it.
      p.arc_length = path_.vertex_arc_length(k);
      p.segment = k > 0 ? static_cast<unsigned int>(k - 1) : 0;
      p.shape_values.resize(fe.n_dofs_per_cell());
      p.dof_indices.resize(fe.n_dofs_per_cell());
      p.material_points.reserve(space_.cell_quadrature().size());
      SheetSoilCell cell;
      dealii::Point<dim> unit;
      if (!find_sheet_cell(space_, sheet_.node(k), cell, unit))
        throw sheet_node_outside_mesh(where, k, sheet_.node(k));
      set_soil_cell(p, cell, unit);
    }
}

void EmbeddedSheet::set_soil_cell(SlidingSoilPoint &p, const dealii::DoFHandler<dim>::cell_iterator &cell,
                                  const dealii::Point<dim> &unit_point)
{
  if (p.cell.state() != dealii::IteratorState::valid || cell != p.cell)
    {
      p.cell = cell;
      p.owned = cell->is_locally_owned();
      // The DoFs and the material points are fetched where the forces are computed (they need
      // the soil's history): mark them stale.
      p.material_points.clear();
    }
  if (!p.owned)
    return;
  const auto &fe = space_.fe();
  for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
    p.shape_values[i] = fe.shape_value(i, unit_point);
}

void EmbeddedSheet::move_soil_point(std::size_t k, double s, unsigned int segment)
{
  SlidingSoilPoint &p = soil_points_[k];
  p.arc_length = s;
  p.segment = segment;
  const dealii::Point<dim> x = path_.point(path_.clamped(s), p.segment);
  SheetSoilCell cell = p.cell;
  dealii::Point<dim> unit;
  // A step moves a point by a small part of a cell: a few neighbours suffice; the search from the
  // coarse cells is the fallback (a point that crossed a region this rank only has coarse).
  if (walk_to_sheet_cell(space_.mapping(), cell, x, unit, 8))
    cell = smallest_id_sheet_cell(space_.mapping(), cell, x, unit);
  else if (!find_sheet_cell(space_, x, cell, unit))
    {
      std::ostringstream message;
      message << "sheet: the soil point of node " << k << " slid to (" << x[0] << ", " << x[1]
              << ") m, outside the soil mesh (the sheet's reference path leaves the mesh between its nodes)";
      throw std::runtime_error(message.str());
    }
  set_soil_cell(p, cell, unit);
}

double EmbeddedSheet::stable_time_step() const
{
  // Gershgorin: omega^2 <= 2 k_ii / m for a node whose springs are its two segments (J / l0 each)
  // and the two faces' interface (2 max(k_n, k_s) L_k).
  const auto &p = sheet_.parameters();
  const double k_interface = 2.0 * std::max(p.interface.normal_stiffness, p.interface.shear_stiffness);
  double smallest = std::numeric_limits<double>::max();
  for (std::size_t k = 0; k < sheet_.n_nodes(); ++k)
    {
      const double stiffness = sheet_.node_stiffness(k, k_interface * sheet_.tributary_length(k));
      smallest = std::min(smallest, 2.0 / std::sqrt(2.0 * stiffness / node_mass(k)));
    }
  return smallest;
}

void EmbeddedSheet::compute_forces(const Vector &soil_displacement, MaterialPointHistory &material_points,
                                   Vector &soil_internal_force)
{
  const std::size_t n = sheet_.n_nodes();
  const SheetInterfaceLaw law(sheet_.parameters().interface);
  // Packed for one MPI sum: the interface force (2 per node), tau (1 per node), the soil point's
  // new arc length and segment (1 and 1 per node), sigma_nn (1 per node); each from the node's owner, zero elsewhere.
  std::fill(shared_.begin(), shared_.end(), 0.0);
  for (std::size_t k = 0; k < n; ++k)
    {
      SlidingSoilPoint &p = soil_points_[k];
      if (!p.owned)
        continue;
      if (p.material_points.empty()) // a new cell: its DoFs and points
        {
          p.cell->get_dof_indices(p.dof_indices);
          for (const auto &point : material_points.at(p.cell))
            p.material_points.push_back(point.get());
        }
      Force soil_u;
      for (unsigned int i = 0; i < p.dof_indices.size(); ++i)
        soil_u[components_[i]] += p.shape_values[i] * soil_displacement[p.dof_indices[i]];
      // The node's soil point moves to the foot of the node on the path, the path displaced with
      // the soil (by the displacement at the last point: the soil's strain over a step's slip is
      // negligible); the slip is the distance it moved along the path, and the gap what is left,
      // along the normal of the part it is on. Beyond the path's ends, the path goes on straight
      // and the soil is that at the end.
      const dealii::Point<dim> node = sheet_.node(k) + displacement_[k] - soil_u;
      const SheetPath::Location foot = path_.nearest_point(node, p.segment);
      const Force t = path_.tangent(foot.segment), normal = path_.normal(foot.segment);
      const double gap_n = (node - path_.point(foot.arc_length, foot.segment)) * normal;
      const double L = sheet_.tributary_length(k);

      const double sigma_nn = mean_normal_stress(p.material_points, normal);
      const double slip_increment = foot.arc_length - p.arc_length;
      const double tau = law.shear(shear_stress_[k], slip_increment, sigma_nn).shear_stress;

      const Force force = -2.0 * L * (tau * t + law.normal_stiffness() * gap_n * normal);
      shared_[2 * k] = force[0];
      shared_[2 * k + 1] = force[1];
      shared_[2 * n + k] = tau;
      shared_[3 * n + k] = foot.arc_length;
      shared_[4 * n + k] = foot.segment;
      shared_[5 * n + k] = sigma_nn;
      // The soil feels -force at P(s_k): its internal force (f_int, resisting) gains +force N_i.
      for (unsigned int i = 0; i < p.dof_indices.size(); ++i)
        soil_internal_force[p.dof_indices[i]] += force[components_[i]] * p.shape_values[i];
    }
  dealii::Utilities::MPI::sum(shared_, space_.communicator(), shared_);
  for (std::size_t k = 0; k < n; ++k)
    {
      interface_force_[k] = Force({shared_[2 * k], shared_[2 * k + 1]});
      shear_stress_[k] = shared_[2 * n + k];
      normal_stress_[k] = shared_[5 * n + k];
      // Every rank follows every node's point, with the same numbers: the owner may change.
      if (shared_[3 * n + k] != soil_points_[k].arc_length)
        move_soil_point(k, shared_[3 * n + k], static_cast<unsigned int>(shared_[4 * n + k]));
    }
  truss_force_ = sheet_.nodal_forces(displacement_);
}

void EmbeddedSheet::advance(double dt, double previous_dt, double mass_proportional_damping, double local_damping,
                            double new_time)
{
  const double dt_velocity = 0.5 * (previous_dt + dt), alpha = mass_proportional_damping;
  // The ledger's terms of this step (SheetEnergyLedger), booked as ExplicitSolver::take_step does.
  double kinetic_before = 0.0, truss_work = 0.0, interface_work = 0.0, damping_work = 0.0, load_work = 0.0;
  for (std::size_t k = 0; k < sheet_.n_nodes(); ++k)
    {
      if (clamped_[k])
        continue;
      const double m = node_mass(k);
      for (unsigned int c = 0; c < dim; ++c)
        {
          const double undamped_force = truss_force_[k][c] + interface_force_[k][c] + node_load_[k][c];
          double force = undamped_force;
          const double v = velocity_[k][c];
          const double v_now = v + 0.5 * previous_dt * force / m; // as in ExplicitSolver::take_step
          if (local_damping > 0.0 && v_now != 0.0)
            force -= local_damping * std::abs(force) * (v_now > 0.0 ? 1.0 : -1.0);
          const double v_new =
            ((1.0 - 0.5 * alpha * dt_velocity) * v + dt_velocity * force / m) / (1.0 + 0.5 * alpha * dt_velocity);
          velocity_[k][c] = v_new;
          const double v_mean = 0.5 * (v + v_new), du = dt_velocity * v_mean;
          kinetic_before += 0.5 * m * v * v;
          truss_work -= truss_force_[k][c] * du;
          interface_work -= interface_force_[k][c] * du;
          load_work += node_load_[k][c] * du;
          damping_work += (undamped_force - force + alpha * m * v_mean) * du;
        }
      displacement_[k] += dt * velocity_[k];
    }
  std::fill(node_load_.begin(), node_load_.end(), Force());
  double clamp_work = 0.0;
  for (const auto &c : clamps_)
    {
      const Force d = c.displacement(new_time);
      const Force v_new = (d - displacement_[c.node]) / dt;
      // The same du as a free node's, from the prescribed motion; the clamp holds the node
      // against the truss and the interface (clamp_force()), so it supplies what they take.
      const Force du = dt_velocity * 0.5 * (velocity_[c.node] + v_new);
      truss_work -= truss_force_[c.node] * du;
      interface_work -= interface_force_[c.node] * du;
      clamp_work -= (truss_force_[c.node] + interface_force_[c.node]) * du;
      velocity_[c.node] = v_new;
      displacement_[c.node] = d;
    }
  if (!advanced_)
    ledger_.initial_kinetic = kinetic_before;
  advanced_ = true;
  ledger_.truss_work += truss_work;
  ledger_.interface_work += interface_work;
  ledger_.damping_work += damping_work;
  ledger_.load_work += load_work;
  ledger_.clamp_work += clamp_work;
}

SheetEnergyLedger EmbeddedSheet::energy_ledger() const
{
  SheetEnergyLedger ledger = ledger_;
  ledger.kinetic = 0.0;
  for (std::size_t k = 0; k < sheet_.n_nodes(); ++k)
    if (!clamped_[k])
      ledger.kinetic += 0.5 * node_mass(k) * velocity_[k].norm_square();
  if (!advanced_)
    ledger.initial_kinetic = ledger.kinetic;
  return ledger;
}

EmbeddedSheetState EmbeddedSheet::export_state() const
{
  EmbeddedSheetState s;
  const auto flatten = [](const std::vector<Force> &v) {
    std::vector<double> out;
    out.reserve(dim * v.size());
    for (const Force &f : v)
      for (unsigned int c = 0; c < dim; ++c)
        out.push_back(f[c]);
    return out;
  };
  s.displacement = flatten(displacement_);
  s.velocity = flatten(velocity_);
  s.truss_force = flatten(truss_force_);
  s.interface_force = flatten(interface_force_);
  s.node_load = flatten(node_load_);
  s.shear_stress = shear_stress_;
  s.normal_stress = normal_stress_;
  for (const SlidingSoilPoint &p : soil_points_)
    {
      s.arc_length.push_back(p.arc_length);
      s.segment.push_back(p.segment);
    }
  s.ledger = ledger_;
  s.advanced = advanced_;
  return s;
}

void EmbeddedSheet::restore_state(const EmbeddedSheetState &s)
{
  const std::size_t n = sheet_.n_nodes();
  for (const std::vector<double> *v : {&s.displacement, &s.velocity, &s.truss_force, &s.interface_force, &s.node_load})
    if (v->size() != dim * n)
      throw std::invalid_argument("sheet: a saved state of " + std::to_string(v->size() / dim) +
                                  " nodes does not fit this sheet of " + std::to_string(n));
  if (s.shear_stress.size() != n || s.normal_stress.size() != n || s.arc_length.size() != n || s.segment.size() != n)
    throw std::invalid_argument("sheet: a saved state's per-node arrays do not fit this sheet of " + std::to_string(n) +
                                " nodes");
  const auto unflatten = [](const std::vector<double> &in, std::vector<Force> &out) {
    for (std::size_t k = 0; k < out.size(); ++k)
      for (unsigned int c = 0; c < dim; ++c)
        out[k][c] = in[dim * k + c];
  };
  unflatten(s.displacement, displacement_);
  unflatten(s.velocity, velocity_);
  unflatten(s.truss_force, truss_force_);
  unflatten(s.interface_force, interface_force_);
  unflatten(s.node_load, node_load_);
  shear_stress_ = s.shear_stress;
  normal_stress_ = s.normal_stress;
  for (std::size_t k = 0; k < n; ++k)
    move_soil_point(k, s.arc_length[k], s.segment[k]);
  ledger_ = s.ledger;
  advanced_ = s.advanced;
}

void EmbeddedSheet::add_node_mass(std::size_t k, double mass)
{
  if (!(mass >= 0.0) || !std::isfinite(mass))
    throw std::invalid_argument("sheet: an added node mass must be non-negative and finite, got " +
                                std::to_string(mass) + " kg/m");
  added_mass_.at(k) += mass;
}

EmbeddedSheet::Force EmbeddedSheet::interface_resultant() const
{
  Force sum;
  for (const auto &f : interface_force_)
    sum += f;
  return sum;
}

EmbeddedSheet::Force EmbeddedSheet::clamp_force(std::size_t c) const
{
  const std::size_t k = clamps_.at(c).node;
  return -(truss_force_[k] + interface_force_[k]);
}
} // namespace geohybrid::fem
