#include "boundary_conditions.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace geohybrid::fem
{
void BoundaryConditions::validate(const dealii::Triangulation<dim> &mesh, const std::string &where) const
{
  // The boundary ids of the coarse mesh are known to every rank, so every rank gives the same
  // answer and no rank is left waiting for the others.
  const std::vector<dealii::types::boundary_id> ids = mesh.get_boundary_ids();
  auto check_id = [&](dealii::types::boundary_id id, const char *kind) {
    if (std::find(ids.begin(), ids.end(), id) == ids.end())
      {
        std::ostringstream message;
        message << where << ": " << kind << " on boundary id " << static_cast<unsigned int>(id)
                << ", which the mesh does not have (its boundary ids:";
        for (const auto i : ids)
          message << " " << static_cast<unsigned int>(i);
        message << ")";
        throw std::invalid_argument(message.str());
      }
  };
  auto check_components = [&](const dealii::Function<dim> *f, unsigned int n, dealii::types::boundary_id id,
                              const char *kind) {
    if (f != nullptr && f->n_components != n)
      throw std::invalid_argument(where + ": the " + kind + " function on boundary id " +
                                  std::to_string(id) + " has " + std::to_string(f->n_components) +
                                  " components instead of " + std::to_string(n));
  };
  for (const auto &d : displacements)
    {
      check_id(d.boundary_id, "a displacement condition");
      check_components(d.displacement.get(), dim, d.boundary_id, "displacement");
      if (!d.constrain_x && !d.constrain_y)
        throw std::invalid_argument(where + ": the displacement condition on boundary id " +
                                    std::to_string(d.boundary_id) + " constrains no component");
    }
  for (const auto &t : tractions)
    {
      check_id(t.boundary_id, "a traction");
      if (t.traction == nullptr)
        throw std::invalid_argument(where + ": the traction on boundary id " + std::to_string(t.boundary_id) +
                                    " has no function");
      check_components(t.traction.get(), dim, t.boundary_id, "traction");
    }
  for (const auto &p : pressures)
    {
      check_id(p.boundary_id, "a pressure");
      if (p.pressure == nullptr)
        throw std::invalid_argument(where + ": the pressure on boundary id " + std::to_string(p.boundary_id) +
                                    " has no function");
      check_components(p.pressure.get(), 1, p.boundary_id, "pressure");
    }
}

void BoundaryConditions::set_load_time(double time)
{
  for (auto &t : tractions)
    t.traction->set_time(time);
  for (auto &p : pressures)
    p.pressure->set_time(time);
}

void BoundaryConditions::add_boundary_loads(const dealii::DoFHandler<dim>::active_cell_iterator &cell,
                                            dealii::FEFaceValues<dim> &face_values,
                                            dealii::Vector<double> &cell_external) const
{
  const dealii::FEValuesExtractors::Vector u(0);
  const unsigned int n_dofs = cell_external.size();
  for (const auto face : cell->face_indices())
    if (cell->at_boundary(face))
      {
        const auto id = cell->face(face)->boundary_id();
        for (const auto &load : tractions)
          if (load.boundary_id == id)
            {
              face_values.reinit(cell, face);
              for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
                {
                  dealii::Tensor<1, dim> t;
                  for (unsigned int c = 0; c < dim; ++c)
                    t[c] = load.traction->value(face_values.quadrature_point(q), c);
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    cell_external(i) += (face_values[u].value(i, q) * t) * face_values.JxW(q);
                }
            }
        for (const auto &load : pressures)
          if (load.boundary_id == id)
            {
              face_values.reinit(cell, face);
              for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
                {
                  const dealii::Tensor<1, dim> t =
                    -load.pressure->value(face_values.quadrature_point(q)) * face_values.normal_vector(q);
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    cell_external(i) += (face_values[u].value(i, q) * t) * face_values.JxW(q);
                }
            }
      }
}
} // namespace geohybrid::fem
