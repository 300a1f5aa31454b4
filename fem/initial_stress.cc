#include "initial_stress.h"

#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>

#include <sstream>
#include <stdexcept>

namespace geohybrid::fem
{
void set_material_point_stress(const DisplacementSpace &space, const SoilModel &soil,
                               MaterialPointHistory &material_points,
                               const std::function<StressTensor(const dealii::Point<dim> &)> &stress,
                               const std::string &description)
{
  dealii::FEValues<dim> fe_values(space.mapping(), space.fe(), space.cell_quadrature(),
                                  dealii::update_quadrature_points);
  std::string violation;
  for (const auto &cell : space.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        auto points = material_points.at(cell);
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            const auto &x = fe_values.quadrature_point(q);
            const StressTensor sigma = stress(x);
            const double f = soil.yield_function(sigma);
            if (violation.empty() && f > 1e-9 * (sigma.norm() + 1.0))
              {
                std::ostringstream message;
                message << description << " lies outside the soil's yield surface at (" << x[0] << ", " << x[1]
                        << ") m: sigma_xx = " << sigma[0][0] << ", sigma_yy = " << sigma[1][1]
                        << ", sigma_zz = " << sigma[2][2] << " Pa, yield function " << f
                        << " Pa > 0 (for a geostatic state, K0 is too far from 1)";
                violation = message.str();
              }
            points[q]->stress = points[q]->trial_stress = sigma;
          }
      }
  // Every rank must throw, or the others would wait for it in the next collective call.
  if (dealii::Utilities::MPI::max(violation.empty() ? 0 : 1, space.communicator()) > 0)
    throw std::invalid_argument(violation.empty() ? description + " lies outside the soil's yield surface on another MPI rank"
                                                  : violation);
}
} // namespace geohybrid::fem
