// The explicit solver's vectors from the cells (explicit_solver.h): the lumped mass with the body
// force, the cells' cached shape gradients and their colours, the internal force (threads over the
// colours), the external force, and the prescribed displacements.
#include "explicit_solver.h"

#include "fem/constitutive/plane_strain_tensors.h"

#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace geohybrid::fem
{
double ExplicitSolver::energy_weight_at(const dealii::FEValues<dim> &fe_values, unsigned int q) const
{
  if (!energy_weight_)
    return 1.0;
  const double w = energy_weight_(fe_values.quadrature_point(q));
  if (!(w >= 0.0 && w <= 1.0))
    throw std::invalid_argument("explicit solver: energy weight " + std::to_string(w) +
                                " outside [0, 1] at a quadrature point");
  return w;
}

std::map<dealii::types::global_dof_index, double> ExplicitSolver::prescribed_displacements(double time) const
{
  // The first condition that names a DoF wins, as in the implicit solver's constraints.
  std::map<dealii::types::global_dof_index, double> values;
  const dealii::Functions::ZeroFunction<dim> zero(dim);
  for (const auto &d : boundary_conditions_.displacements)
    {
      std::map<dealii::types::global_dof_index, double> these;
      if (d.displacement)
        d.displacement->set_time(time);
      dealii::VectorTools::interpolate_boundary_values(
        space_.mapping(), space_.dof_handler(), d.boundary_id,
        d.displacement ? static_cast<const dealii::Function<dim> &>(*d.displacement) : zero, these,
        dealii::ComponentMask(std::vector<bool>{d.constrain_x, d.constrain_y}));
      for (const auto &entry : these)
        if (space_.locally_owned_dofs().is_element(entry.first))
          values.insert(entry);
    }
  return values;
}

void ExplicitSolver::assemble_mass_and_body_force()
{
  mass_ = 0.0;
  body_force_ = 0.0;
  const auto &fe = space_.fe();
  dealii::FEValues<dim> fe_values(space_.mapping(), fe, space_.cell_quadrature(),
                                  dealii::update_values | dealii::update_JxW_values |
                                    (energy_weight_ ? dealii::update_quadrature_points : dealii::update_default));
  const unsigned int n_dofs = fe.n_dofs_per_cell();
  std::vector<dealii::types::global_dof_index> dof_indices(n_dofs);
  const double rho = settings_.density;
  for (const auto &cell : space_.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            const unsigned int c = fe.system_to_component_index(i).first;
            // Row sum of the consistent mass: the shape functions of a component sum to one.
            double integral = 0.0;
            for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
              integral += fe_values.shape_value_component(i, q, c) * fe_values.JxW(q) * energy_weight_at(fe_values, q);
            mass_[dof_indices[i]] += rho * integral;
            body_force_[dof_indices[i]] += rho * settings_.gravity[c] * integral;
          }
      }
  mass_.compress(dealii::VectorOperation::add);
  body_force_.compress(dealii::VectorOperation::add);
  double smallest = std::numeric_limits<double>::max();
  for (unsigned int i = 0; i < mass_.locally_owned_size(); ++i)
    smallest = std::min(smallest, mass_.local_element(i));
  if (dealii::Utilities::MPI::min(smallest, space_.communicator()) <= 0.0)
    throw std::invalid_argument(energy_weight_ ? "explicit solver: energy weight: a node has no mass left (the mesh "
                                                 "reaches past the overlap band, where the continuum's weight is 0)"
                                               : "explicit solver: the row-sum lumped mass is not positive at some "
                                                 "node (a badly distorted cell?)");
}

void ExplicitSolver::build_cell_cache()
{
  const auto &fe = space_.fe();
  const unsigned int n_dofs = fe.n_dofs_per_cell(), n_q = space_.cell_quadrature().size();
  const unsigned int n_scalar = fe.base_element(0).n_dofs_per_cell();
  dof_component_.resize(n_dofs);
  dof_scalar_.resize(n_dofs);
  for (unsigned int i = 0; i < n_dofs; ++i)
    {
      dof_component_[i] = fe.system_to_component_index(i).first;
      dof_scalar_[i] = fe.system_to_component_index(i).second;
    }
  dealii::FEValues<dim> fe_values(space_.mapping(), fe, space_.cell_quadrature(),
                                  dealii::update_gradients | dealii::update_JxW_values |
                                    (energy_weight_ ? dealii::update_quadrature_points : dealii::update_default));
  // The step sums a component's DoFs of a cell in the cell's DoF order through their scalar
  // shapes in increasing order (add_cell_internal_force): the two orders must be the same, as
  // they are in FESystem's numbering of FE_Q's.
  for (unsigned int i = 0; i < n_dofs; ++i)
    for (unsigned int j = i + 1; j < n_dofs; ++j)
      if (dof_component_[i] == dof_component_[j] && dof_scalar_[i] >= dof_scalar_[j])
        throw std::logic_error("explicit solver: a component's DoFs out of the order of their shape functions");
  const auto &partitioner = *displacement_.get_partitioner();
  std::vector<dealii::types::global_dof_index> dof_indices(n_dofs);
  cells_ = CellCache();
  cells_.n_dofs = n_dofs;
  cells_.n_points = n_q;
  cells_.n_scalar = n_scalar;
  for (const auto &cell : space_.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dof_indices);
        for (const auto g : dof_indices)
          cells_.local_dofs.push_back(partitioner.global_to_local(g));
        for (const auto &p : material_points_.at(cell))
          cells_.points.push_back(p.get());
        const std::size_t first_gradient = cells_.gradients.size();
        cells_.gradients.resize(first_gradient + n_q * n_scalar);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            cells_.JxW.push_back(fe_values.JxW(q) * energy_weight_at(fe_values, q));
            for (unsigned int i = 0; i < n_dofs; ++i)
              cells_.gradients[first_gradient + q * n_scalar + dof_scalar_[i]] =
                fe_values.shape_grad_component(i, q, dof_component_[i]);
          }
      }
  // Colours: greedy in cell order, the lowest colour none of the cell's DoFs has yet (a
  // structured Q1 or Q2 mesh takes 4).
  std::vector<std::uint64_t> dof_colours(partitioner.locally_owned_size() + partitioner.n_ghost_indices(), 0);
  colours_.clear();
  for (unsigned int k = 0; k < cells_.n_cells(); ++k)
    {
      const unsigned int *dofs = &cells_.local_dofs[k * n_dofs];
      std::uint64_t taken = 0;
      for (unsigned int i = 0; i < n_dofs; ++i)
        taken |= dof_colours[dofs[i]];
      unsigned int colour = 0;
      while (colour < 64 && (taken >> colour & 1u))
        ++colour;
      if (colour == 64)
        throw std::logic_error("explicit solver: more than 64 colours of cells (a DoF in more than 64 cells?)");
      for (unsigned int i = 0; i < n_dofs; ++i)
        dof_colours[dofs[i]] |= std::uint64_t(1) << colour;
      if (colour >= colours_.size())
        colours_.resize(colour + 1);
      colours_[colour].push_back(k);
    }
}

template <unsigned int n_scalar>
void ExplicitSolver::add_cell_internal_force(unsigned int cell, const Vector &displacement_increment)
{
  constexpr unsigned int n_dofs = dim * n_scalar;
  const unsigned int n_points = cells_.n_points;
  const unsigned int *local_dofs = &cells_.local_dofs[cell * n_dofs];
  MaterialPoint *const *points = &cells_.points[cell * n_points];
  const double *JxW = &cells_.JxW[cell * n_points];
  // The increment per component and scalar shape: a component's DoFs in the cell's DoF order
  // (build_cell_cache checks that this is the order of their shapes).
  double increment[dim][n_scalar];
  for (unsigned int i = 0; i < n_dofs; ++i)
    increment[dof_component_[i]][dof_scalar_[i]] = displacement_increment.local_element(local_dofs[i]);
  dealii::Tensor<1, dim> cell_force[n_scalar]; // per scalar shape, both components
  for (unsigned int q = 0; q < n_points; ++q)
    {
      const dealii::Tensor<1, dim> *gradients = &cells_.gradients[(cell * n_points + q) * n_scalar];
      // grad du: each entry sums its terms in the cell's DoF order, as it always has (the same
      // bits), but with the loops' bounds known the entries stay in registers.
      dealii::Tensor<2, dim> displacement_gradient;
      for (unsigned int c = 0; c < dim; ++c)
        for (unsigned int j = 0; j < n_scalar; ++j)
          for (unsigned int d = 0; d < dim; ++d)
            displacement_gradient[c][d] += increment[c][j] * gradients[j][d];
      // Explicit: every step is committed, so the update starts from the last step's stress. No
      // tangent: nothing here assembles a stiffness.
      MaterialPoint &point = *points[q];
      const StressOnlyUpdate update = soil_.update_stress(point.stress, dealii::symmetrize(displacement_gradient));
      point.stress = point.trial_stress = update.stress;
      point.plastic_strain += update.plastic_strain_increment;
      point.trial_plastic_strain = point.plastic_strain;
      point.region = point.trial_region = update.region;
      // f_i = int sigma : sym(e_c x grad phi_j) = int (sigma grad phi_j)_c.
      const dealii::SymmetricTensor<2, dim> in_plane_stress = in_plane_part(update.stress);
      for (unsigned int j = 0; j < n_scalar; ++j)
        cell_force[j] += (in_plane_stress * gradients[j]) * JxW[q];
    }
  for (unsigned int i = 0; i < n_dofs; ++i)
    internal_force_.local_element(local_dofs[i]) += cell_force[dof_scalar_[i]][dof_component_[i]];
}

void ExplicitSolver::assemble_internal_force(const Vector &displacement_increment)
{
  internal_force_ = 0.0;
  const unsigned int n_scalar = cells_.n_scalar;
  AssertThrow(n_scalar == 4 || n_scalar == 9, dealii::ExcMessage("explicit solver: Q1 or Q2 elements only"));
  // Colour by colour: a colour's cells share no DoF, so its threads write to distinct entries
  // and each DoF sums its cells in colour order, whatever the number of threads.
  // One parallel region for all colours (waking the threads costs more than a colour's cells
  // on a small mesh); the loop's implicit barrier separates the colours.
#pragma omp parallel num_threads(settings_.n_threads) if (settings_.n_threads > 1)
  for (const std::vector<unsigned int> &colour : colours_)
    {
      const auto n_cells = static_cast<std::ptrdiff_t>(colour.size());
#pragma omp for schedule(static)
      for (std::ptrdiff_t k = 0; k < n_cells; ++k)
        if (n_scalar == 4)
          add_cell_internal_force<4>(colour[k], displacement_increment);
        else
          add_cell_internal_force<9>(colour[k], displacement_increment);
    }
  if (sheet_)
    sheet_->compute_forces(displacement_, material_points_, internal_force_);
  internal_force_.compress(dealii::VectorOperation::add);
}

void ExplicitSolver::assemble_external_force(double time)
{
  external_force_ = body_force_;
  added_force_ = 0.0;
  if (!boundary_conditions_.tractions.empty() || !boundary_conditions_.pressures.empty())
    {
      boundary_conditions_.set_load_time(time);
      const auto &fe = space_.fe();
      dealii::FEFaceValues<dim> face_values(space_.mapping(), fe, space_.face_quadrature(),
                                            dealii::update_values | dealii::update_quadrature_points |
                                              dealii::update_normal_vectors | dealii::update_JxW_values);
      const dealii::FEValuesExtractors::Vector u(0);
      const unsigned int n_dofs = fe.n_dofs_per_cell();
      dealii::Vector<double> cell_external(n_dofs);
      std::vector<dealii::types::global_dof_index> dof_indices(n_dofs);
      for (const auto &cell : space_.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned() && cell->at_boundary())
          {
            cell_external = 0.0;
            boundary_conditions_.add_boundary_loads(cell, face_values, cell_external);
            cell->get_dof_indices(dof_indices);
            external_force_.add(dof_indices, cell_external);
          }
    }
  external_force_.compress(dealii::VectorOperation::add);
}
} // namespace geohybrid::fem
