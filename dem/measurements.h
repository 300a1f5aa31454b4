#pragma once
// What a soil mechanician measures on a granular assembly: average stress (Love-Weber),
// porosity, coordination number and the unbalanced-force ratio.
#include "dem_system.h"

#include <array>

namespace geohybrid::dem
{
/// An axis-aligned measurement rectangle [m].
struct Region
{
  double x_min, y_min, x_max, y_max;
  double area() const { return (x_max - x_min) * (y_max - y_min); }
  bool contains(double x, double y) const { return x >= x_min && x <= x_max && y >= y_min && y <= y_max; }
};

/// Love-Weber average stress over the bodies whose centre of mass lies in the region:
///   sigma_ab = (1/A) sum_bodies sum_contacts f_a (x_c - x_body)_b   (f the force on the body),
/// written per body so that clusters, walls and sheets need no special branch vector. Compression is
/// negative (continuum mechanics sign), components {xx, yy, xy} [Pa]. The xy entry is the
/// symmetric part; equilibrium makes the skew part vanish.
std::array<double, 3> love_weber_stress(const DemSystem &system, const Region &region);

/// 1 - (solid area of the bodies whose centre lies in the region) / (region area). Bodies cut by
/// the region's edge are counted whole, so use regions much larger than a particle.
double porosity(const DemSystem &system, const Region &region);

/// Mean number of touching contacts per body, 2 N_c / N_b (wall and sheet contacts count once each).
double coordination_number(const DemSystem &system);

/// What the discs apply to the two faces of a sheet, averaged over segments [first, last)
/// (default: the whole sheet): the normal stress sum(Fn) / L and the shear stress
/// sum(F . u) / L on each face, with L the current length of those segments, u the unit vector of
/// each contact's segment (from node k to k + 1) and F the force on the sheet; the left face is the
/// one perp(u) points to (the top of a sheet running along +x) [Pa]. A normal stress against the
/// overburden gamma H, or the shear stresses against the head tension, checks a pull-out run.
struct SheetFaceStresses
{
  double normal_left = 0.0, normal_right = 0.0;
  double shear_left = 0.0, shear_right = 0.0;
};
SheetFaceStresses sheet_face_stresses(const DemSystem &system, std::size_t sheet, std::size_t first_segment = 0,
                                      std::size_t last_segment = static_cast<std::size_t>(-1));

/// PFC's unbalanced-force ratio: mean |resultant force| over movable bodies divided by the mean
/// contact force magnitude; tends to 0 at static equilibrium.
double unbalanced_force_ratio(const DemSystem &system);

/// The energy balance's error from `start` to `now`, relative: (now.total() - start.total()) over
/// the largest magnitude of the budget's terms at either time (kinetic, gravitational, elastic,
/// each dissipated term, the boundary work, the sheets' kinetic and elastic energies). Finite in
/// any scene (without gravity, a relative figure over |gravitational| alone divided by zero); 0
/// when every term is 0 (the change is then 0 too).
double energy_balance_error(const EnergyBudget &start, const EnergyBudget &now);
} // namespace geohybrid::dem
