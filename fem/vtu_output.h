#pragma once
// ParaView output of the soil: the displacement field, and per cell the quadrature-point averages
// of the stresses, of the mean and deviatoric stresses, of the accumulated plastic shear strain and
// the fraction of the cell's points that yielded in the last step. One VTU piece per MPI rank and
// a PVTU record that ties them together.
#include "fem/displacement_space.h"
#include "fem/material_point_history.h"

#include <deal.II/lac/petsc_vector.h>

#include <string>

namespace geohybrid::fem
{
/// Writes `directory/basename_NNNN.R.vtu` per rank and `directory/basename_NNNN.pvtu`; returns the
/// PVTU file name (without the directory). `displacement` must have ghost entries. Collective.
/// Throws std::runtime_error naming the file if a write fails (a full disk).
std::string write_soil_vtu(const DisplacementSpace &space, const dealii::PETScWrappers::MPI::Vector &displacement,
                           MaterialPointHistory &material_points, const std::string &directory,
                           const std::string &basename, unsigned int step);
} // namespace geohybrid::fem
