#pragma once
// The state of the soil at each quadrature point of the locally owned cells (deal.II's
// CellDataStorage, as in step-18): the converged ("committed") stress and plastic strain of the
// last completed load step, and the trial values of the current Newton iterate. A trial never
// overwrites the committed state, so a failed step is abandoned simply by not committing it.
#include "fem/constitutive/stress_update.h"

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_point_data.h>
#include <deal.II/grid/tria.h>

#include <functional>
#include <memory>
#include <vector>

namespace geohybrid::fem
{
struct MaterialPoint
{
  StressTensor stress;                               ///< committed sigma, with sigma_zz [Pa]
  dealii::SymmetricTensor<2, 3> plastic_strain;      ///< committed accumulated eps^p [-]
  ReturnRegion region = ReturnRegion::elastic;       ///< of the last committed step
  StressTensor trial_stress;                         ///< at the current Newton iterate [Pa]
  dealii::SymmetricTensor<2, 3> trial_plastic_strain;
  ReturnRegion trial_region = ReturnRegion::elastic;
};

class MaterialPointHistory
{
public:
  using CellIterator = dealii::Triangulation<dim>::cell_iterator;

  /// One MaterialPoint per quadrature point of each locally owned active cell of `mesh`.
  void initialise(const dealii::Triangulation<dim> &mesh, unsigned int n_points_per_cell);

  std::vector<std::shared_ptr<MaterialPoint>> at(const CellIterator &cell)
  {
    return storage_.get_data(cell);
  }
  std::vector<std::shared_ptr<const MaterialPoint>> at(const CellIterator &cell) const
  {
    return storage_.get_data(cell);
  }

  /// Trial state becomes the committed one, everywhere (end of a converged load step).
  void commit();

  /// Calls `visit` for every locally owned cell with its points (e.g. to set an initial stress,
  /// or to read results).
  void for_each_cell(const std::function<void(const CellIterator &, std::vector<std::shared_ptr<MaterialPoint>> &)> &visit);

private:
  const dealii::Triangulation<dim> *mesh_ = nullptr;
  dealii::CellDataStorage<CellIterator, MaterialPoint> storage_;
};
} // namespace geohybrid::fem
