#pragma once
// The coupling's three benchmarks as functions that return their measured figures, so that the
// tests (tests/test_coupling_*.cc) and `geohybrid coupling-test` run the same code:
//   - the patch test: a uniform strain on both sides of the band, the ghost forces it leaves;
//   - the energy of an undamped coupled run: its drift over many steps;
//   - a long wave through the band: the fraction of its energy the band reflects.
// Measured figures and their discussion: coupling/README.md.
#include "apps/coupling_benchmarks/coupled_patch.h"

#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace geohybrid::coupling::benchmarks
{
/// A uniform in-plane strain (small: the lattice is geometrically exact, the continuum linear) [-].
struct PlaneStrain
{
  double xx = 0.0, yy = 0.0, xy = 0.0;
};

/// The bonded lattice of `discs` (kn, ks of `g`) strained affinely by `strain` about the origin:
/// held at constant velocity for 20 steps (so that the bonded contacts' tangential springs load),
/// then released at rest.
std::unique_ptr<dem::DemSystem> strained_lattice(dem::ParticleSet discs, const PatchGeometry &g, const PlaneStrain &strain);
/// The continuum given u = eps x and the lattice's isotropic prestress -sqrt(3) kn delta0 / d.
void strain_continuum(fem::ExplicitSolver &continuum, const PatchGeometry &g, const PlaneStrain &strain);
/// |sigma| = sqrt(sigma : sigma) of the lattice's in-plane law under `strain` [Pa].
double stress_norm(const PatchGeometry &g, const PlaneStrain &strain);

/// The patch strained uniformly by `strain` on both sides and coupled by `method`: the discs moved
/// affinely (held, at constant velocity over 20 steps, so that their bonded contacts' tangential
/// springs load), then released at rest; the continuum given u = eps x and the lattice's prestress
/// -sqrt(3) kn delta0 / d (isotropic), then the coupled forces at t = 0 evaluated.
CoupledPatch strained_patch(const CouplingMethod &method, const PlaneStrain &strain, const PatchGeometry &geometry = {});
/// The same with the band given instead of patch_band(geometry): the same lattice and mesh, so the
/// band must have the patch's band as its active side (a polygon whose other sides lie far outside
/// the patch tests the polygon's code path on the same physics).
CoupledPatch strained_patch(const CouplingMethod &method, const PlaneStrain &strain, const PatchGeometry &geometry,
                            const OverlapBand &band);

/// The largest residual forces of a strained patch, relative to |sigma| times the length each
/// carries (the spacing d for a disc, the cell width for a node) [-].
struct GhostForces
{
  double particles_outside_band = 0.0; ///< largest |F| on an interior disc of the particle-only region
  double continuum_nodes = 0.0;        ///< largest |r_I| at an interior node, particles' forces projected
  double band_particles = 0.0;         ///< largest |F| a band disc's own tie must carry
  /// The figure of the patch test: the largest ghost force anywhere outside the ties.
  double largest() const { return std::max(particles_outside_band, continuum_nodes); }
};

/// The residual of the constrained system at node I is r_I = f_ext,I - f_int,I + sum_p N_I(X_p)
/// F_p: the forces on the band's discs reach the continuum through the constraint (the
/// multipliers cancel in it), and it is the same for both methods. Discs and nodes whose
/// neighbourhood reaches the patch's free surfaces (where the uniform stress has no traction to
/// balance it) are left out.
GhostForces ghost_forces(const CoupledPatch &patch, const PlaneStrain &strain);

/// The measure behind ghost_forces, for any layout of a strained coupled patch: the largest |F|
/// over |sigma| d of the untied free discs and of the tied ones, and the largest residual r_I over
/// |sigma| times `node_length` (the cell's size across the band) at the nodes, over the discs and
/// nodes the predicates call interior (away from the free surfaces). Also counts them.
struct GhostForceMeasure
{
  GhostForces ghost;
  std::size_t n_discs = 0, n_nodes = 0; ///< untied free discs and DoFs measured
};
GhostForceMeasure measure_ghost_forces(const dem::ParticleSet &particles, const fem::ExplicitSolver &continuum,
                                       const BandParticles &band, double stress, double disc_length,
                                       double node_length, const std::function<bool(std::size_t)> &interior_disc,
                                       const std::function<bool(const dealii::Point<2> &)> &interior_node);

struct PatchTestResult
{
  GhostForces ghost;
  std::size_t n_particles = 0, n_cells = 0;
};
PatchTestResult patch_test(const CouplingMethod &method, const PlaneStrain &strain, const PatchGeometry &geometry = {});
/// Through a given band (see strained_patch).
PatchTestResult patch_test(const CouplingMethod &method, const PlaneStrain &strain, const PatchGeometry &geometry,
                           const OverlapBand &band);

// ---- The patch test along the lattice's rows: the layout in which the weights are exact ----
//
// With the band running along the lattice's rows (its normal +y), the weight is constant along a
// row, so a disc's two horizontal contacts cancel and its two upper contacts share one weight:
// the net weighted force on a disc of row k is (W_k+1/2 - W_k-1/2) F_up, W the mean of the
// particles' weight 1 - w over [y_k, y_k+1] and F_up the force of its two upper neighbours
// (d sigma.e_y). Its projection sum_p N_I(x_p) F_p equals the continuum's -int w sigma : grad N_I
// exactly when (i) the cells' sides lie on multiples of half a spacing and their width is a whole
// number of spacings (each row's sum of a hat N_I is then its integral: the trapezoidal rule on
// one row parity, the midpoint rule on the other, both exact for piecewise linear functions),
// (ii) the cells' horizontal sides lie on lattice rows (N_I is then linear between two rows, and
// the sum over rows is the integral summed by parts), (iii) the band's edges lie on cell sides
// (w linear in each cell: 2x2 Gauss integrates w grad N_I exactly), and (iv) both models carry
// the same stress. (iv) is where the DEM's geometric non-linearity enters: the closed-form moduli
// are its tangent at zero strain, so the continuum's C : eps differs from the strained lattice's
// stress by O(eps) relative. Given the lattice's own stress, the continuum carries exactly what
// the lattice does and the residual is the coupling's alone, at any strain; then the strain can
// be large enough (1e-3) for the discs' position round-off (about 1e-17 m, against contact
// displacements eps d) to fall below 1e-10 of the forces.
// Across the rows (the straight patch above) or with cells out of step with the lattice, (i)-(iii)
// fail and a quadrature error of order d / w remains (coupling/README.md).
// Moments: under a shear strain a disc's contacts carry tangential forces, whose moments about
// its centre cancel by symmetry only where the weight is linear over the disc's three rows. On
// the rows at the band's two edges (the weight's kinks) a disc is left a moment
// (W_k+1/2 + W_k-1/2 - 2 W_k)(m_60 + m_120), which no translation constraint balances: reported,
// not removed (zero for strains without shear).

/// How a patch test stresses the continuum.
enum class PatchContinuumStress
{
  matching_moduli, ///< u = eps x with the lattice's closed-form moduli (and its prestress), on the unstrained mesh
  lattice          ///< the strained lattice's own stress, on the mesh strained with it (u = 0 from there)
};

/// The stress of the strained lattice at disc `body`, as a continuum can carry it: the Love-Weber
/// stress of its contacts over its Voronoi cell (d h det(I + eps) for the hexagonal lattice of
/// `g`) is not quite symmetric under a finite shear (the incremental tangential springs leave
/// each disc a moment of order eps^2), so the symmetric stress returned has the lattice's
/// traction on planes of unit normal `normal` (the band's: what the coupling transmits) and its
/// normal stress along them; sigma_zz = nu (sigma_xx + sigma_yy) of the matching continuum [Pa].
/// Exact for a disc whose six contacts are the lattice's (away from free surfaces).
fem::StressTensor lattice_stress(const dem::DemSystem &lattice, std::size_t body, const PatchGeometry &g,
                                 const PlaneStrain &strain, const Vec2 &normal);

/// The layout of the row patch, lengths in spacings d (rows at y = j h, h = d sqrt(3) / 2; the odd
/// rows shifted half a spacing right). The default is commensurate ((i)-(iii) above): rows 0-5
/// particles only, the band on rows 6-10 (w = 4 h), cells 2 d x 2 h from x = -0.5 d, the mesh to
/// y = 18 h.
struct RowPatchLayout
{
  unsigned int columns = 14;        ///< discs per row
  double band_start = 6.0 * std::sqrt(3.0) / 2.0; ///< y of the band's particle edge, the mesh's bottom
  double band_width = 4.0 * std::sqrt(3.0) / 2.0; ///< w
  double mesh_top = 18.0 * std::sqrt(3.0) / 2.0;
  double mesh_left = -0.5, mesh_right = 15.5;
  unsigned int cells_x = 8, cells_y = 6;
};

/// The commensurate row patch nearest a band `band_width` spacings wide and cells about
/// `cell_size` spacings wide: the band an even number of rows (at least 2), cells 2 rows high and
/// a whole number of spacings wide (at least 1) from x = -0.5 d over at least 16 spacings (the
/// default 14 columns of discs), 6 rows of particles
/// below the band and 8 rows of mesh above it. Throws std::invalid_argument naming 'band width'
/// or 'cell size' if not positive.
RowPatchLayout commensurate_row_patch(double band_width, double cell_size);

/// The patch test along the rows: the ghost forces as GhostForces (relative to |sigma| d for a
/// disc, |sigma| times the cell height for a node), measured on the discs and nodes whose
/// neighbourhood stays inside the lattice (away from its free bottom and its two ends) and below
/// the mesh's free top; and the largest moment on a measured disc, tied or not, relative to
/// |sigma| d^2. |sigma| is the lattice's (its stress at the strain, `lattice_stress`).
struct RowPatchTestResult
{
  GhostForces ghost;
  double disc_moments = 0.0;
  std::size_t n_discs = 0, n_nodes = 0, n_tied = 0, n_driven = 0;
};
RowPatchTestResult row_patch_test(const CouplingMethod &method, const PlaneStrain &strain,
                                  PatchContinuumStress stress, const PatchGeometry &lattice = {},
                                  const RowPatchLayout &layout = {});

/// One sample of an undamped coupled run's energies [J/m], at `time` [s].
struct EnergySample
{
  double time = 0.0;
  double relative_change = 0.0; ///< (E(t) - E(0)) / E(0) [-]
  double particle_energy = 0.0, continuum_kinetic = 0.0, continuum_elastic = 0.0, coupling_energy = 0.0;
};

/// The energy of an undamped coupled run, sampled every 10 steps, relative to E(0): its drift
/// (the mean over the last quarter of the run minus the mean over the first quarter), its largest
/// deviation from E(0), the largest share of E(0) the continuum held.
struct EnergyRecord
{
  double drift = 0.0, largest_deviation = 0.0, continuum_share = 0.0;
  double time_step = 0.0; ///< [s]
  /// Over every step: the largest |sum of the coupling forces on both sides| (round-off if the
  /// coupling conserves momentum) and the largest |sum on the particles| [N/m].
  double largest_force_imbalance = 0.0, largest_coupling_force = 0.0;
  std::vector<EnergySample> history;
};

/// The energy of `stepper`'s undamped run of `n_steps` steps from its present state (the record
/// above; E(0) is the energy now). Throws std::invalid_argument below 40 steps.
EnergyRecord undamped_energy_record(CoupledStepper &stepper, unsigned int n_steps);

/// A smooth pulse of x-velocity, amplitude x exp(-((x - 2 d) / 2 d)^2) [m/s], on the discs of the
/// particle-only region of `patch` (x_c two spacings in, width two spacings): a wave that crosses
/// the band.
void launch_energy_pulse(CoupledPatch &patch, double amplitude);

/// The patch at rest, a smooth pulse of x-velocity V exp(-((x - 2 d) / 2 d)^2), V = 1 mm/s, on
/// the discs of the particle-only region (a wave that crosses the band), run undamped for
/// `n_steps` steps of `time_step` (0: the stepper's own) [s].
EnergyRecord energy_record(const CouplingMethod &method, unsigned int n_steps, double time_step = 0.0,
                           const PatchGeometry &geometry = {}, const MultiRate &rate = {});

/// A pulse of x-velocity 1e-3 exp(-r^2 / width^2) [m/s]: 1D (r = x - x0) or a 2D blob round
/// (x0, y0) [m].
struct Pulse
{
  double x0 = 0.0, y0 = 0.0, width = 0.0;
  bool blob = false;
  double value(double x, double y) const;
};

/// The energy of the difference between the coupled run and a run of the particles alone over
/// the whole patch (the reference: no band, no reflection), summed over the coupled run's free
/// discs (kinetic, and the linearised springs of the contacts between them), relative to half
/// the initial energy (a 1D pulse sends half of it toward the band; a 2D blob less: for it the
/// fraction is a bound from above).
struct WaveSample
{
  double time = 0.0;              ///< [s]
  double reflected = 0.0;         ///< the difference energy in the free discs / half E(0) [-]
  double in_continuum = 0.0;      ///< the continuum's kinetic + elastic energy / half E(0) [-]
};
struct WaveRecord
{
  double reflected = 0.0, transmitted = 0.0; ///< the last sample's
  double time_step = 0.0;                    ///< [s]
  unsigned int n_steps = 0;
  std::size_t n_particles = 0, n_cells = 0;  ///< of the coupled run
  std::vector<WaveSample> history;           ///< about 200 samples, the last at the end
};

/// The energy [J/m] of the difference between a coupled run's discs and the same discs in a run
/// of the lattice alone (`reference`; `coupled_of[r]`: the coupled body of reference body r, -1
/// if it is not counted): kinetic, and the linearised springs (kn, ks of `g`) of the reference's
/// touching contacts between counted discs.
double difference_energy(const dem::DemSystem &coupled, const dem::DemSystem &reference,
                         const std::vector<long> &coupled_of, const PatchGeometry &g);

/// Steps the coupled run and the reference together for record.n_steps steps (both at the same
/// step), sampling the difference energy and the continuum's share over `half_initial` [J/m]
/// about 200 times (the samples only read), and sets record.reflected and record.transmitted
/// from the last sample.
void run_beside_reference(CoupledStepper &stepper, dem::DemSystem &reference, const dem::DemSystem &coupled,
                          const std::vector<long> &coupled_of, const PatchGeometry &g, double half_initial,
                          WaveRecord &record);

/// The pulse launched on the free discs of the patch `g` at rest, run until the slowest wave of
/// interest, at `speed` [m/s], has gone `travel` [m]. `continuum_step_ratio` as StripSpec's.
WaveRecord crossing(const CouplingMethod &method, const PatchGeometry &g, const Pulse &pulse, double travel,
                    double speed, unsigned int continuum_step_ratio = 1);

/// A strip 6 rows high (3 cells over its height: the wave is 1D-like): particles over `length`
/// spacings, a band of `band_width` spacings, the continuum `length` spacings beyond it in cells of
/// `cell_size` spacings along the strip. The pulse, `pulse_width` spacings wide, starts halfway
/// along the particle region; it is measured when it has run half `length` into the continuum, at
/// the bar speed sqrt(E_2D / rho) (the long-wave speed of a strip with free sides).
struct StripSpec
{
  double band_width = 4.0, pulse_width = 4.0, length = 40.0, cell_size = 1.0; ///< in spacings
  /// Multi-rate (MultiRate): the particles at the lockstep's step over it, the continuum at the lockstep's.
  unsigned int continuum_step_ratio = 1;
};
PatchGeometry strip_geometry(const StripSpec &spec, const PatchGeometry &lattice = {});
WaveRecord strip_crossing(const CouplingMethod &method, const StripSpec &spec, const PatchGeometry &lattice = {});

// ---- The geostatic column (methods 1 and 2): gravity and damping across the band ----

/// A column under its own weight across the band, damped to rest. The patch's layout turned on
/// its side: gravity points along -x, so x is the height; the lattice (particles below the band,
/// `rows` rows wide, its first disc of each row fixed: the rigid base) carries the band and the
/// continuum above it, whose far edge x_top = continuum_end spacings is the free surface. Sides
/// free on both models (a uniaxial column), the continuum's density the lattice's mass per area,
/// local damping on both sides (the multipliers' tied discs and nodes exempt: coupled_stepper.h).
/// At rest the vertical stress is the weight above, sigma_xx(x) = -rho g (x_top - x), in both
/// models whatever the lateral stress, since the sides carry no shear.
struct ColumnSpec
{
  double gravity = 9.81;              ///< [m/s^2]
  double local_damping = 0.7;         ///< both sides [-]
  unsigned int rows = 8;
  double band_start = 16.3, band_width = 4.0, continuum_end = 36.3; ///< in spacings
  double window = 4.0;                ///< length of each stress window along the column, in spacings
  double tolerance = 1e-6;            ///< rest: the windows' stresses change by less than this, relative, over 500 steps
  unsigned int max_steps = 60000;
  /// The band's inertia scaled (BandTreatment::scale_inertia): the statics must not change.
  bool scale_band_inertia = false;
  double time_step = 0.0;             ///< [s]; 0: the coupled stable step (a smaller one is taken as given)
  /// Multi-rate (MultiRate): with time_step 0, the particles take the lockstep's step over it and
  /// the continuum the lockstep's. Rest is checked every 500 steps: a divisor of 500.
  unsigned int continuum_step_ratio = 1;
};
/// One stress window: its centre's height [m], the measured vertical stress and the weight above
/// it (both as compressions, positive) [Pa], the model that measured it.
struct ColumnSample
{
  double height = 0.0, measured = 0.0, closed_form = 0.0;
  bool particles = true; ///< Love-Weber stress of the lattice; false: the continuum's mean stress
  double relative_error() const { return (measured - closed_form) / closed_form; }
};
struct ColumnRecord
{
  std::vector<ColumnSample> samples;   ///< from the base up: the lattice's windows below the band, the continuum's above
  unsigned int n_steps = 0;            ///< to rest
  double time_step = 0.0;              ///< the particles' [s]
  unsigned int continuum_step_ratio = 1; ///< the continuum's step over time_step
  double base_stress = 0.0;            ///< rho g x_top, the closed-form stress at x = 0 [Pa]
  /// At rest: the largest |(x_p - X_p) - u(X_p)| of the tied discs (the ties hold them on the
  /// continuum: round-off with the multipliers, the springs' stretch with the penalty), and the
  /// largest tied displacement |x_p - X_p| it compares with [m].
  double tied_mismatch = 0.0, tied_displacement = 0.0;
  /// energy_balance_error (coupled_stepper.h) from the start to rest (gravity, damping and the
  /// multipliers or springs in the ledger), and the largest |value| at the checks every 500 steps,
  /// where the first ones, in the release's dynamics, weigh the two integrators' different
  /// kinetic energies against a small scale [-].
  double energy_balance_error = 0.0, largest_energy_balance_error = 0.0;
  double largest_relative_error() const;
  /// The step in vertical stress across the band: the continuum's first window above it against
  /// the lattice's last below it, each relative to its closed form: (s_c / s_c,0) - (s_p / s_p,0) [-].
  double jump_across_band() const;
};
/// Throws std::invalid_argument for the interface coupling (method 3 has no band: its column is
/// interface_geostatic_column) or if rest is not reached within max_steps.
ColumnRecord geostatic_column(const CouplingMethod &method, const ColumnSpec &spec = {});

/// The columns' run to rest: `stepper` advances 500 steps at a time (counted in
/// `record.n_steps`) until no value of `measure` changes by more than `tolerance` x
/// `record.base_stress` over 500 steps; returns the last values. Throws std::invalid_argument
/// naming `what` and 'max steps' if that takes more than `max_steps`.
std::vector<double> run_column_to_rest(CoupledStepper &stepper, const std::function<std::vector<double>()> &measure,
                                       double tolerance, unsigned int max_steps, ColumnRecord &record,
                                       const std::string &what);

// ---- Method 3, the non-overlapping interface: a lattice standing on the continuum ----
// (standing_lattice.h; the same measures as above, across the interface y = 0 instead of a band.)

/// Method 3's patch test: 14 x 9 discs standing on 14 x 6 cells of one spacing, strained
/// affinely by `strain` as in strained_patch (held, then released at rest), the continuum given
/// u = eps x and the lattice's prestress, the interface's forces at t = 0 evaluated. The ghost
/// forces relative to |sigma| d (a disc and a node both carry one spacing): the largest |F| on
/// the bottom row's discs and the largest residual f_ext - f_int at the interface's nodes, both
/// more than 1.5 spacings from the free sides. Closed form with the matched springs
/// (coupling/README.md): round-off for a uniaxial eps_yy, lambda eps_xx / |sigma| otherwise (one
/// normal spring per disc has no Poisson coupling). Throws std::invalid_argument if strain.xy is
/// not 0 (a contact formed at the strained state starts with an unloaded tangential spring: the
/// set-up cannot strain the interface in shear) or if the strain is 0.
struct InterfacePatchTestResult
{
  double bottom_discs = 0.0, interface_nodes = 0.0; ///< [-]
  double stress = 0.0;                              ///< |sigma| of the strain [Pa]
  std::size_t n_particles = 0, n_cells = 0;
  double largest() const { return std::max(bottom_discs, interface_nodes); }
};
InterfacePatchTestResult interface_patch_test(const InterfaceCoupling &interface, const PlaneStrain &strain,
                                              const PatchGeometry &lattice = {});

/// Method 3's long wave: the standing strip of `spec` (standing_strip), a Gaussian pulse of
/// downward velocity 1e-3 exp(-((y - y0) / s)^2) [m/s] on every disc, y0 = length / 2 spacings
/// above the bottom row, s = pulse_width spacings (its downward half a compression that crosses
/// the interface: the interface carries no tension). Measured as `crossing`: the difference from
/// the lattice extended below the interface in place of the continuum, over all the coupled
/// run's discs, relative to half the initial energy, when the pulse has run half `length` into
/// the continuum at the bar speed.
WaveRecord interface_strip_crossing(const InterfaceCoupling &interface, const StripSpec &spec,
                                    const PatchGeometry &lattice = {});

/// Method 3's geostatic column: `columns` x `rows` bonded discs standing on the matching
/// continuum, `depth` cells of one spacing deep, its base fixed, the sides of both free; gravity
/// along -y and local damping `local_damping` on both sides; run, 500 steps at a time, until the
/// windows' stresses change by less than `tolerance` of the base stress. The vertical stress of
/// windows `window` spacings high against the weight above: the lattice's Love-Weber stress over
/// whole rows from the second row up (the bottom row's interface forces are not contacts, which
/// Love-Weber counts) to the last whole window below the top, the continuum's cell mean from the
/// interface down to the base. Samples from the top down: the lattice's last sample and the
/// continuum's first are the two beside the interface (ColumnRecord::jump_across_band). Throws
/// std::invalid_argument if rest is not reached within max_steps.
struct InterfaceColumnSpec
{
  double gravity = 9.81;              ///< [m/s^2]
  double local_damping = 0.7;         ///< both sides [-]
  unsigned int columns = 8, rows = 24, depth = 20;
  double window = 4.0;                ///< in spacings (the lattice's: whole rows, the nearest number)
  double tolerance = 1e-6;
  unsigned int max_steps = 60000;
};
ColumnRecord interface_geostatic_column(const InterfaceCoupling &interface, const InterfaceColumnSpec &spec = {},
                                        const PatchGeometry &lattice = {});

/// Method 3's undamped energy run: the standing strip of `spec` with the pulse of
/// interface_strip_crossing, `n_steps` steps of `time_step` (0: the coupled stable step) [s]. The
/// pulse crosses, reflects at the continuum's free bottom as a tension that opens the interface.
EnergyRecord interface_energy_record(const InterfaceCoupling &interface, const StripSpec &spec, unsigned int n_steps,
                                     double time_step = 0.0, const PatchGeometry &lattice = {});
} // namespace geohybrid::coupling::benchmarks
