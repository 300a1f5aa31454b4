#include "sheet_interface.h"

#include "fem/constitutive/plane_strain_tensors.h"
#include "fem/sheet_interface_law.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::fem
{
std::vector<SheetSoilPoint> locate_sheet_in_soil(const DisplacementSpace &space, const TrussSheet &sheet,
                                                 const std::string &where)
{
  const std::size_t n = sheet.n_nodes();
  std::vector<SheetSoilPoint> soil_points;
  // A node on a cell edge or vertex touches several cells, and the soil stress (sigma_nn) is that
  // of one of them: the one with the smallest CellId, whatever the partition, so that the result
  // does not depend on the number of ranks. A rank that owns one of those cells also sees all the
  // others (owned or ghost), so every such rank picks the same cell; its owner takes the node.
  const MPI_Comm comm = space.communicator();
  const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const auto &fe = space.fe();
  soil_points.resize(n);
  std::vector<unsigned int> owner(n, n_ranks);
  std::vector<dealii::Point<dim>> reference_points(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      std::vector<std::pair<dealii::DoFHandler<dim>::active_cell_iterator, dealii::Point<dim>>> around;
      try
        {
          around = dealii::GridTools::find_all_active_cells_around_point(space.mapping(), space.dof_handler(),
                                                                          sheet.node(k), 1e-10);
        }
      catch (...)
        {
          // Not in a cell this rank knows: another rank's node, or outside the mesh.
        }
      bool touches_own_cell = false;
      for (const auto &c : around)
        touches_own_cell = touches_own_cell || c.first->is_locally_owned();
      if (!touches_own_cell)
        continue;
      const std::pair<dealii::DoFHandler<dim>::active_cell_iterator, dealii::Point<dim>> *chosen = nullptr;
      for (const auto &c : around)
        if (!c.first->is_artificial() && (chosen == nullptr || c.first->id() < chosen->first->id()))
          chosen = &c;
      if (chosen->first->is_locally_owned())
        {
          owner[k] = rank;
          soil_points[k].cell = chosen->first;
          reference_points[k] = dealii::GeometryInfo<dim>::project_to_unit_cell(chosen->second);
        }
    }
  dealii::Utilities::MPI::min(owner, comm, owner);
  for (std::size_t k = 0; k < n; ++k)
    {
      if (owner[k] == n_ranks)
        {
          std::ostringstream message;
          message << where << ": node " << k << " at (" << sheet.node(k)[0] << ", " << sheet.node(k)[1]
                  << ") m lies outside the soil mesh";
          throw std::invalid_argument(message.str());
        }
      auto &p = soil_points[k];
      p.owned = owner[k] == rank;
      if (!p.owned)
        continue;
      const unsigned int n_dofs = fe.n_dofs_per_cell();
      p.shape_values.resize(n_dofs);
      p.components.resize(n_dofs);
      p.dof_indices.resize(n_dofs);
      p.cell->get_dof_indices(p.dof_indices);
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          p.components[i] = fe.system_to_component_index(i).first;
          p.shape_values[i] = fe.shape_value(i, reference_points[k]);
        }
    }
  return soil_points;
}

double sheet_normal_stress(MaterialPointHistory &material_points, const SheetSoilPoint &point,
                           const dealii::Tensor<1, dim> &normal)
{
  double sigma_nn = 0.0;
  const auto points = material_points.at(point.cell);
  for (const auto &p : points)
    sigma_nn += normal * (in_plane_part(p->stress) * normal);
  return sigma_nn / points.size();
}

EmbeddedSheet::EmbeddedSheet(const DisplacementSpace &space, const TrussSheet &sheet, std::vector<SheetClamp> clamps,
                             const std::string &where)
  : space_(space), sheet_(sheet), clamps_(std::move(clamps))
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
  interface_force_.assign(n, Force());
  committed_gap_.assign(n, Force());
  shear_stress_.assign(n, 0.0);

  soil_points_ = locate_sheet_in_soil(space_, sheet_, where);
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
      double stiffness = k_interface * sheet_.tributary_length(k);
      if (k > 0)
        stiffness += p.axial_stiffness / sheet_.rest_length(k - 1);
      if (k + 1 < sheet_.n_nodes())
        stiffness += p.axial_stiffness / sheet_.rest_length(k);
      smallest = std::min(smallest, 2.0 / std::sqrt(2.0 * stiffness / sheet_.node_mass(k)));
    }
  return smallest;
}

void EmbeddedSheet::compute_forces(const Vector &soil_displacement, MaterialPointHistory &material_points,
                                   Vector &soil_internal_force)
{
  const std::size_t n = sheet_.n_nodes();
  const SheetInterfaceLaw law(sheet_.parameters().interface);
  // Packed for one MPI sum: the interface force (2 per node), then tau (1 per node).
  std::vector<double> shared(3 * n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    {
      const auto &p = soil_points_[k];
      if (!p.owned)
        continue;
      Force soil_u;
      for (unsigned int i = 0; i < p.dof_indices.size(); ++i)
        soil_u[p.components[i]] += p.shape_values[i] * soil_displacement[p.dof_indices[i]];
      const Force gap = displacement_[k] - soil_u;
      const Force t = sheet_.tangent(k);
      const Force normal({-t[1], t[0]});
      const double L = sheet_.tributary_length(k);

      const double sigma_nn = sheet_normal_stress(material_points, p, normal);
      const double slip_increment = (gap - committed_gap_[k]) * t;
      const double tau = law.shear(shear_stress_[k], slip_increment, sigma_nn).shear_stress;
      committed_gap_[k] = gap;

      const Force force = -2.0 * L * (tau * t + law.normal_stiffness() * (gap * normal) * normal);
      shared[2 * k] = force[0];
      shared[2 * k + 1] = force[1];
      shared[2 * n + k] = tau;
      // The soil feels -force at X_k: its internal force (f_int, resisting) gains +force N_i.
      for (unsigned int i = 0; i < p.dof_indices.size(); ++i)
        soil_internal_force[p.dof_indices[i]] += force[p.components[i]] * p.shape_values[i];
    }
  dealii::Utilities::MPI::sum(shared, space_.communicator(), shared);
  for (std::size_t k = 0; k < n; ++k)
    {
      interface_force_[k] = Force({shared[2 * k], shared[2 * k + 1]});
      shear_stress_[k] = shared[2 * n + k];
    }
  truss_force_ = sheet_.nodal_forces(displacement_);
}

void EmbeddedSheet::advance(double dt, double previous_dt, double mass_proportional_damping, double local_damping,
                            double new_time)
{
  const double dt_velocity = 0.5 * (previous_dt + dt), alpha = mass_proportional_damping;
  for (std::size_t k = 0; k < sheet_.n_nodes(); ++k)
    {
      if (clamped_[k])
        continue;
      const double m = sheet_.node_mass(k);
      for (unsigned int c = 0; c < dim; ++c)
        {
          double force = truss_force_[k][c] + interface_force_[k][c];
          const double v = velocity_[k][c];
          const double v_now = v + 0.5 * previous_dt * force / m; // as in ExplicitSolver::take_step
          if (local_damping > 0.0 && v_now != 0.0)
            force -= local_damping * std::abs(force) * (v_now > 0.0 ? 1.0 : -1.0);
          velocity_[k][c] = ((1.0 - 0.5 * alpha * dt_velocity) * v + dt_velocity * force / m) /
                            (1.0 + 0.5 * alpha * dt_velocity);
        }
      displacement_[k] += dt * velocity_[k];
    }
  for (const auto &c : clamps_)
    {
      const Force d = c.displacement(new_time);
      velocity_[c.node] = (d - displacement_[c.node]) / dt;
      displacement_[c.node] = d;
    }
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
