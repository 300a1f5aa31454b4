#include "contact_law.h"

#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
namespace
{
void require(bool condition, const std::string &where, const std::string &name, double value,
             const std::string &what)
{
  if (!condition)
    {
      std::ostringstream message;
      message << where << ": parameter '" << name << "' = " << value << " " << what;
      throw std::invalid_argument(message.str());
    }
}
} // namespace

void ContactParameters::validate(const std::string &where) const
{
  require(normal_stiffness > 0.0 && std::isfinite(normal_stiffness), where, "normal stiffness",
          normal_stiffness, "must be positive [N/m/m]");
  require(shear_stiffness >= 0.0 && std::isfinite(shear_stiffness), where, "shear stiffness",
          shear_stiffness, "must be zero or positive [N/m/m]");
  require(friction_angle_deg >= 0.0 && friction_angle_deg < 90.0, where, "friction angle",
          friction_angle_deg, "must lie in [0, 90) degrees");
  require(shear_strength >= 0.0, where, "shear strength", shear_strength, "must not be negative [N/m]");
  require(tensile_strength >= 0.0, where, "tensile strength", tensile_strength,
          "must not be negative [N/m]");
  require(restitution > 0.0 && restitution <= 1.0, where, "restitution coefficient", restitution,
          "must lie in (0, 1]");
}

LinearContactLaw::LinearContactLaw(const ContactParameters &parameters)
  : parameters_(parameters)
{
  parameters_.validate("contact law");
  // A zero shear stiffness would make the slip work ill-defined; a frictionless contact is
  // expressed by a zero friction angle instead, with ks kept for the bookkeeping.
  if (parameters_.shear_stiffness == 0.0)
    parameters_.shear_stiffness = 1e-12 * parameters_.normal_stiffness;
  friction_coefficient_ = std::tan(degrees_to_radians(parameters_.friction_angle_deg));
  const double log_e    = std::log(parameters_.restitution);
  damping_ratio_        = -log_e / std::sqrt(pi * pi + log_e * log_e);
  bonding_enabled_      = parameters_.bond_new_contacts &&
                     (parameters_.shear_strength > 0.0 || parameters_.tensile_strength > 0.0);
}
} // namespace geohybrid::dem
