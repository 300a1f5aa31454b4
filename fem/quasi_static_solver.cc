// The implicit quasi-static solver (quasi_static_solver.h): its system, the constraints of a load
// step, the assembly of the tangent and the forces, and the load stepping with its cutbacks. The
// Newton iterations of one step and their linear solves are in quasi_static_newton.cc.
#include "quasi_static_solver.h"

#include "fem/constitutive/parameter_check.h"
#include "fem/constitutive/plane_strain_tensors.h"
#include "fem/initial_stress.h"
#include "fem/vtu_output.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace geohybrid::fem
{
void QuasiStaticSettings::validate(const std::string &where) const
{
  require_parameter(density >= 0.0 && std::isfinite(density), where, "density", density,
                    "must be zero or positive [kg/m^3]");
  require_parameter(std::isfinite(gravity.norm()), where, "gravity", gravity.norm(), "must be finite [m/s^2]");
  require_parameter(newton.relative_tolerance > 0.0, where, "Newton relative tolerance",
                    newton.relative_tolerance, "must be positive [-]");
  require_parameter(newton.absolute_tolerance >= 0.0, where, "Newton absolute tolerance",
                    newton.absolute_tolerance, "must be zero or positive [N/m]");
  require_parameter(newton.max_iterations >= 1, where, "Newton maximum iterations", newton.max_iterations,
                    "must be at least 1");
  require_parameter(linear_solver.relative_tolerance > 0.0 && linear_solver.relative_tolerance < 1.0, where,
                    "linear solver relative tolerance", linear_solver.relative_tolerance, "must lie in (0, 1) [-]");
  require_parameter(linear_solver.amg_strong_threshold > 0.0 && linear_solver.amg_strong_threshold < 1.0, where,
                    "AMG strong threshold", linear_solver.amg_strong_threshold, "must lie in (0, 1) [-]");
  require_parameter(stepping.increment > 0.0, where, "load increment", stepping.increment, "must be positive [-]");
  require_parameter(stepping.minimum_increment > 0.0 && stepping.minimum_increment <= stepping.increment, where,
                    "minimum load increment", stepping.minimum_increment,
                    "must be positive and at most the load increment [-]");
}

QuasiStaticSolver::QuasiStaticSolver(const dealii::parallel::distributed::Triangulation<dim> &mesh,
                                     const SoilModel &soil, const BoundaryConditions &boundary_conditions,
                                     const QuasiStaticSettings &settings)
  : soil_(soil)
  , boundary_conditions_(boundary_conditions)
  , settings_(settings)
  , space_(mesh, settings.element_degree)
{
  settings_.validate("quasi-static solver");
  boundary_conditions_.validate(mesh, "quasi-static solver");
  material_points_.initialise(mesh, space_.cell_quadrature().size());

  x_component_dofs_ = dealii::DoFTools::extract_dofs(space_.dof_handler(), dealii::ComponentMask(std::vector<bool>{true, false}));
  setup_system();
}

dealii::AffineConstraints<double> QuasiStaticSolver::base_constraints() const
{
  dealii::AffineConstraints<double> constraints(relevant_dofs_);
  dealii::DoFTools::make_hanging_node_constraints(space_.dof_handler(), constraints);
  return constraints;
}

void QuasiStaticSolver::setup_system()
{
  // The sheet's DoFs follow the soil's and belong to the last rank, which owns the soil's last
  // block: every rank's range stays contiguous, as PETSc needs. Every rank sees them all.
  const auto n_soil = space_.dof_handler().n_dofs();
  const auto n_total = n_soil + (sheet_ ? sheet_->n_dofs() : 0);
  owned_dofs_ = dealii::IndexSet(n_total);
  owned_dofs_.add_indices(space_.locally_owned_dofs());
  relevant_dofs_ = dealii::IndexSet(n_total);
  relevant_dofs_.add_indices(space_.locally_relevant_dofs());
  if (sheet_)
    {
      relevant_dofs_.add_range(n_soil, n_total);
      if (sheet_->owns_dofs())
        owned_dofs_.add_range(n_soil, n_total);
    }
  owned_dofs_.compress();
  relevant_dofs_.compress();

  // The DoFs with a prescribed displacement are the same at every step; only their values change.
  homogeneous_constraints_ = base_constraints();
  for (const auto &d : boundary_conditions_.displacements)
    dealii::VectorTools::interpolate_boundary_values(space_.mapping(), space_.dof_handler(), d.boundary_id,
                                                     dealii::Functions::ZeroFunction<dim>(dim),
                                                     homogeneous_constraints_,
                                                     dealii::ComponentMask(std::vector<bool>{d.constrain_x, d.constrain_y}));
  if (sheet_)
    sheet_->add_clamp_constraints(homogeneous_constraints_, time_, nullptr);
  homogeneous_constraints_.close();

  const MPI_Comm comm = space_.communicator();
  dealii::DynamicSparsityPattern pattern(relevant_dofs_);
  dealii::DoFTools::make_sparsity_pattern(space_.dof_handler(), pattern, homogeneous_constraints_, false);
  if (sheet_)
    sheet_->for_each_coupling([&](const std::vector<dealii::types::global_dof_index> &dofs) {
      homogeneous_constraints_.add_entries_local_to_global(dofs, pattern, false);
    });
  dealii::SparsityTools::distribute_sparsity_pattern(pattern, owned_dofs_, comm, relevant_dofs_);
  tangent_.reinit(owned_dofs_, owned_dofs_, pattern, comm);
  for (auto *v : {&newton_rhs_, &residual_, &internal_force_, &external_force_, &correction_, &increment_,
                  &last_increment_, &line_search_base_, &displacement_owned_})
    v->reinit(owned_dofs_, comm);
  increment_relevant_.reinit(owned_dofs_, relevant_dofs_, comm);
  displacement_.reinit(owned_dofs_, relevant_dofs_, comm);
  if (settings_.linear_solver.preconditioner == LinearSolverSettings::Preconditioner::rigid_body_amg)
    {
      std::vector<dealii::Point<dim>> sheet_nodes;
      if (sheet_)
        for (std::size_t k = 0; k < sheet_->sheet().n_nodes(); ++k)
          sheet_nodes.push_back(sheet_->sheet().node(k));
      rigid_body_modes_ = rigid_body_modes(space_, owned_dofs_, sheet_nodes);
    }
}

void QuasiStaticSolver::attach_sheet(const TrussSheet &sheet, std::vector<SheetClamp> clamps)
{
  if (time_ != 0.0)
    throw std::logic_error("quasi-static solver: attach_sheet after the first load step (t = " +
                           std::to_string(time_) + "); lay the sheet before loading");
  sheet_ = std::make_unique<ImplicitSheet>(space_, sheet, std::move(clamps), space_.dof_handler().n_dofs(),
                                           "quasi-static solver: sheet");
  setup_system();
}

std::vector<dealii::Tensor<1, dim>> QuasiStaticSolver::sheet_displacements() const
{
  return sheet_ ? sheet_->node_displacements(displacement_) : std::vector<dealii::Tensor<1, dim>>();
}

dealii::Tensor<1, dim> QuasiStaticSolver::sheet_node_reaction(std::size_t node) const
{
  dealii::Tensor<1, dim> reaction;
  if (sheet_ && sheet_->owns_dofs())
    for (unsigned int c = 0; c < dim; ++c)
      reaction[c] = internal_force_[sheet_->dof(node, c)] - external_force_[sheet_->dof(node, c)];
  return dealii::Utilities::MPI::sum(reaction, space_.communicator());
}

void QuasiStaticSolver::set_initial_stress(const std::function<StressTensor(const dealii::Point<dim> &)> &stress,
                                           const std::string &description)
{
  set_material_point_stress(space_, soil_, material_points_, stress, description);
}

void QuasiStaticSolver::set_initial_stress(const GeostaticStress &geostatic)
{
  geostatic.validate("geostatic stress");
  set_initial_stress([&](const dealii::Point<dim> &x) { return geostatic.stress_at(x); },
                     "the geostatic stress (K0 = " + std::to_string(geostatic.k0) + ")");
}

dealii::AffineConstraints<double> QuasiStaticSolver::step_constraints(double new_time) const
{
  // The increment of each prescribed displacement from the current (converged) one.
  dealii::AffineConstraints<double> constraints = base_constraints();
  for (const auto &d : boundary_conditions_.displacements)
    {
      std::map<dealii::types::global_dof_index, double> values;
      const dealii::Functions::ZeroFunction<dim> zero(dim);
      if (d.displacement)
        d.displacement->set_time(new_time);
      dealii::VectorTools::interpolate_boundary_values(space_.mapping(), space_.dof_handler(), d.boundary_id,
                                                       d.displacement ? static_cast<const dealii::Function<dim> &>(*d.displacement) : zero, values,
                                                       dealii::ComponentMask(std::vector<bool>{d.constrain_x, d.constrain_y}));
      for (const auto &[dof, value] : values)
        if (!constraints.is_constrained(dof))
          {
            constraints.add_line(dof);
            constraints.set_inhomogeneity(dof, value - displacement_[dof]);
          }
    }
  if (sheet_)
    sheet_->add_clamp_constraints(constraints, new_time, &displacement_);
  constraints.close();
  return constraints;
}

void QuasiStaticSolver::assemble(double time, const dealii::AffineConstraints<double> &constraints)
{
  tangent_ = 0.0;
  for (auto *v : {&newton_rhs_, &residual_, &internal_force_, &external_force_})
    *v = 0.0;
  boundary_conditions_.set_load_time(time);

  const auto &fe = space_.fe();
  dealii::FEValues<dim> fe_values(space_.mapping(), fe, space_.cell_quadrature(),
                                  dealii::update_values | dealii::update_gradients | dealii::update_JxW_values);
  dealii::FEFaceValues<dim> face_values(space_.mapping(), fe, space_.face_quadrature(),
                                        dealii::update_values | dealii::update_quadrature_points |
                                          dealii::update_normal_vectors | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Vector u(0);
  const unsigned int n_dofs = fe.n_dofs_per_cell(), n_q = space_.cell_quadrature().size();
  dealii::FullMatrix<double> cell_tangent(n_dofs, n_dofs);
  dealii::Vector<double> cell_internal(n_dofs), cell_external(n_dofs), cell_rhs(n_dofs);
  std::vector<dealii::types::global_dof_index> dof_indices(n_dofs);
  std::vector<StrainTensor> strain_increments(n_q);
  std::vector<StrainTensor> shape_strains(n_dofs);
  const dealii::Tensor<1, dim> body_force = settings_.density * settings_.gravity;

  for (const auto &cell : space_.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        cell_tangent = 0.0;
        cell_internal = 0.0;
        cell_external = 0.0;
        fe_values[u].get_function_symmetric_gradients(increment_relevant_, strain_increments);
        auto points = material_points_.at(cell);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const StressUpdate update = soil_.update(points[q]->stress, strain_increments[q]);
            points[q]->trial_stress = update.stress;
            points[q]->trial_plastic_strain = points[q]->plastic_strain + update.plastic_strain_increment;
            points[q]->trial_region = update.region;
            const auto in_plane_stress = in_plane_part(update.stress);
            const double JxW = fe_values.JxW(q);
            for (unsigned int i = 0; i < n_dofs; ++i)
              shape_strains[i] = fe_values[u].symmetric_gradient(i, q);
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                cell_internal(i) += (in_plane_stress * shape_strains[i]) * JxW;
                cell_external(i) += (fe_values[u].value(i, q) * body_force) * JxW;
                const auto stress_of_i = shape_strains[i] * update.tangent;
                for (unsigned int j = 0; j < n_dofs; ++j)
                  cell_tangent(i, j) += (stress_of_i * shape_strains[j]) * JxW;
              }
          }
        boundary_conditions_.add_boundary_loads(cell, face_values, cell_external);
        cell->get_dof_indices(dof_indices);
        cell_rhs = cell_external;
        cell_rhs -= cell_internal;
        constraints.distribute_local_to_global(cell_tangent, cell_rhs, dof_indices, tangent_, newton_rhs_, true);
        homogeneous_constraints_.distribute_local_to_global(cell_rhs, dof_indices, residual_);
        internal_force_.add(dof_indices, cell_internal);
        external_force_.add(dof_indices, cell_external);
      }
  if (sheet_)
    sheet_->for_each_element(displacement_, increment_relevant_, material_points_,
                             [&](const ImplicitSheet::LocalElement &element) {
                               dealii::Vector<double> rhs(element.internal_force);
                               rhs *= -1.0;
                               constraints.distribute_local_to_global(element.tangent, rhs, element.dofs, tangent_,
                                                                      newton_rhs_, true);
                               homogeneous_constraints_.distribute_local_to_global(rhs, element.dofs, residual_);
                               internal_force_.add(element.dofs, element.internal_force);
                             });
  tangent_.compress(dealii::VectorOperation::add);
  for (auto *v : {&newton_rhs_, &residual_, &internal_force_, &external_force_})
    v->compress(dealii::VectorOperation::add);
}

LoadSteppingReport QuasiStaticSolver::advance_to(double end_time)
{
  LoadSteppingReport report;
  double increment = settings_.stepping.increment;
  const double time_tolerance = 1e-12 * std::max(1.0, std::abs(end_time));
  while (time_ < end_time - time_tolerance)
    {
      const double step = std::min(increment, end_time - time_);
      const NewtonOutcome outcome = solve_step(time_ + step);
      if (outcome.converged)
        {
          displacement_owned_ += increment_;
          displacement_ = displacement_owned_;
          last_increment_ = increment_;
          last_step_ = step;
          material_points_.commit();
          if (sheet_)
            sheet_->commit();
          time_ += step;
          report.steps.push_back(
            {time_, step, outcome.n_iterations, outcome.n_linear_iterations, outcome.relative_residuals,
             outcome.n_backtracks});
          // After a cutback, grow back towards the requested increment once steps converge again.
          increment = std::min(2.0 * step, settings_.stepping.increment);
          continue;
        }
      // Every residual evaluated is one iteration's assembly (line-search trials aside).
      report.cutbacks.push_back(
        {time_, time_ + step, static_cast<unsigned int>(outcome.relative_residuals.size()), outcome.failure});
      increment = 0.5 * step;
      if (increment < settings_.stepping.minimum_increment)
        {
          // Leave the forces and trial states of the last converged step, not of the failed
          // iterate, so that reactions and output still describe a solution.
          increment_ = 0.0;
          increment_relevant_ = increment_;
          assemble(time_, homogeneous_constraints_);
          std::ostringstream message;
          message << "quasi-static solver: no equilibrium found from t = " << time_ << " to t = " << time_ + step
                  << " with the increment at its minimum " << settings_.stepping.minimum_increment << " (after "
                  << report.n_cutbacks() << " cutbacks): " << outcome.failure
                  << ". The load may exceed what the soil can carry (collapse), or the minimum increment be too large.";
          throw ConvergenceFailure(message.str(), time_);
        }
    }
  return report;
}

dealii::Tensor<1, dim> QuasiStaticSolver::boundary_reaction(dealii::types::boundary_id boundary_id) const
{
  const dealii::IndexSet boundary_dofs =
    dealii::DoFTools::extract_boundary_dofs(space_.dof_handler(), dealii::ComponentMask(), {boundary_id});
  dealii::Tensor<1, dim> reaction;
  for (const auto dof : boundary_dofs)
    if (space_.locally_owned_dofs().is_element(dof))
      reaction[x_component_dofs_.is_element(dof) ? 0 : 1] += internal_force_[dof] - external_force_[dof];
  return dealii::Utilities::MPI::sum(reaction, space_.communicator());
}

std::string QuasiStaticSolver::write_vtu(const std::string &directory, const std::string &basename, unsigned int step)
{
  if (!sheet_)
    return write_soil_vtu(space_, displacement_, material_points_, directory, basename, step);
  // The output shows the soil: its DoFs only, without the sheet's.
  dealii::PETScWrappers::MPI::Vector soil_owned(space_.locally_owned_dofs(), space_.communicator());
  for (const auto i : space_.locally_owned_dofs())
    soil_owned[i] = displacement_owned_[i];
  soil_owned.compress(dealii::VectorOperation::insert);
  dealii::PETScWrappers::MPI::Vector soil(space_.locally_owned_dofs(), space_.locally_relevant_dofs(),
                                          space_.communicator());
  soil = soil_owned;
  return write_soil_vtu(space_, soil, material_points_, directory, basename, step);
}
} // namespace geohybrid::fem
