#include "truss_sheet.h"

#include "fem/constitutive/parameter_check.h"

#include <cmath>
#include <stdexcept>

namespace geohybrid::fem
{
void TrussSheetParameters::validate(const std::string &where) const
{
  require_parameter(axial_stiffness > 0.0 && std::isfinite(axial_stiffness), where, "axial stiffness J",
                    axial_stiffness, "must be positive [N/m]");
  require_parameter(areal_mass > 0.0 && std::isfinite(areal_mass), where, "areal mass", areal_mass,
                    "must be positive [kg/m^2]");
  require_parameter(mass_scaling >= 1.0 && std::isfinite(mass_scaling), where, "mass scaling", mass_scaling,
                    "must be at least 1 [-]");
  require_parameter(interface.friction_angle_deg >= 0.0 && interface.friction_angle_deg < 90.0, where,
                    "interface friction angle", interface.friction_angle_deg, "must lie in [0, 90) [deg]");
  require_parameter(interface.cohesion >= 0.0 && std::isfinite(interface.cohesion), where, "interface cohesion",
                    interface.cohesion, "must be zero or positive [Pa]");
  require_parameter(interface.normal_stiffness > 0.0 && std::isfinite(interface.normal_stiffness), where,
                    "interface normal stiffness", interface.normal_stiffness, "must be positive [Pa/m]");
  require_parameter(interface.shear_stiffness > 0.0 && std::isfinite(interface.shear_stiffness), where,
                    "interface shear stiffness", interface.shear_stiffness, "must be positive [Pa/m]");
}

TrussSheet::TrussSheet(const std::vector<dealii::Point<dim>> &nodes, const TrussSheetParameters &parameters,
                       const std::string &where)
  : nodes_(nodes), parameters_(parameters)
{
  parameters_.validate(where);
  if (nodes_.size() < 2)
    throw std::invalid_argument(where + ": a sheet needs at least two nodes, got " + std::to_string(nodes_.size()));
  for (std::size_t s = 0; s + 1 < nodes_.size(); ++s)
    {
      const double l0 = nodes_[s].distance(nodes_[s + 1]);
      if (!(l0 > 0.0))
        throw std::invalid_argument(where + ": nodes " + std::to_string(s) + " and " + std::to_string(s + 1) +
                                    " coincide (a segment of zero length)");
      rest_lengths_.push_back(l0);
    }
}

double TrussSheet::tributary_length(std::size_t k) const
{
  double length = 0.0;
  if (k > 0)
    length += 0.5 * rest_lengths_[k - 1];
  if (k + 1 < nodes_.size())
    length += 0.5 * rest_lengths_[k];
  return length;
}

TrussSheet::Force TrussSheet::tangent(std::size_t k) const
{
  Force t;
  if (k > 0)
    t += (nodes_[k] - nodes_[k - 1]) / rest_lengths_[k - 1];
  if (k + 1 < nodes_.size())
    t += (nodes_[k + 1] - nodes_[k]) / rest_lengths_[k];
  return t / t.norm();
}

double TrussSheet::node_mass(std::size_t k) const
{
  return parameters_.areal_mass * tributary_length(k) * parameters_.mass_scaling;
}

std::vector<double> TrussSheet::axial_forces(const std::vector<Force> &u) const
{
  const geosynthetic::TensionOnlyChain law = chain();
  std::vector<double> forces(n_segments());
  for (std::size_t s = 0; s < n_segments(); ++s)
    {
      const double l = ((nodes_[s + 1] + u[s + 1]) - (nodes_[s] + u[s])).norm();
      forces[s] = law.tension_at_strain(law.strain(l, rest_lengths_[s]));
    }
  return forces;
}

std::vector<TrussSheet::Force> TrussSheet::nodal_forces(const std::vector<Force> &u) const
{
  const std::vector<double> T = axial_forces(u);
  std::vector<Force> forces(n_nodes());
  for (std::size_t s = 0; s < n_segments(); ++s)
    if (T[s] > 0.0)
      {
        const Force d = (nodes_[s + 1] + u[s + 1]) - (nodes_[s] + u[s]);
        const Force pull = T[s] * d / d.norm(); // on node s, towards node s + 1
        forces[s] += pull;
        forces[s + 1] -= pull;
      }
  return forces;
}

dealii::Tensor<2, dim> TrussSheet::segment_stiffness(const std::vector<Force> &u, std::size_t s) const
{
  const Force d = (nodes_[s + 1] + u[s + 1]) - (nodes_[s] + u[s]);
  const double l = d.norm(), l0 = rest_lengths_[s];
  const geosynthetic::TensionOnlyChain law = chain();
  dealii::Tensor<2, dim> K;
  if (l < l0)
    return K;
  const Force e = d / l;
  const double T = law.tension_at_strain(law.strain(l, l0)); // l >= l0: J (l / l0 - 1)
  K = (law.spring_stiffness(l0) - T / l) * dealii::outer_product(e, e);
  for (unsigned int i = 0; i < dim; ++i)
    K[i][i] += T / l;
  return K;
}
} // namespace geohybrid::fem
