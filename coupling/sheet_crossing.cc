#include "sheet_crossing.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geohybrid::coupling
{
SheetCrossing::SheetCrossing(const dem::SparSheet &dem_sheet, std::size_t dem_sheet_index,
                             fem::EmbeddedSheet &continuum_sheet, double rest_length)
  : dem_sheet_index_(dem_sheet_index)
  , dem_node_(dem_sheet.n_nodes() - 1)
  , rest_length_(rest_length)
  , chain_(dem_sheet.chain())
{
  const std::string where = "sheet crossing: ";
  const fem::TrussSheet &truss = continuum_sheet.sheet();
  if (!(rest_length > 0.0) || !std::isfinite(rest_length))
    throw std::invalid_argument(where + "the joining segment's rest length must be positive, got " +
                                std::to_string(rest_length) + " m");
  const double neighbours = std::min(dem_sheet.rest_length[dem_sheet.n_segments() - 1], truss.rest_length(0));
  if (rest_length < 0.9 * neighbours)
    {
      std::ostringstream message;
      message << where << "the joining segment (" << rest_length << " m) is shorter than 0.9 x its neighbours ("
              << neighbours << " m): its ends would be stiffer than the stable steps count";
      throw std::invalid_argument(message.str());
    }
  const double J = chain_.axial_stiffness;
  if (std::abs(truss.chain().axial_stiffness - J) > 1e-12 * J)
    throw std::invalid_argument(where + "the two parts of the sheet have different axial stiffnesses J");
  continuum_sheet.add_node_mass(0, 0.5 * truss.parameters().areal_mass * rest_length *
                                     truss.parameters().mass_scaling);
}

void SheetCrossing::apply(dem::SparSheet &dem_sheet, fem::EmbeddedSheet &continuum_sheet)
{
  const dealii::Point<fem::dim> far = continuum_sheet.node_position(0);
  const double dx = far[0] - dem_sheet.x[dem_node_], dy = far[1] - dem_sheet.y[dem_node_];
  const double length = std::sqrt(dx * dx + dy * dy);
  tension_ = chain_.tension(length, rest_length_);
  energy_ = chain_.elastic_energy(length, rest_length_);
  if (tension_ == 0.0)
    return;
  const double fx = tension_ * dx / length, fy = tension_ * dy / length;
  dem_sheet.fx[dem_node_] += fx;
  dem_sheet.fy[dem_node_] += fy;
  fem::EmbeddedSheet::Force on_continuum;
  on_continuum[0] = -fx;
  on_continuum[1] = -fy;
  continuum_sheet.add_node_load(0, on_continuum);
}
} // namespace geohybrid::coupling
