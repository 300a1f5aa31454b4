#pragma once
// Declaring and reading the micro-parameters of a contact law (Table 5 of the reference paper)
// in a deal.II ParameterHandler subsection. Shared by every command that builds a DEM.
#include "dem/contact_law.h"

#include <deal.II/base/parameter_handler.h>

namespace geohybrid::apps
{
/// Declares the entries of a contact law inside the current subsection, with `defaults`.
void declare_contact_parameters(dealii::ParameterHandler &prm, const dem::ContactParameters &defaults);
/// Reads them back (the current subsection must be the one declared) and validates them;
/// `where` names the subsection in error messages.
dem::ContactParameters parse_contact_parameters(dealii::ParameterHandler &prm, const std::string &where);
} // namespace geohybrid::apps
