#include "implicit_sheet.h"

#include <deal.II/base/mpi.h>

#include <stdexcept>

namespace geohybrid::fem
{
ImplicitSheet::ImplicitSheet(const DisplacementSpace &space, const TrussSheet &sheet, std::vector<SheetClamp> clamps,
                             DofIndex first_dof, const std::string &where)
  : space_(space), sheet_(sheet), law_(sheet.parameters().interface), clamps_(std::move(clamps)), first_dof_(first_dof)
{
  for (const auto &c : clamps_)
    if (c.node >= sheet_.n_nodes() || !c.displacement)
      throw std::invalid_argument(where + ": a clamp holds node " + std::to_string(c.node) + " of a sheet of " +
                                  std::to_string(sheet_.n_nodes()) + " nodes" +
                                  (c.displacement ? "" : ", without a displacement"));
  const MPI_Comm comm = space_.communicator();
  owns_dofs_ = dealii::Utilities::MPI::this_mpi_process(comm) + 1 == dealii::Utilities::MPI::n_mpi_processes(comm);
  soil_points_ = locate_sheet_in_soil(space_, sheet_, where);
  trial_shear_stress_.assign(sheet_.n_nodes(), 0.0);
  sliding_.assign(sheet_.n_nodes(), false);
  trial_sliding_.assign(sheet_.n_nodes(), false);
  shear_stress_.assign(sheet_.n_nodes(), 0.0);
}

void ImplicitSheet::for_each_coupling(const std::function<void(const std::vector<DofIndex> &)> &visit) const
{
  for (std::size_t k = 0; k < sheet_.n_nodes(); ++k)
    if (soil_points_[k].owned)
      {
        std::vector<DofIndex> dofs{dof(k, 0), dof(k, 1)};
        dofs.insert(dofs.end(), soil_points_[k].dof_indices.begin(), soil_points_[k].dof_indices.end());
        visit(dofs);
      }
  if (owns_dofs_)
    for (std::size_t s = 0; s < sheet_.n_segments(); ++s)
      visit({dof(s, 0), dof(s, 1), dof(s + 1, 0), dof(s + 1, 1)});
}

std::vector<ImplicitSheet::Force>
ImplicitSheet::node_displacements(const dealii::PETScWrappers::MPI::Vector &displacement) const
{
  std::vector<Force> u(sheet_.n_nodes());
  for (std::size_t k = 0; k < u.size(); ++k)
    for (unsigned int c = 0; c < dim; ++c)
      u[k][c] = displacement[dof(k, c)];
  return u;
}

void ImplicitSheet::for_each_element(const dealii::PETScWrappers::MPI::Vector &displacement,
                                     const dealii::PETScWrappers::MPI::Vector &increment,
                                     MaterialPointHistory &material_points,
                                     const std::function<void(const LocalElement &)> &add)
{
  const std::vector<Force> u_converged = node_displacements(displacement), du = node_displacements(increment);
  std::vector<Force> u(u_converged.size());
  for (std::size_t k = 0; k < u.size(); ++k)
    u[k] = u_converged[k] + du[k];

  LocalElement element;
  for (std::size_t k = 0; k < sheet_.n_nodes(); ++k)
    {
      const auto &p = soil_points_[k];
      if (!p.owned)
        continue;
      // g = u_k - sum_i N_i u_i = B [u_k; u_soil], B = [I, -N_i e_(c_i)]; dg the same of du.
      const unsigned int n_soil = p.dof_indices.size(), n = dim + n_soil;
      std::vector<Force> columns(n); // B's columns
      columns[0][0] = columns[1][1] = 1.0;
      for (unsigned int i = 0; i < n_soil; ++i)
        columns[dim + i][p.components[i]] = -p.shape_values[i];
      Force gap = u[k], gap_increment = du[k];
      for (unsigned int i = 0; i < n_soil; ++i)
        {
          gap += displacement[p.dof_indices[i]] * columns[dim + i] + increment[p.dof_indices[i]] * columns[dim + i];
          gap_increment += increment[p.dof_indices[i]] * columns[dim + i];
        }
      const Force t = sheet_.tangent(k), normal({-t[1], t[0]});
      const double two_L = 2.0 * sheet_.tributary_length(k); // both faces
      const double sigma_nn = sheet_normal_stress(material_points, p, normal);
      const double slip_increment = gap_increment * t;
      InterfaceShearUpdate shear = law_.shear(shear_stress_[k], slip_increment, sigma_nn);
      // Before any slip in the step (the predictor), a face that slid in the last step sits at
      // its limit, where tau(ds) has two one-sided derivatives; take the sliding one (the
      // pull-out goes on in the same direction), not k_s, which would drag the soil with the
      // sheet in the predictor and leave Newton to undo it.
      if (slip_increment == 0.0 && sliding_[k])
        shear.tangent = 0.0;
      trial_shear_stress_[k] = shear.shear_stress;
      trial_sliding_[k] = shear.sliding;

      // The sheet node's resisting force f_g and its derivative K_g with respect to g.
      const Force f_g = two_L * (shear.shear_stress * t + law_.normal_stiffness() * (gap * normal) * normal);
      const dealii::Tensor<2, dim> K_g =
        two_L * (shear.tangent * dealii::outer_product(t, t) + law_.normal_stiffness() * dealii::outer_product(normal, normal));
      element.dofs = {dof(k, 0), dof(k, 1)};
      element.dofs.insert(element.dofs.end(), p.dof_indices.begin(), p.dof_indices.end());
      element.tangent.reinit(n, n);
      element.internal_force.reinit(n);
      for (unsigned int a = 0; a < n; ++a)
        {
          element.internal_force(a) = columns[a] * f_g;
          const Force K_b = K_g * columns[a];
          for (unsigned int b = 0; b < n; ++b)
            element.tangent(b, a) = columns[b] * K_b;
        }
      add(element);
    }

  if (owns_dofs_)
    {
      const std::vector<double> T = sheet_.axial_forces(u);
      element.tangent.reinit(2 * dim, 2 * dim);
      element.internal_force.reinit(2 * dim);
      for (std::size_t s = 0; s < sheet_.n_segments(); ++s)
        {
          element.dofs = {dof(s, 0), dof(s, 1), dof(s + 1, 0), dof(s + 1, 1)};
          const Force d = (sheet_.node(s + 1) + u[s + 1]) - (sheet_.node(s) + u[s]);
          const Force pull = T[s] * d / d.norm(); // on node s, towards s + 1; resisting: -pull
          dealii::Tensor<2, dim> K = sheet_.segment_stiffness(u, s);
          // A slack segment has no stiffness, and a node between slack segments whose interface
          // slides has none along the sheet: the Newton matrix is singular there (MUMPS meets a
          // zero pivot, Krylov stalls; seen at the far end of a run-out sheet once it all slides,
          // when a predictor shortens the last segment). That happens only at iterates: at
          // equilibrium a sliding node needs a taut segment to balance its friction. So the
          // matrix, not the force, gives a slack segment a small axial stiffness along it; a
          // converged state is the same.
          if (d.norm() < sheet_.rest_length(s))
            K = slack_segment_stiffness_fraction * sheet_.parameters().axial_stiffness / sheet_.rest_length(s) *
                dealii::outer_product(d / d.norm(), d / d.norm());
          for (unsigned int i = 0; i < dim; ++i)
            {
              element.internal_force(i) = -pull[i];
              element.internal_force(dim + i) = pull[i];
              for (unsigned int j = 0; j < dim; ++j)
                {
                  element.tangent(i, j) = element.tangent(dim + i, dim + j) = K[i][j];
                  element.tangent(i, dim + j) = element.tangent(dim + i, j) = -K[i][j];
                }
            }
          add(element);
        }
    }
}

void ImplicitSheet::add_clamp_constraints(dealii::AffineConstraints<double> &constraints, double time,
                                          const dealii::PETScWrappers::MPI::Vector *displacement) const
{
  for (const auto &c : clamps_)
    {
      const Force d = c.displacement(time);
      for (unsigned int component = 0; component < dim; ++component)
        {
          const DofIndex i = dof(c.node, component);
          if (constraints.is_constrained(i))
            continue;
          constraints.add_line(i);
          if (displacement != nullptr)
            constraints.set_inhomogeneity(i, d[component] - (*displacement)[i]);
        }
    }
}

void ImplicitSheet::commit()
{
  std::vector<double> shared(sheet_.n_nodes(), 0.0);
  for (std::size_t k = 0; k < shared.size(); ++k)
    if (soil_points_[k].owned)
      shared[k] = trial_shear_stress_[k];
  dealii::Utilities::MPI::sum(shared, space_.communicator(), shear_stress_);
  sliding_ = trial_sliding_;
}
} // namespace geohybrid::fem
