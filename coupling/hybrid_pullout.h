#pragma once
// The hybrid pull-out (issue 6, `geohybrid pullout` with mode = hybrid): the INSA tank of the DEM
// pull-out (dem/laboratory/pullout_tank.h) with particles only in a box round the anchorage and the
// rest of the tank a deal.II continuum, tied across an overlap band by the coupled stepper.
//
// The set-up, in the tank's frame (x from the back wall to the front wall, y up):
//
//   y = fill  +-------------------------------------------------------+
//             |                 continuum                             |
//             |        +----------------- particle box ---------------+
//             |        |  band | pad                                  |
//             |        |   +------------- DEM core -------------------|  front wall
//             |        |   |      ==========  sheet  =================== o clamp
//             |        |   +------------------------------------------|
//             |        +----------------------------------------------+
//   y = 0     +-------------------------------------------------------+
//
// - The particle box reaches `margin` beyond the sheet below it, above it (above the upper part
//   of a wrap-around) and behind its far end, clipped to the tank: a side of the box on a tank
//   wall keeps that wall, the others are shared with the continuum. The box is filled in lifts as
//   the DEM tank is (dem/laboratory/tank_filling.h), its walls where the tank's are and temporary walls on
//   its shared sides, with as many particles as the whole tank would have in its area (the same
//   grain size); the sheet is laid on the lift at its depth. Its lifts: particle_box.h. Once
//   filled, and before the coupling, the box settles on its own: under the overburden through
//   its lid, or after its sheet was cut (hybrid_box_settling.h).
// - Method 3 (InterfaceCoupling) has no band: the DEM core is the box, the continuum's mesh the
//   tank without it, its hole's edges the deformable walls the grains touch with their own contact
//   law (frictional, no bonds); the hole's top is the box's settled top surface (where the lid
//   stood under the overburden), not the lift's top above the grains. No sheet crossing with it.
// - Methods 1 and 2: the DEM core is the box less, on each shared side, a pad of one branch length (the longest
//   contact between two bodies: the driven particles of coupled_stepper.h) and the band (width w).
//   The continuum's mesh is the tank's with the core's cells removed (hybrid_continuum.h); the
//   core's and the band's edges lie on mesh lines, the cells are uniform over the band and the
//   core's span and grow away from them (the continuum runs at the particles' step: its cells
//   cost as much as the particles on a uniform mesh). It starts at the geostatic stress of the whole
//   tank (sigma_v = gamma (fill - y), sigma_h = K0 sigma_v), u = 0, under gravity; the base is
//   fixed, the back and front walls are smooth rollers, the top is free.
// - The temporary walls are parked away, the coupling ties the particles to the continuum (the
//   overburden now comes through the band), and both settle together, damped, until the
//   particles' unbalanced-force ratio is below the fill's; then the clamp pulls the sheet as in
//   the DEM pull-out (dem::PullOut, advanced by the coupled stepper).
//
// - With a DEM region length (HybridRegionSpec::dem_region_length), the box is that long and
//   the sheet laid in it reaches two thicknesses from its back; after the fill the sheet is cut at the
//   core's edge: the nodes past it (in the pad and the band) and the rest of the sheet as drawn
//   (the lower part's tail; a wrap-around's return and upper part) become a truss sheet in the
//   continuum, joined to the particles' part by one segment (sheet_crossing.h). The head
//   tension is still the DEM clamp's. Nodes are not handed over: the continuum's first nodes,
//   pulled into the core, keep the soil at the drawn path's start (coupling/README.md).
//
// What is left out, on purpose or not yet: without a DEM region length the sheet must lie in the
// DEM core, one branch clear of the band (`margin` is checked against that); wall contacts of the band's particles (at the front
// wall, at the base) are not weighted (dem::CouplingAttachment::set_energy_weights); the continuum's walls are
// smooth (the DEM's have the wall friction); one MPI rank. Checkpoints: the filled box (a DEM
// checkpoint) and, during the pull, the particles' and the continuum's states; a resumed run
// repeats the set-up from the filled box (deterministic) and takes the states (restore_state).
#include "coupling/continuum_region.h"
#include "coupling/coupled_stepper.h"
#include "coupling/coupling_method.h"
#include "coupling/overlap_band.h"
#include "coupling/particle_box.h"
#include "dem/laboratory/pullout_tank.h"
#include "fem/constitutive/soil_model.h"
#include "fem/sheet_interface.h"
#include "fem/explicit_solver.h"

#include <deal.II/distributed/tria.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace geohybrid::coupling
{
/// Where the particles are and how they meet the continuum.
struct HybridRegionSpec
{
  /// From the sheet to the particle box's edge, below, above and behind it; 0.15 m by default, the
  /// least within 3 % of pure DEM's sheet normal force on the wrap-around (VALIDATION.md 6.4) [m].
  double margin = 0.15;
  /// 0: the whole sheet lies in the particles' core (the box reaches `margin` behind its end).
  /// Otherwise the particle box reaches only this far back from the front wall, shorter than the
  /// lower part L: the sheet crosses into the continuum (sheet_crossing.h), its part in the core
  /// touched by the grains, the rest (from the core's edge on) held by the continuum's
  /// Mohr-Coulomb interface (HybridContinuumSpec::sheet_interface) [m].
  double dem_region_length = 0.0;
  /// The box's lifts are at most this thick; 0 = automatic, from the grains and the margin
  /// (particle_box.h) [m].
  double lift_thickness = 0.0;
  /// The box is cut out of a filled tank (the app's 'Hybrid/particles from'), not filled: given
  /// lifts then set only its shape, whatever the grains' size, and it is not settled under its
  /// overburden (fill_under_overburden): its grains stand as they stood in the tank, under it all.
  bool box_cut_from_a_filled_tank = false;
  double band_width = 0.0;       ///< w; 0 = four mean grain sizes [m]
  double cell_size = 0.0;        ///< of the continuum's cells in the band and over the core's span; 0 = w / 2 [m]
  /// The cells grow (by 1.3 per cell) away from the band up to this size; 0 = 4 x cell_size [m].
  double far_cell_size = 0.0;
  CouplingMethod method = LagrangeMultiplierCoupling{};
  /// The band's particles lighter than this are driven by the continuum, not tied to it: the
  /// stable step then stays within about a third of the particles' own (OverlapBand::driven_from;
  /// with 0 a tank's band took it from 4e-5 s to 1.6e-7 s) [-].
  double driven_below_weight = 0.1;
  /// The band's inertia scaled (dem::CouplingAttachment::scale_band_inertia): a quasi-static
  /// pull-out needs the band's statics, not its weighted dynamics, and the step goes back to the
  /// particles' own.
  bool scale_band_inertia = true;
  /// The continuum's step in particle steps (MultiRate; method 1 only): 1 lockstep, 0 automatic.
  unsigned int continuum_step_ratio = 1;
  /// Before the coupling, the box's top (if the continuum lies above it) is loaded by the weight
  /// of the soil above it, gamma (fill - y1), through a frictionless lid servo-controlled to that
  /// stress, and the box settles under it; the lid is then parked. The particles so start at the
  /// overburden the continuum starts at (its geostatic stress). Without it, the box, filled under
  /// its own weight alone, takes the overburden only once tied to the continuum, settles more than
  /// the continuum beside it, and the load arches onto the continuum (coupling/README.md).
  bool fill_under_overburden = true;
  /// Throws std::invalid_argument naming `where` and the parameter.
  void validate(const std::string &where) const;
};

/// The continuum soil of the far field (from the biaxial calibration: `geohybrid biaxial` writes it).
struct HybridContinuumSpec
{
  fem::SoilParameters soil;
  double k0 = 0.0;             ///< sigma_h / sigma_v at rest; 0 takes the soil's default (1 - sin phi) [-]
  double local_damping = 0.7;  ///< the continuum's, as the grains' [-]
  /// The interface of the sheet's part in the continuum (HybridRegionSpec::dem_region_length):
  /// friction angle, cohesion and penalty stiffnesses. Its friction angle should be the
  /// macroscopic angle the DEM's sheet mobilises (calibrate it on a DEM pull-out, T / (2 sigma_v
  /// L)), which is below the grains' contact angle (the tank's sheet interface's).
  fem::SheetInterfaceParameters sheet_interface;
};

struct HybridPullOutSpec
{
  /// The whole tank: its geometry, sheet, soil and filling (n_particles for the whole tank).
  dem::PullOutTankSpec tank;
  HybridRegionSpec region;
  HybridContinuumSpec continuum;
  /// Settling of the coupled model before the pull: until the particles' unbalanced-force ratio
  /// is below the fill's (tank.filling.equilibrium_unbalanced_ratio), at most this many steps.
  std::uint64_t max_settling_steps = 200000;
  void validate(const std::string &where) const;
};


/// What the set-up measured.
struct HybridSetUp
{
  std::size_t n_particles = 0, n_cells = 0, n_tied = 0, n_driven = 0;
  double band_width = 0.0, cell_size = 0.0, pad = 0.0; ///< [m]
  std::uint64_t fill_steps = 0, settling_steps = 0;
  /// The box under its overburden (HybridRegionSpec::fill_under_overburden): the stress asked
  /// and the lid's stress when released (0 if not loaded) [Pa].
  double overburden = 0.0, overburden_reached = 0.0;
  /// The box's own settling after the fill, before the coupling: under its overburden, or
  /// after its sheet was cut (0 if neither).
  std::uint64_t box_settling_steps = 0;
  double settled_unbalanced_ratio = 0.0;
  double time_step = 0.0;          ///< the coupled step [s]
  /// The sheet's nodes in the particles' core and in the continuum (0 when it does not cross),
  /// and where it crosses: x of the joining segment's DEM end, in the tank's frame [m].
  std::size_t n_sheet_nodes_particles = 0, n_sheet_nodes_continuum = 0;
  double crossing_x = 0.0;
  double particle_time_step = 0.0; ///< the particles' own step, before the coupling [s]
  /// Wall time of the box's own settling (box_settling_steps) and of the coupled settling
  /// (settling_steps) [s]; the continuum's and the band's building is the rest of the set-up.
  double box_settling_wall_time = 0.0, coupled_settling_wall_time = 0.0;
};

class HybridPullOut
{
public:
  /// Fills the particle box, builds the continuum, ties them and settles the coupled model.
  /// `progress` (optional) gets a fraction in [0, 1] of the fill. Throws std::invalid_argument
  /// for bad input (naming the parameter), std::runtime_error if the fill or the settling fails.
  HybridPullOut(const HybridPullOutSpec &spec, const std::string &where,
                const std::function<void(double)> &progress = {});
  /// The same from a box filled earlier (the dem::PullOutTank of fill_particle_box, or one
  /// restored from a checkpoint written after the fill: dem::restore_pullout_tank): the set-up
  /// from there is the first constructor's, bit for bit.
  HybridPullOut(const HybridPullOutSpec &spec, const std::string &where, dem::PullOutTank filled_box);
  HybridPullOut(const HybridPullOut &) = delete;
  HybridPullOut &operator=(const HybridPullOut &) = delete;
  ~HybridPullOut();

  /// Pulls the clamp as dem::pull_out does (the same PullSpec), the coupled stepper advancing
  /// both models; `record` is called with each point.
  std::vector<dem::PullPoint> pull(const dem::PullSpec &spec,
                                   const std::function<void(const dem::PullPoint &)> &record = {});
  /// What advances the coupled model one step of a pull (dem::PullOut's `advance`, for a pull
  /// driven step by step): the stepper's step, counted in pull_steps(). The function refers to
  /// this object.
  std::function<void()> pull_step();

  /// The coupled run's state between two steps of a pull, beyond the particles' own
  /// (particle_system().export_state()): the continuum's (its sheet's included) and the pull's
  /// step count. The rest (the band, its weights and ties, the crossing) is the set-up's, which
  /// the constructors rebuild bit for bit from the same filled box.
  fem::ExplicitSolverState continuum_state() const { return continuum_->export_state(); }
  /// Continues a run from a checkpoint: `particles` and `continuum` exported at one moment of a
  /// pull by a HybridPullOut set up from the same input and filled box. Throws
  /// std::invalid_argument if they do not fit this one.
  void restore_state(dem::DemSystemState particles, const fem::ExplicitSolverState &continuum,
                     std::uint64_t pull_steps);

  const HybridSetUp &set_up() const { return set_up_; }
  std::uint64_t pull_steps() const { return pull_steps_; } ///< coupled steps taken by pull()
  const ParticleBox &box() const { return box_; }
  const dem::PullOutTank &particles() const { return *tank_; }
  dem::DemSystem &particle_system() { return tank_->tank.system; }
  const fem::ExplicitSolver &continuum() const { return *continuum_; }
  CoupledStepper &stepper() { return *stepper_; }
  const OverlapBand &band() const { return *band_; }

private:
  /// What both constructors do once the box is filled (tank_): the core, the continuum, the tie
  /// and the coupled settling.
  void set_up_coupled_model(const HybridPullOutSpec &spec, const std::string &where);

  ParticleBox box_;
  std::unique_ptr<dem::PullOutTank> tank_;
  std::unique_ptr<dealii::parallel::distributed::Triangulation<fem::dim>> mesh_;
  std::unique_ptr<fem::ExplicitSolver> continuum_;
  std::unique_ptr<OverlapBand> band_;
  std::unique_ptr<CoupledStepper> stepper_;
  HybridSetUp set_up_;
  std::uint64_t pull_steps_ = 0;
};
} // namespace geohybrid::coupling
