#pragma once
// Conventions used everywhere in geohybrid's continuum (fem/), stated once.
//
// - 2D plane strain, small strain, per metre of thickness: forces are N/m, stresses Pa, body
//   forces N/m^3, displacements m. SI units inside the code.
// - Stress and strain are positive in TENSION, as in continuum mechanics and deal.II (the DEM in
//   dem/ counts compression positive, as soil mechanics does; coupling/ converts). A soil at rest
//   therefore has negative normal stresses, and "pressure" p = -tr(sigma)/3 is positive.
// - Principal stresses are ordered sigma_1 >= sigma_2 >= sigma_3, so sigma_3 is the MOST
//   compressive one (the "major" principal stress of soil mechanics).
// - Plane strain keeps the out-of-plane normal stress sigma_zz: stresses are stored as 3x3
//   symmetric tensors with xz = yz = 0; strains as 2x2 symmetric tensors (eps_zz = 0 in total,
//   though its plastic part may not vanish).
// - The vertical axis is y, pointing up; gravity is usually (0, -9.81) m/s^2.
// - Pseudo-time t drives quasi-static loading: boundary data are deal.II Functions evaluated at t.
#include <deal.II/base/symmetric_tensor.h>

namespace geohybrid::fem
{
constexpr unsigned int dim = 2; ///< the continuum is two-dimensional (plane strain)

using StressTensor  = dealii::SymmetricTensor<2, 3>; ///< plane-strain stress with sigma_zz [Pa]
using StrainTensor  = dealii::SymmetricTensor<2, 2>; ///< in-plane strain (eps_zz = 0) [-]
using TangentTensor = dealii::SymmetricTensor<4, 2>; ///< d(in-plane stress)/d(in-plane strain) [Pa]

constexpr double pi = 3.14159265358979323846;
inline double degrees_to_radians(double degrees) { return degrees * pi / 180.0; }
} // namespace geohybrid::fem
