#pragma once
// The biaxial compression test of the reference paper (section 4.2, Figure 6): a sample in a box
// of four frictionless walls, the lateral walls servo-controlled at a constant stress sigma_0,
// the top wall moving down at a constant speed V slow enough to be quasi-static. Strains and
// stresses come from the walls' displacements and forces. Compression is positive here, as in
// soil mechanics.
#include "dem/dem_system.h"
#include "box.h"

#include <cstdint>
#include <string>
#include <functional>
#include <vector>

namespace geohybrid::dem
{
/// Isotropic consolidation: the four walls servo-controlled to one stress until equilibrium.
struct ConsolidationSpec
{
  double stress = 10e3;             ///< [Pa]
  double stress_tolerance = 0.02;   ///< accepted relative error of each wall pair's stress [-]
  double unbalanced_ratio = 1e-3;   ///< accepted unbalanced-force ratio [-]
  double servo_max_speed = 0.05;    ///< cap on the walls' speed [m/s]
  std::uint64_t max_steps = 2'000'000;
};

/// Consolidates the sample held by `system` in `box` to spec.stress, isotropically: the four
/// walls are servo-controlled to it until both wall pairs' stresses are within the tolerance and
/// the unbalanced-force ratio is below its limit, checked every 200 steps. A sample already there
/// (made by REDF at that stress) takes no step. Returns the number of steps; throws
/// std::runtime_error after spec.max_steps.
std::uint64_t consolidate_isotropically(DemSystem &system, const RectangularBox &box, const ConsolidationSpec &spec);

struct BiaxialSpec
{
  double confining_stress = 10e3;   ///< sigma_0 on the lateral walls [Pa]
  double top_wall_speed = 0.0;      ///< V [m/s]; 0 = from target_inertial_number
  double target_inertial_number = 2e-4; ///< used when top_wall_speed is 0 [-]
  double final_axial_strain = 0.10; ///< [-]
  double record_interval = 1e-3;    ///< axial strain between recorded points [-]
  double servo_max_speed = 0.05;    ///< cap on the lateral walls' speed [m/s]
  double ramp_strain = 0.005;       ///< the top wall reaches V after this axial strain [-]
  /// Before shearing, the sample is consolidated to sigma_0 (consolidate_isotropically) with
  /// these tolerances: a sample made at one stress serves tests at others.
  double consolidation_stress_tolerance = 0.02;  ///< [-]
  double consolidation_unbalanced_ratio = 1e-3;  ///< [-]
};

struct BiaxialPoint
{
  double axial_strain;       ///< (H0 - H) / H0
  double lateral_strain;     ///< (W0 - W) / W0
  double volumetric_strain;  ///< axial + lateral (2D), compression positive
  double axial_stress;       ///< top and bottom wall stresses, averaged since the last point [Pa]
  double lateral_stress;     ///< left and right wall stresses, averaged since the last point [Pa]
  double deviatoric_stress;  ///< axial - lateral [Pa]
};

struct BiaxialCurve
{
  double confining_stress = 0.0;
  double initial_porosity = 0.0;
  double top_wall_speed = 0.0;
  double inertial_number = 0.0; ///< I = strain rate x mean diameter x sqrt(density / sigma_0)
  std::uint64_t consolidation_steps = 0;
  std::uint64_t compression_steps = 0;
  int final_threads = 0;        ///< threads of the system when the test ended (see thread_budget)
  std::vector<BiaxialPoint> points;
};

/// Rebuilds `system` on `n_threads` threads from its complete state: it continues bit for bit as
/// it would have (a DemSystem's results do not depend on its thread count). Allocates: for a
/// change now and then (a test given the thread of one that finished), not for every step.
void move_to_threads(DemSystem &system, int n_threads);

/// Consolidates the sample held by `system` in `box` to sigma_0, then shears it (its walls are
/// reused: lateral walls servo-controlled, the bottom wall fixed, the top wall driven down).
/// `mean_diameter` and `density` give the inertial number. Strains are measured from the
/// consolidated state, and initial_porosity is that state's. `thread_budget` (optional), asked
/// before every compression step, says how many threads the test may use now; when it changes,
/// the system moves onto that many (move_to_threads), so tests run side by side can take over
/// the threads of those that have finished without changing any result.
BiaxialCurve run_biaxial_test(DemSystem &system, const RectangularBox &box, const BiaxialSpec &spec,
                              double mean_diameter, double density,
                              const std::function<void(double)> &progress = {},
                              const std::function<int()> &thread_budget = {});

/// Macroscopic parameters read from biaxial curves at one or more confining stresses.
struct BiaxialParameters
{
  double peak_friction_angle_deg = 0.0;     ///< Mohr-Coulomb fit of the peaks
  double cohesion = 0.0;                    ///< [Pa], from the same fit (0 for one confinement)
  double residual_friction_angle_deg = 0.0; ///< fit of the residual states (last 10 % of strain)
  double young_modulus = 0.0;               ///< initial tangent d(q)/d(axial strain) [Pa]
  double young_modulus_50 = 0.0;            ///< secant at half the peak deviator (E50) [Pa]
  double poisson_ratio = 0.0;               ///< -d(lateral strain)/d(axial strain), initial
  double dilatancy_angle_deg = 0.0;         ///< sin psi = -dev/(dea - del) at the peak dilation rate
};

/// Mohr-Coulomb fit t = c cos(phi) + s sin(phi) over (s, t) = ((s1 + s3)/2, (s1 - s3)/2) pairs,
/// by least squares; with one pair, c = 0 and sin(phi) = t/s. Returns {phi [deg], c [Pa]}.
std::pair<double, double> fit_mohr_coulomb(const std::vector<double> &sigma_1, const std::vector<double> &sigma_3);

/// Elastic and strength parameters of the curves; the moduli and angles are averaged over the
/// confinements, the friction angles fitted across them.
BiaxialParameters analyse_biaxial_curves(const std::vector<BiaxialCurve> &curves);

/// The continuum (plane-strain, 3D isotropic elastic and Mohr-Coulomb) soil that reproduces the
/// biaxial test's response, for a continuum run of the same soil (geohybrid pullout, mode = fem).
/// The biaxial's moduli are those of the plane: E_2D = dq/d(eps_a) under a constant lateral stress
/// and nu_2D = -d(eps_lat)/d(eps_a). A plane-strain continuum (eps_zz = 0) gives E_2D = E / (1 - nu^2)
/// and nu_2D = nu / (1 - nu), so nu = nu_2D / (1 + nu_2D) and E = E_2D (1 - nu^2). The peak friction
/// angle and the cohesion of the fit are plane-strain values already (sigma_1 and sigma_3 are the
/// in-plane principal stresses), and so is the dilatancy angle; a negative cohesion or dilatancy
/// angle of a fit is taken as 0, a dilatancy angle above the friction angle as the friction angle.
struct ContinuumEquivalent
{
  double young_modulus = 0.0;         ///< E [Pa]
  double poisson_ratio = 0.0;         ///< nu [-]
  double friction_angle_deg = 0.0;    ///< phi (peak) [deg]
  double cohesion = 0.0;              ///< c [Pa]
  double dilatancy_angle_deg = 0.0;   ///< psi [deg]
  std::string invalid_reason;         ///< empty if the continuum exists (e.g. nu_2D >= 1 has none)
};
ContinuumEquivalent continuum_equivalent(const BiaxialParameters &biaxial);
} // namespace geohybrid::dem
