#include "material_point_history.h"

namespace geohybrid::fem
{
void MaterialPointHistory::initialise(const dealii::Triangulation<dim> &mesh, unsigned int n_points_per_cell)
{
  mesh_ = &mesh;
  storage_.clear();
  for (const auto &cell : mesh.active_cell_iterators())
    if (cell->is_locally_owned())
      storage_.initialize(cell, n_points_per_cell);
}

void MaterialPointHistory::commit()
{
  for_each_cell([](const CellIterator &, std::vector<std::shared_ptr<MaterialPoint>> &points) {
    for (auto &p : points)
      {
        p->stress = p->trial_stress;
        p->plastic_strain = p->trial_plastic_strain;
        p->region = p->trial_region;
      }
  });
}

void MaterialPointHistory::for_each_cell(
  const std::function<void(const CellIterator &, std::vector<std::shared_ptr<MaterialPoint>> &)> &visit)
{
  for (const auto &cell : mesh_->active_cell_iterators())
    if (cell->is_locally_owned())
      {
        auto points = storage_.get_data(cell);
        visit(cell, points);
      }
}
} // namespace geohybrid::fem
