#pragma once
// A geosynthetic sheet as a chain of tension-only spar elements (Chareyre & Villard 2005, the
// model of the reference paper, section 4.2 and Figure 5): nodes carry lumped mass, the segments
// between consecutive nodes carry an axial force
//
//   T = J (l - l0) / l0   when l > l0,   T = 0   when l <= l0 (no compression, no bending),
//
// with J the tensile stiffness per metre of width [N/m] (GT75: 687 kN/m, GT230: 2104 kN/m,
// Table 2), l the current and l0 the rest length of the segment. That law, its node stiffness and
// its energy are geosynthetic::TensionOnlyChain's (geosynthetic/tension_only_chain.h), shared with
// the continuum's truss. The chain is any polyline, so a
// wrap-around anchorage (lower part, vertical return, upper part) is one sheet. In 2D, per metre
// of width like everything else (conventions.h): T in N/m, node masses in kg/m.
//
// The sheet has a thickness t: a disc of radius r touches a segment when its centre is closer
// than r + t/2 to it (a capsule), and a node touches a wall as a disc of radius t/2
// (sheet_contacts.h). The disc-sheet interface is a LinearContactLaw with its own parameters
// (normal and shear stiffness, interface friction angle, a_s).
//
// Node masses. A node carries the mass of half of each adjacent segment: m = rho_A (l0_left +
// l0_right) / 2 per metre of width, rho_A the geosynthetic's mass per unit area (GT230: 620 g/m2).
// Real masses make the sheet the stiffest, lightest part of the model: a node between two
// segments of rest length l0 is a mass m on a spring 2 J / l0, stable only for
// dt < sqrt(m / (2 J / l0)), which for GT230 and l0 = 5 mm is about 2e-6 s, far below a sand's
// DEM step. For quasi-static problems (pull-out at a slow rate) the inertia of the sheet is
// irrelevant, so `mass_scaling` multiplies the inertial mass of every node (gravity still acts
// on the real mass); required_mass_scaling() gives the factor that keeps the sheet from
// limiting a chosen time step. The scaled mass is the one in the kinetic energy.
//
// Kinematic nodes (the clamp): prescribe_velocity() gives a node infinite inertial mass and a
// velocity it keeps whatever the forces; its reaction (the force the clamp applies to hold that
// motion) is reported after each step, and the clamp's work enters the energy balance as
// boundary work. A node may also carry an external load (set_load: a force-controlled pull, a
// hanging weight), whose work is boundary work too.
//
// Node and segment data are public structure-of-arrays, as ParticleSet's: DemSystem's loops and
// the contact code read them directly; SparSheet keeps them consistent.
#include "contact_law.h"
#include "soa_vector.h"

#include "geosynthetic/tension_only_chain.h"

#include <string>
#include <vector>

namespace geohybrid::dem
{
/// The interface law's defaults: the soil-geosynthetic friction angle calibrated in the reference
/// paper (25.6 degrees, section 4.3), no cohesion, the stiffnesses of the soil's contacts.
ContactParameters default_interface_parameters();

struct SheetParameters
{
  double axial_stiffness = 2.104e6; ///< J per metre of width [N/m]; default GT230 (Table 2)
  double thickness = 3.2e-3;        ///< t, used for contact only [m]; default GT230
  double areal_mass = 0.62;         ///< mass per unit area [kg/m^2]; default GT230 (620 g/m^2)
  double mass_scaling = 1.0;        ///< factor on the nodes' inertial mass, >= 1 [-]
  /// Disc-sheet contact law: tau <= a_s + sigma_n tan(delta). a_s acts while a contact is bonded
  /// (LinearContactLaw): set bond_new_contacts for an interface cohesion.
  ContactParameters interface = default_interface_parameters();

  /// Throws std::invalid_argument naming `where` and the offending parameter.
  void validate(const std::string &where) const;
};

class SparSheet
{
public:
  /// A sheet through `nodes` (at least two, consecutive nodes distinct), unstretched: the rest
  /// lengths are the initial segment lengths. Every node is free. Throws std::invalid_argument
  /// naming the sheet and the parameter for bad input.
  SparSheet(std::string name, const std::vector<Vec2> &nodes, const SheetParameters &parameters);

  const std::string &name() const { return name_; }
  const SheetParameters &parameters() const { return parameters_; }
  const LinearContactLaw &interface_law() const { return interface_law_; }
  double axial_stiffness() const { return parameters_.axial_stiffness; }
  /// The tension-only law of its segments, with its J.
  geosynthetic::TensionOnlyChain chain() const { return {parameters_.axial_stiffness}; }
  double thickness() const { return parameters_.thickness; }

  std::size_t n_nodes() const { return x.size(); }
  std::size_t n_segments() const { return rest_length.size(); }
  Vec2 node(std::size_t k) const { return Vec2(x[k], y[k]); }
  double segment_length(std::size_t k) const;
  /// Strain (l - l0) / l0 of segment k now (negative when slack) [-].
  double segment_strain(std::size_t k) const
  {
    return geosynthetic::TensionOnlyChain::strain(segment_length(k), rest_length[k]);
  }

  /// Node k moves at velocity v whatever the forces (a clamp); its reaction is reported.
  void prescribe_velocity(std::size_t k, const Vec2 &v);
  /// Node k becomes free again (dynamics with its inertial mass).
  void release(std::size_t k);
  bool is_kinematic(std::size_t k) const { return inverse_mass[k] == 0.0; }
  /// Force the clamp applies to kinematic node k to hold its motion, at the last force
  /// evaluation: minus the sum of tension, contact, wall, gravity and load forces on it [N/m]. Zero for a
  /// free node. For the first node of a pulled sheet, its component along the pull is the head
  /// tension.
  Vec2 reaction(std::size_t k) const { return Vec2(reaction_x[k], reaction_y[k]); }

  /// Node k carries the external force `load` from now on [N/m] (zero by default).
  void set_load(std::size_t k, const Vec2 &load);

  /// Keeps nodes [0, n_kept) and the segments between them, with their state; the nodes past
  /// them are dropped (a coupling takes them over: coupling/sheet_crossing.h). The new last node
  /// keeps its mass, half of which is the dropped segment's: the coupling's segment that replaces
  /// it. Throws std::invalid_argument unless 2 <= n_kept <= n_nodes().
  void keep_first_nodes(std::size_t n_kept);

  /// Sets the factor on the inertial masses (>= 1); kinematic nodes stay kinematic.
  void set_mass_scaling(double factor);
  /// Largest stable step of the node dynamics, sqrt(m / k) over the free nodes with k the sum of
  /// the adjacent segments' J / l0 and `contact_stiffness` (the stiffest contact a node can have).
  double critical_time_step(double contact_stiffness) const;
  /// The smallest mass scaling (>= 1) for which critical_time_step(contact_stiffness) >= dt.
  double required_mass_scaling(double dt, double contact_stiffness) const;

  // ---- one velocity-Verlet step, as DemSystem does for bodies ------------------------------------
  /// fx, fy = the weight of each node (gravity on the real mass) plus its external load.
  void start_forces(const Vec2 &gravity);
  /// Adds each segment's axial force to its two nodes and stores it in `tension`.
  void add_axial_forces();
  /// What one step did to the energy balance [J/m].
  struct StepWork
  {
    double damping = 0.0; ///< work of the local damping forces (<= 0: dissipated)
    double boundary = 0.0; ///< work on the rest of the system of the clamps and external loads
  };
  /// Half kick with the forces and local damping forces of the last evaluation, then drift. The
  /// boundary work is the external loads' on the free nodes, load . (x(t + dt) - x(t)) (exact
  /// for a load constant over the step, as gravity's).
  StepWork kick_and_drift(double dt);
  /// After the forces of the new positions are complete: the local damping forces
  /// -alpha |F| sign(v) (Cundall 1987), the reactions of the kinematic nodes, then the second
  /// half kick. The boundary work is the clamps', trapezoidal in time over the reactions of the
  /// previous and this evaluation (as a moving wall's), the kinematic nodes having moved at their
  /// velocity.
  StepWork damp_and_kick(double dt, double local_damping, const Vec2 &gravity);

  // ---- energy [J/m] ---------------------------------------------------------------------------
  double kinetic_energy() const;                             ///< free nodes, inertial mass
  double gravitational_energy(const Vec2 &gravity) const;    ///< free nodes, - m g . x
  double elastic_energy() const;                             ///< sum 0.5 (J / l0) (l - l0)^2, l > l0

  // ---- nodes ----------------------------------------------------------------------------------
  SoaVector<double> x, y;                  ///< [m]
  SoaVector<double> vx, vy;                ///< [m/s]
  SoaVector<double> fx, fy;                ///< resultant of the last force evaluation [N/m]
  SoaVector<double> mass;                  ///< inertial mass (scaled) [kg/m]
  SoaVector<double> inverse_mass;          ///< 0 for a kinematic node [m/kg]
  SoaVector<double> gravitational_mass;    ///< real mass, on which gravity acts [kg/m]
  SoaVector<double> damping_fx, damping_fy; ///< local damping force of the last evaluation [N/m]
  SoaVector<double> reaction_x, reaction_y; ///< see reaction() [N/m]
  SoaVector<double> load_x, load_y;        ///< external force on the node [N/m]
  // ---- segments (segment k joins nodes k and k + 1) -------------------------------------------
  SoaVector<double> rest_length;           ///< l0 [m]
  SoaVector<double> tension;               ///< axial force of the last evaluation, >= 0 [N/m]

private:
  std::string name_;
  SheetParameters parameters_;
  LinearContactLaw interface_law_;
};

/// Nodes along a polyline through `corners`, each straight part cut into equal segments no
/// longer than `max_segment_length`; the corners are nodes. Throws std::invalid_argument for
/// fewer than two corners, coinciding consecutive corners or a non-positive length.
std::vector<Vec2> subdivide_polyline(const std::vector<Vec2> &corners, double max_segment_length);
} // namespace geohybrid::dem
