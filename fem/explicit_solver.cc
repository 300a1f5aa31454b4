// The explicit solver (explicit_solver.h): its set-up, the stable step, the initial conditions, and
// the central-difference step. The vectors it assembles from the cells are in explicit_forces.cc,
// what a run reads of it (energy, balance, reactions) in explicit_energy_and_balance.cc, and its
// checkpointed state in explicit_solver_state.cc.
#include "explicit_solver.h"

#include "fem/constitutive/parameter_check.h"
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
  prepare_steps(where, "this mesh and soil");
}

void ExplicitSolver::prepare_steps(const std::string &where, const std::string &what_mesh)
{
  assemble_mass_and_body_force();
  build_cell_cache();
  critical_time_step_ = compute_critical_time_step();
  if (settings_.time_step > stable_time_step())
    {
      std::ostringstream message;
      message << where << ": parameter 'time step' = " << settings_.time_step << " s exceeds the stable step "
              << stable_time_step() << " s of " << what_mesh << " (safety factor " << settings_.safety_factor
              << " times the critical step " << critical_time_step_
              << " s); use a smaller step, or 0 for the stable one";
      throw std::invalid_argument(message.str());
    }
  time_step_ = settings_.time_step > 0.0 ? settings_.time_step : stable_time_step();
  increment_ = 0.0;
  assemble_internal_force(increment_);
  assemble_external_force(time_);
}

void ExplicitSolver::set_energy_weight(const std::function<double(const dealii::Point<dim> &)> &weight)
{
  if (energy_weight_)
    throw std::invalid_argument("explicit solver: the energy weight is already set");
  if (n_steps_ > 0)
    throw std::invalid_argument("explicit solver: the energy weight must be set before the first step");
  energy_weight_ = weight;
  prepare_steps("explicit solver: energy weight", "the weighted mesh");
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
