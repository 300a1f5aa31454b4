#pragma once
// Setting the soil's stress at every quadrature point before a run (a geostatic state, or any
// field), with the one check both solvers need: the stress must lie inside the yield surface, or
// the first step would start from an inadmissible state.
#include "fem/constitutive/soil_model.h"
#include "fem/displacement_space.h"
#include "fem/material_point_history.h"

#include <functional>
#include <string>

namespace geohybrid::fem
{
/// Sets committed and trial stress of every locally owned point to `stress(x)`. Throws
/// std::invalid_argument on every rank, naming `description` and the point, if the stress lies
/// outside `soil`'s yield surface somewhere. Collective.
void set_material_point_stress(const DisplacementSpace &space, const SoilModel &soil,
                               MaterialPointHistory &material_points,
                               const std::function<StressTensor(const dealii::Point<dim> &)> &stress,
                               const std::string &description);
} // namespace geohybrid::fem
