#include "contact_parameters.h"

#include "run_directory.h"

#include <iomanip>
#include <sstream>

namespace geohybrid::apps
{
using dealii::Patterns::Bool;
using dealii::Patterns::Double;

void declare_contact_parameters(dealii::ParameterHandler &prm, const dem::ContactParameters &d)
{
  prm.declare_entry("normal stiffness", number(d.normal_stiffness), Double(0.0),
                    "Normal contact stiffness kn, per metre of thickness [N/m/m]");
  prm.declare_entry("shear stiffness", number(d.shear_stiffness), Double(0.0),
                    "Tangential contact stiffness ks, per metre of thickness [N/m/m]");
  prm.declare_entry("friction angle", number(d.friction_angle_deg), Double(0.0, 89.99),
                    "Contact friction angle delta: Coulomb limit |Ft| <= a_s + Fn tan(delta) [deg]");
  prm.declare_entry("shear strength", number(d.shear_strength), Double(0.0),
                    "Contact shear strength a_s, carried while the contact is bonded [N/m]");
  prm.declare_entry("tensile strength", number(d.tensile_strength), Double(0.0),
                    "Contact tensile strength a_n; 0 = no tension [N/m]");
  prm.declare_entry("restitution coefficient", number(d.restitution), Double(1e-6, 1.0),
                    "Normal coefficient of restitution e setting a viscous dashpot of damping ratio "
                    "-ln e / sqrt(pi^2 + ln^2 e); the dashpot never makes an unbonded contact pull, so a rebound "
                    "keeps a little more than e (0.55 at e = 0.5: dem/contact_law.h); 1 = none [-]");
  prm.declare_entry("bond new contacts", d.bond_new_contacts ? "true" : "false", Bool(),
                    "Whether a contact starts bonded (carrying a_s and a_n) when it forms, as in a cementing "
                    "soil; otherwise only the contacts touching at the start are bonded [-]");
}

dem::ContactParameters parse_contact_parameters(dealii::ParameterHandler &prm, const std::string &where)
{
  dem::ContactParameters c;
  c.normal_stiffness = prm.get_double("normal stiffness");
  c.shear_stiffness = prm.get_double("shear stiffness");
  c.friction_angle_deg = prm.get_double("friction angle");
  c.shear_strength = prm.get_double("shear strength");
  c.tensile_strength = prm.get_double("tensile strength");
  c.restitution = prm.get_double("restitution coefficient");
  c.bond_new_contacts = prm.get_bool("bond new contacts");
  c.validate(where);
  return c;
}
} // namespace geohybrid::apps
