#include "explicit_solver.h"

#include "fem/constitutive/parameter_check.h"
#include "fem/constitutive/plane_strain_tensors.h"
#include "fem/initial_stress.h"
#include "fem/vtu_output.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace geohybrid::fem
{
void ExplicitSettings::validate(const std::string &where) const
{
  require_parameter(density > 0.0 && std::isfinite(density), where, "density", density,
                    "must be positive for a dynamic analysis [kg/m^3]");
  require_parameter(std::isfinite(gravity.norm()), where, "gravity", gravity.norm(), "must be finite [m/s^2]");
  require_parameter(safety_factor > 0.0 && safety_factor <= 1.0, where, "safety factor", safety_factor,
                    "must lie in (0, 1] [-]");
  require_parameter(time_step >= 0.0 && std::isfinite(time_step), where, "time step", time_step,
                    "must be zero (the stable step) or positive [s]");
  require_parameter(damping.mass_proportional >= 0.0 && std::isfinite(damping.mass_proportional), where,
                    "mass-proportional damping", damping.mass_proportional, "must be zero or positive [1/s]");
  require_parameter(damping.local >= 0.0 && damping.local < 1.0, where, "local damping", damping.local,
                    "must lie in [0, 1) [-]");
  require_parameter(n_threads >= 1, where, "threads", n_threads, "must be at least 1");
}

ExplicitSolver::ExplicitSolver(const dealii::parallel::distributed::Triangulation<dim> &mesh, const SoilModel &soil,
                               const BoundaryConditions &boundary_conditions, const ExplicitSettings &settings)
  : soil_(soil)
  , boundary_conditions_(boundary_conditions)
  , settings_(settings)
  , space_(mesh, settings.element_degree)
{
  const std::string where = "explicit solver";
  settings_.validate(where);
  boundary_conditions_.validate(mesh, where);
  // A lumped mass on hanging nodes would need the constraints in every vector operation; the
  // solver is meant for the conforming meshes of meshes/ and GridGenerator.
  const auto hanging = space_.hanging_node_constraints();
  if (dealii::Utilities::MPI::max(hanging.n_constraints(), space_.communicator()) > 0)
    throw std::invalid_argument(where + ": the mesh has hanging nodes (local refinement), which the lumped-mass "
                                        "explicit solver does not handle; refine it globally instead");
  material_points_.initialise(mesh, space_.cell_quadrature().size());

  const auto &owned = space_.locally_owned_dofs();
  const auto &relevant = space_.locally_relevant_dofs();
  const MPI_Comm comm = space_.communicator();
  for (auto *v : {&mass_, &body_force_, &external_force_, &internal_force_, &displacement_, &increment_})
    v->reinit(owned, relevant, comm);
  velocity_.reinit(owned, comm);
  added_force_.reinit(owned, comm);

  const unsigned int n_owned = owned.n_elements();
  const dealii::IndexSet x_dofs =
    dealii::DoFTools::extract_dofs(space_.dof_handler(), dealii::ComponentMask(std::vector<bool>{true, false}));
  x_component_.resize(n_owned);
  for (unsigned int i = 0; i < n_owned; ++i)
    x_component_[i] = x_dofs.is_element(owned.nth_index_in_set(i)) ? 1 : 0;
  constrained_.assign(n_owned, false);
  prescribed_ = prescribed_displacements(0.0);
  for (const auto &entry : prescribed_)
    constrained_[owned.index_within_set(entry.first)] = true;
  // Supports that do not move (no function: u = 0) are the same at every step: interpolated once
  // (here). Interpolating boundary values visits every boundary face and costs more than the rest
  // of a small mesh's step (a coupled run steps the continuum at the particles' step).
  fixed_supports_ = std::all_of(boundary_conditions_.displacements.begin(), boundary_conditions_.displacements.end(),
                                [](const DisplacementBoundary &d) { return !d.displacement; });

  assemble_mass_and_body_force();
  build_cell_cache();
  critical_time_step_ = compute_critical_time_step();
  if (settings_.time_step > stable_time_step())
    {
      std::ostringstream message;
      message << where << ": parameter 'time step' = " << settings_.time_step << " s exceeds the stable step "
              << stable_time_step() << " s of this mesh and soil (safety factor " << settings_.safety_factor
              << " times the critical step " << critical_time_step_
              << " s); use a smaller step, or 0 for the stable one";
      throw std::invalid_argument(message.str());
    }
  time_step_ = settings_.time_step > 0.0 ? settings_.time_step : stable_time_step();

  increment_ = 0.0;
  assemble_internal_force(increment_);
  assemble_external_force(time_);
}

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

void ExplicitSolver::set_energy_weight(const std::function<double(const dealii::Point<dim> &)> &weight)
{
  if (energy_weight_)
    throw std::invalid_argument("explicit solver: the energy weight is already set");
  if (n_steps_ > 0)
    throw std::invalid_argument("explicit solver: the energy weight must be set before the first step");
  energy_weight_ = weight;
  assemble_mass_and_body_force();
  build_cell_cache();
  critical_time_step_ = compute_critical_time_step();
  if (settings_.time_step > stable_time_step())
    {
      std::ostringstream message;
      message << "explicit solver: energy weight: parameter 'time step' = " << settings_.time_step
              << " s exceeds the stable step " << stable_time_step() << " s of the weighted mesh";
      throw std::invalid_argument(message.str());
    }
  time_step_ = settings_.time_step > 0.0 ? settings_.time_step : stable_time_step();
  increment_ = 0.0;
  assemble_internal_force(increment_);
  assemble_external_force(time_);
}

void ExplicitSolver::set_initial_stress(const std::function<StressTensor(const dealii::Point<dim> &)> &stress,
                                        const std::string &description)
{
  set_material_point_stress(space_, soil_, material_points_, stress, description);
  increment_ = 0.0;
  assemble_internal_force(increment_);
}

void ExplicitSolver::set_initial_stress(const GeostaticStress &geostatic)
{
  geostatic.validate("geostatic stress");
  set_initial_stress([&](const dealii::Point<dim> &x) { return geostatic.stress_at(x); },
                     "the geostatic stress (K0 = " + std::to_string(geostatic.k0) + ")");
}

void ExplicitSolver::set_initial_displacement(const dealii::Function<dim> &displacement)
{
  if (displacement.n_components != dim)
    throw std::invalid_argument("explicit solver: the initial displacement function has " +
                                std::to_string(displacement.n_components) + " components instead of 2");
  if (n_steps_ > 0)
    throw std::invalid_argument("explicit solver: the initial displacement must be set before the first step");
  dealii::PETScWrappers::MPI::Vector interpolated(space_.locally_owned_dofs(), space_.communicator());
  dealii::VectorTools::interpolate(space_.mapping(), space_.dof_handler(), displacement, interpolated);
  const auto &owned = space_.locally_owned_dofs();
  for (unsigned int i = 0; i < displacement_.locally_owned_size(); ++i)
    {
      increment_.local_element(i) = interpolated[owned.nth_index_in_set(i)] - displacement_.local_element(i);
      displacement_.local_element(i) += increment_.local_element(i);
    }
  increment_.update_ghost_values();
  displacement_.update_ghost_values();
  assemble_internal_force(increment_);
}

void ExplicitSolver::set_initial_velocity(const dealii::Function<dim> &velocity)
{
  if (velocity.n_components != dim)
    throw std::invalid_argument("explicit solver: the initial velocity function has " +
                                std::to_string(velocity.n_components) + " components instead of 2");
  dealii::PETScWrappers::MPI::Vector interpolated(space_.locally_owned_dofs(), space_.communicator());
  dealii::VectorTools::interpolate(space_.mapping(), space_.dof_handler(), velocity, interpolated);
  const auto &owned = space_.locally_owned_dofs();
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    velocity_.local_element(i) = constrained_[i] ? 0.0 : interpolated[owned.nth_index_in_set(i)];
}

void ExplicitSolver::attach_sheet(const TrussSheet &sheet, std::vector<SheetClamp> clamps)
{
  auto embedded = std::make_unique<EmbeddedSheet>(space_, sheet, std::move(clamps), "explicit solver: sheet");
  const double sheet_step = embedded->stable_time_step();
  if (sheet_step < time_step_)
    {
      // omega scales as 1/sqrt(m): the mass must grow by (dt / dt_sheet)^2.
      const double needed = sheet.parameters().mass_scaling * std::pow(time_step_ / sheet_step, 2);
      std::ostringstream message;
      message << "explicit solver: sheet: parameter 'mass scaling' = " << sheet.parameters().mass_scaling
              << " leaves the sheet's nodes stable only below " << sheet_step << " s, less than the time step "
              << time_step_ << " s; a mass scaling of at least " << needed
              << " is needed (the sheet's inertia is irrelevant in a quasi-static pull)";
      throw std::invalid_argument(message.str());
    }
  sheet_ = std::move(embedded);
  increment_ = 0.0;
  assemble_internal_force(increment_);
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

double ExplicitSolver::compute_critical_time_step() const
{
  // Irons: omega_max of the assembled lumped system <= max over cells of the cell's omega_max, the
  // square root of the largest eigenvalue of M_e^-1/2 K_e M_e^-1/2 with the elastic stiffness.
  const auto &fe = space_.fe();
  dealii::FEValues<dim> fe_values(space_.mapping(), fe, space_.cell_quadrature(),
                                  dealii::update_values | dealii::update_gradients | dealii::update_JxW_values |
                                    (energy_weight_ ? dealii::update_quadrature_points : dealii::update_default));
  const dealii::FEValuesExtractors::Vector u(0);
  const unsigned int n_dofs = fe.n_dofs_per_cell();
  const TangentTensor &C = soil_.elasticity().plane_strain_stiffness();
  std::vector<StrainTensor> shape_strains(n_dofs);
  std::vector<double> cell_mass(n_dofs);
  double largest_omega_squared = 0.0;
  for (const auto &cell : space_.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        dealii::LAPACKFullMatrix<double> scaled(n_dofs, n_dofs);
        std::fill(cell_mass.begin(), cell_mass.end(), 0.0);
        for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
          {
            const double JxW = fe_values.JxW(q) * energy_weight_at(fe_values, q);
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                shape_strains[i] = fe_values[u].symmetric_gradient(i, q);
                cell_mass[i] += settings_.density *
                                fe_values.shape_value_component(i, q, fe.system_to_component_index(i).first) * JxW;
              }
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const auto stress_of_i = C * shape_strains[i];
                for (unsigned int j = 0; j < n_dofs; ++j)
                  scaled(i, j) += (stress_of_i * shape_strains[j]) * JxW;
              }
          }
        // A cell with zero energy weight at all its points has neither mass nor stiffness.
        if (*std::min_element(cell_mass.begin(), cell_mass.end()) <= 0.0)
          continue;
        for (unsigned int i = 0; i < n_dofs; ++i)
          for (unsigned int j = 0; j < n_dofs; ++j)
            scaled(i, j) /= std::sqrt(cell_mass[i] * cell_mass[j]);
        scaled.compute_eigenvalues(false, false);
        for (unsigned int i = 0; i < n_dofs; ++i)
          largest_omega_squared = std::max(largest_omega_squared, scaled.eigenvalue(i).real());
      }
  largest_omega_squared = dealii::Utilities::MPI::max(largest_omega_squared, space_.communicator());
  return 2.0 / std::sqrt(largest_omega_squared);
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
  const auto &partitioner = *displacement_.get_partitioner();
  std::vector<dealii::types::global_dof_index> dof_indices(n_dofs);
  cells_.clear();
  for (const auto &cell : space_.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        CellCache c;
        cell->get_dof_indices(dof_indices);
        for (const auto g : dof_indices)
          c.local_dofs.push_back(partitioner.global_to_local(g));
        for (const auto &p : material_points_.at(cell))
          c.points.push_back(p.get());
        c.gradients.resize(n_q * n_scalar);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            c.JxW.push_back(fe_values.JxW(q) * energy_weight_at(fe_values, q));
            for (unsigned int i = 0; i < n_dofs; ++i)
              c.gradients[q * n_scalar + dof_scalar_[i]] = fe_values.shape_grad_component(i, q, dof_component_[i]);
          }
        cells_.push_back(std::move(c));
      }
  // Colours: greedy in cell order, the lowest colour none of the cell's DoFs has yet (a
  // structured Q1 or Q2 mesh takes 4).
  std::vector<std::uint64_t> dof_colours(partitioner.locally_owned_size() + partitioner.n_ghost_indices(), 0);
  colours_.clear();
  for (unsigned int k = 0; k < cells_.size(); ++k)
    {
      std::uint64_t taken = 0;
      for (const unsigned int i : cells_[k].local_dofs)
        taken |= dof_colours[i];
      unsigned int colour = 0;
      while (colour < 64 && (taken >> colour & 1u))
        ++colour;
      if (colour == 64)
        throw std::logic_error("explicit solver: more than 64 colours of cells (a DoF in more than 64 cells?)");
      for (const unsigned int i : cells_[k].local_dofs)
        dof_colours[i] |= std::uint64_t(1) << colour;
      if (colour >= colours_.size())
        colours_.resize(colour + 1);
      colours_[colour].push_back(k);
    }
}

void ExplicitSolver::assemble_internal_force(const Vector &displacement_increment)
{
  internal_force_ = 0.0;
  const unsigned int n_dofs = dof_component_.size();
  const unsigned int n_scalar = space_.fe().base_element(0).n_dofs_per_cell();
  constexpr unsigned int max_scalar = 9; // Q2
  AssertThrow(n_scalar <= max_scalar, dealii::ExcMessage("explicit solver: Q1 or Q2 elements only"));
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
        {
          const CellCache &c = cells_[colour[k]];
          double increment[2 * max_scalar];
          dealii::Tensor<1, dim> cell_force[max_scalar]; // per scalar shape, both components
          for (unsigned int i = 0; i < n_dofs; ++i)
            increment[i] = displacement_increment.local_element(c.local_dofs[i]);
          for (unsigned int q = 0; q < c.points.size(); ++q)
            {
              const dealii::Tensor<1, dim> *gradients = &c.gradients[q * n_scalar];
              dealii::Tensor<2, dim> displacement_gradient;
              for (unsigned int i = 0; i < n_dofs; ++i)
                for (unsigned int d = 0; d < dim; ++d)
                  displacement_gradient[dof_component_[i]][d] += increment[i] * gradients[dof_scalar_[i]][d];
              // Explicit: every step is committed, so the update starts from the last step's stress.
              MaterialPoint &point = *c.points[q];
              const StressUpdate update = soil_.update(point.stress, dealii::symmetrize(displacement_gradient));
              point.stress = point.trial_stress = update.stress;
              point.plastic_strain += update.plastic_strain_increment;
              point.trial_plastic_strain = point.plastic_strain;
              point.region = point.trial_region = update.region;
              // f_i = int sigma : sym(e_c x grad phi_j) = int (sigma grad phi_j)_c.
              const dealii::SymmetricTensor<2, dim> in_plane_stress = in_plane_part(update.stress);
              for (unsigned int j = 0; j < n_scalar; ++j)
                cell_force[j] += (in_plane_stress * gradients[j]) * c.JxW[q];
            }
          for (unsigned int i = 0; i < n_dofs; ++i)
            internal_force_.local_element(c.local_dofs[i]) += cell_force[dof_scalar_[i]][dof_component_[i]];
        }
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
      for (auto &t : boundary_conditions_.tractions)
        t.traction->set_time(time);
      for (auto &p : boundary_conditions_.pressures)
        p.pressure->set_time(time);
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

void ExplicitSolver::take_step(double dt)
{
  // Central differences with the velocity at half steps; with a step that changes, the velocity
  // jump uses the mean of the two half steps around t_n.
  const double dt_velocity = 0.5 * (previous_step_ + dt);
  const double alpha = settings_.damping.mass_proportional, alpha_local = settings_.damping.local;
  const double new_time = time_ + dt;
  if (!fixed_supports_)
    prescribed_ = prescribed_displacements(new_time);
  const auto &prescribed = prescribed_;
  const auto &owned = space_.locally_owned_dofs();
  // The ledger's terms of this step (ExplicitEnergyLedger): each force times du = dt_velocity
  // (v_n-1/2 + v_n+1/2) / 2, which makes them add up to the change of the kinetic energy.
  double internal_work = 0.0, damping_work = 0.0, gravity_work = 0.0, load_work = 0.0, added_work = 0.0;
  double kinetic_before = 0.0;
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    {
      if (constrained_[i])
        continue;
      const double undamped_force = external_force_.local_element(i) - internal_force_.local_element(i);
      double force = undamped_force;
      const double v = velocity_.local_element(i);
      // The local damping opposes the velocity at t_n, where the force acts (v_{n-1/2} plus half
      // a step of undamped acceleration, as Yade's second-order Cundall damping): the sign of
      // v_{n-1/2} alone would be that of round-off at a node that a wave is about to reach, and
      // the run would depend on the number of ranks.
      const double v_now = v + 0.5 * previous_step_ * force / mass_.local_element(i);
      const bool damped = undamped_.empty() || !undamped_[i];
      const double alpha_i = damped ? alpha : 0.0;
      if (damped && alpha_local > 0.0 && v_now != 0.0)
        force -= alpha_local * std::abs(force) * (v_now > 0.0 ? 1.0 : -1.0);
      // (v+ - v-)/dt = f/m - alpha (v+ + v-)/2
      const double m = mass_.local_element(i);
      const double v_new = ((1.0 - 0.5 * alpha_i * dt_velocity) * v + dt_velocity * force / m) /
                           (1.0 + 0.5 * alpha_i * dt_velocity);
      velocity_.local_element(i) = v_new;
      const double v_mean = 0.5 * (v + v_new), du = dt_velocity * v_mean;
      kinetic_before += 0.5 * m * v * v;
      internal_work += internal_force_.local_element(i) * du;
      // The local damping's force, undamped_force - force, and the mass-proportional alpha m v_mean.
      damping_work += (undamped_force - force + alpha_i * m * v_mean) * du;
      const double added = added_force_.local_element(i), body = body_force_.local_element(i);
      gravity_work += body * du;
      added_work += added * du;
      load_work += (external_force_.local_element(i) - body - added) * du;
    }
  if (n_steps_ == 0)
    ledger_.initial_kinetic = kinetic_before;
  ledger_.internal_work += internal_work;
  ledger_.damping_work += damping_work;
  ledger_.gravity_work += gravity_work;
  ledger_.load_work += load_work;
  ledger_.added_force_work += added_work;
  for (const auto &entry : prescribed)
    {
      const unsigned int i = owned.index_within_set(entry.first);
      velocity_.local_element(i) = (entry.second - displacement_.local_element(i)) / dt;
    }
  if (sheet_)
    sheet_->advance(dt, previous_step_, alpha, alpha_local, new_time);
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    {
      increment_.local_element(i) = dt * velocity_.local_element(i);
      displacement_.local_element(i) += increment_.local_element(i);
    }
  // Prescribed values exactly, not up to the round-off of u + dt (g - u)/dt.
  for (const auto &entry : prescribed)
    displacement_.local_element(owned.index_within_set(entry.first)) = entry.second;
  increment_.update_ghost_values();
  displacement_.update_ghost_values();

  assemble_internal_force(increment_);
  assemble_external_force(new_time);
  time_ = new_time;
  previous_step_ = dt;
  ++n_steps_;
}

void ExplicitSolver::set_undamped_dofs(const std::vector<unsigned int> &local_dofs)
{
  const unsigned int n = velocity_.locally_owned_size();
  if (local_dofs.empty())
    {
      undamped_.clear();
      return;
    }
  std::vector<bool> undamped(n, false);
  for (const unsigned int i : local_dofs)
    {
      if (i >= n)
        throw std::invalid_argument("explicit solver: undamped DoF " + std::to_string(i) +
                                    " is not a locally owned DoF (" + std::to_string(n) + " owned)");
      undamped[i] = true;
    }
  undamped_ = std::move(undamped);
}

void ExplicitSolver::set_time_step(double dt)
{
  if (!(dt > 0.0) || dt > stable_time_step())
    {
      std::ostringstream message;
      message << "explicit solver: parameter 'time step' = " << dt << " s must be positive and at most the stable step "
              << stable_time_step() << " s";
      throw std::invalid_argument(message.str());
    }
  time_step_ = dt;
}

namespace
{
constexpr unsigned int numbers_per_material_point = 26;

void put_symmetric(std::vector<double> &out, const dealii::SymmetricTensor<2, 3> &t)
{
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      out.push_back(t[i][j]);
}

dealii::SymmetricTensor<2, 3> get_symmetric(const double *&in)
{
  dealii::SymmetricTensor<2, 3> t;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      t[i][j] = *in++;
  return t;
}
} // namespace

ExplicitSolverState ExplicitSolver::export_state() const
{
  ExplicitSolverState s;
  s.time = time_;
  s.previous_step = previous_step_;
  s.time_step = time_step_;
  s.n_steps = n_steps_;
  const auto owned = [](const Vector &v) {
    std::vector<double> out(v.locally_owned_size());
    for (unsigned int i = 0; i < v.locally_owned_size(); ++i)
      out[i] = v.local_element(i);
    return out;
  };
  s.velocity = owned(velocity_);
  s.displacement = owned(displacement_);
  s.internal_force = owned(internal_force_);
  s.external_force = owned(external_force_);
  s.added_force = owned(added_force_);
  for (const CellCache &c : cells_)
    for (const MaterialPoint *p : c.points)
      {
        put_symmetric(s.material_points, p->stress);
        put_symmetric(s.material_points, p->plastic_strain);
        put_symmetric(s.material_points, p->trial_stress);
        put_symmetric(s.material_points, p->trial_plastic_strain);
        s.material_points.push_back(static_cast<double>(static_cast<int>(p->region)));
        s.material_points.push_back(static_cast<double>(static_cast<int>(p->trial_region)));
      }
  s.ledger = ledger_;
  s.has_sheet = sheet_ != nullptr;
  if (sheet_)
    s.sheet = sheet_->export_state();
  return s;
}

void ExplicitSolver::restore_state(const ExplicitSolverState &s)
{
  const unsigned int n = velocity_.locally_owned_size();
  std::size_t n_points = 0;
  for (const CellCache &c : cells_)
    n_points += c.points.size();
  for (const std::vector<double> *v : {&s.velocity, &s.displacement, &s.internal_force, &s.external_force, &s.added_force})
    if (v->size() != n)
      throw std::invalid_argument("explicit solver: a saved state of " + std::to_string(v->size()) +
                                  " DoFs does not fit this solver's " + std::to_string(n));
  if (s.material_points.size() != numbers_per_material_point * n_points)
    throw std::invalid_argument("explicit solver: a saved state of " +
                                std::to_string(s.material_points.size() / numbers_per_material_point) +
                                " material points does not fit this solver's " + std::to_string(n_points));
  if (s.has_sheet != (sheet_ != nullptr))
    throw std::invalid_argument(std::string("explicit solver: a saved state ") + (s.has_sheet ? "with" : "without") +
                                " a sheet does not fit this solver");
  if (!(s.time_step > 0.0) || s.time_step > stable_time_step())
    throw std::invalid_argument("explicit solver: the saved time step is not stable here");
  time_ = s.time;
  previous_step_ = s.previous_step;
  time_step_ = s.time_step;
  n_steps_ = static_cast<unsigned int>(s.n_steps);
  const auto restore = [n](const std::vector<double> &in, Vector &v) {
    for (unsigned int i = 0; i < n; ++i)
      v.local_element(i) = in[i];
  };
  restore(s.velocity, velocity_);
  restore(s.displacement, displacement_);
  restore(s.internal_force, internal_force_);
  restore(s.external_force, external_force_);
  restore(s.added_force, added_force_);
  displacement_.update_ghost_values();
  const double *in = s.material_points.data();
  for (CellCache &c : cells_)
    for (MaterialPoint *p : c.points)
      {
        p->stress = get_symmetric(in);
        p->plastic_strain = get_symmetric(in);
        p->trial_stress = get_symmetric(in);
        p->trial_plastic_strain = get_symmetric(in);
        p->region = static_cast<ReturnRegion>(static_cast<int>(*in++));
        p->trial_region = static_cast<ReturnRegion>(static_cast<int>(*in++));
      }
  ledger_ = s.ledger;
  if (sheet_)
    sheet_->restore_state(s.sheet);
}

void ExplicitSolver::step()
{
  take_step(time_step_);
}

unsigned int ExplicitSolver::advance_to(double end_time)
{
  const double remaining = end_time - time_;
  if (remaining <= 1e-12 * std::max(1.0, std::abs(end_time)))
    return 0;
  const unsigned int n = static_cast<unsigned int>(std::ceil(remaining / time_step_ * (1.0 - 1e-12)));
  const double dt = remaining / n;
  for (unsigned int k = 0; k < n; ++k)
    take_step(dt);
  time_ = end_time;
  return n;
}

double ExplicitSolver::kinetic_energy() const
{
  double energy = 0.0;
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    energy += 0.5 * mass_.local_element(i) * velocity_.local_element(i) * velocity_.local_element(i);
  return dealii::Utilities::MPI::sum(energy, space_.communicator());
}

ExplicitEnergyLedger ExplicitSolver::energy_ledger() const
{
  double kinetic = 0.0;
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    if (!constrained_[i])
      kinetic += 0.5 * mass_.local_element(i) * velocity_.local_element(i) * velocity_.local_element(i);
  const MPI_Comm comm = space_.communicator();
  ExplicitEnergyLedger sum;
  sum.kinetic = dealii::Utilities::MPI::sum(kinetic, comm);
  if (n_steps_ == 0)
    {
      sum.initial_kinetic = sum.kinetic;
      return sum;
    }
  sum.initial_kinetic = dealii::Utilities::MPI::sum(ledger_.initial_kinetic, comm);
  sum.internal_work = dealii::Utilities::MPI::sum(ledger_.internal_work, comm);
  sum.damping_work = dealii::Utilities::MPI::sum(ledger_.damping_work, comm);
  sum.gravity_work = dealii::Utilities::MPI::sum(ledger_.gravity_work, comm);
  sum.load_work = dealii::Utilities::MPI::sum(ledger_.load_work, comm);
  sum.added_force_work = dealii::Utilities::MPI::sum(ledger_.added_force_work, comm);
  return sum;
}

double ExplicitSolver::out_of_balance_ratio() const
{
  double residual = 0.0, internal = 0.0, external = 0.0;
  for (unsigned int i = 0; i < velocity_.locally_owned_size(); ++i)
    {
      const double fi = internal_force_.local_element(i), fe = external_force_.local_element(i);
      internal += fi * fi;
      external += fe * fe;
      if (!constrained_[i])
        residual += (fe - fi) * (fe - fi);
    }
  const MPI_Comm comm = space_.communicator();
  residual = std::sqrt(dealii::Utilities::MPI::sum(residual, comm));
  const double scale = std::sqrt(dealii::Utilities::MPI::sum(internal, comm)) +
                       std::sqrt(dealii::Utilities::MPI::sum(external, comm));
  return scale > 0.0 ? residual / scale : residual;
}

dealii::Tensor<1, dim> ExplicitSolver::boundary_reaction(dealii::types::boundary_id boundary_id) const
{
  const dealii::IndexSet boundary_dofs =
    dealii::DoFTools::extract_boundary_dofs(space_.dof_handler(), dealii::ComponentMask(), {boundary_id});
  const auto &owned = space_.locally_owned_dofs();
  dealii::Tensor<1, dim> reaction;
  for (const auto dof : boundary_dofs)
    if (owned.is_element(dof))
      {
        const unsigned int i = owned.index_within_set(dof);
        reaction[x_component_[i] ? 0 : 1] += internal_force_.local_element(i) - external_force_.local_element(i);
      }
  return dealii::Utilities::MPI::sum(reaction, space_.communicator());
}

std::string ExplicitSolver::write_vtu(const std::string &directory, const std::string &basename, unsigned int step)
{
  dealii::PETScWrappers::MPI::Vector owned(space_.locally_owned_dofs(), space_.communicator());
  const auto &owned_dofs = space_.locally_owned_dofs();
  for (unsigned int i = 0; i < displacement_.locally_owned_size(); ++i)
    owned[owned_dofs.nth_index_in_set(i)] = displacement_.local_element(i);
  owned.compress(dealii::VectorOperation::insert);
  dealii::PETScWrappers::MPI::Vector ghosted(owned_dofs, space_.locally_relevant_dofs(), space_.communicator());
  ghosted = owned;
  return write_soil_vtu(space_, ghosted, material_points_, directory, basename, step);
}
} // namespace geohybrid::fem
