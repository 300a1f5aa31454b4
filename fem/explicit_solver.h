#pragma once
// The explicit dynamic solver of the soil: M a = f_ext(t) - f_int(u) - f_damping, integrated with
// central differences (velocities at half steps) on a lumped (row-sum) mass, so that a step costs
// one pass over the cells (strain increment, SoilModel::update, internal force) and a few vector
// operations, and never a global matrix. This is the solver the DEM coupling runs in lockstep with.
//
// Damping, for quasi-static runs (both may be combined, both default to none):
// - mass-proportional (Rayleigh alpha): f_d = alpha M v, which damps low frequencies most;
// - local non-viscous damping as in PFC/FLAC (Cundall 1987): f_d,i = alpha_l |f_i| sign(v_i) per
//   DoF, a force against the motion proportional to the out-of-balance force, which needs no
//   frequency and vanishes at equilibrium.
//
// The stable step comes from the mesh: the largest eigenfrequency of the lumped system is bounded
// by the largest element eigenfrequency omega_e (Irons' element eigenvalue theorem) of the elastic
// stiffness, so dt_crit = 2 / max_e omega_e. For a 1D-like bar of Q1 cells this is h / c_p
// (the cell size over the P-wave speed); in 2D and for Q2 it is the exact, smaller, bound. The step
// used is a safety factor times dt_crit, and a user step above that is refused. Plastic flow only
// softens the stiffness, so the elastic bound stays safe.
//
// Every step commits the material points (the stress is integrated from the last step's). The
// state lives in deal.II distributed vectors with ghosts: the solver works on any number of MPI
// ranks and gives the same numbers (to round-off in the order of summation) on each.
#include "fem/boundary_conditions.h"
#include "fem/constitutive/soil_model.h"
#include "fem/displacement_space.h"
#include "fem/geostatic_stress.h"
#include "fem/material_point_history.h"
#include "fem/sheet_interface.h"

#include <deal.II/lac/la_parallel_vector.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace geohybrid::fem
{
struct ExplicitDamping
{
  double mass_proportional = 0.0; ///< alpha in f_d = alpha M v, >= 0 [1/s]
  double local = 0.0;             ///< alpha_l in f_d = alpha_l |f| sign(v), in [0, 1) (PFC's default 0.7) [-]
};

/// The continuum's energy ledger since the first step [J/m], from the work of each force on the
/// free DoFs (those without a prescribed displacement). Central differences keep an exact discrete
/// balance: M (v_n+1/2 - v_n-1/2) = dt_n f_n dotted with the mean velocity (v_n+1/2 + v_n-1/2) / 2
/// gives the change of 1/2 v.M v over the step as f_n . du_n, du_n = dt_n (v_n+1/2 + v_n-1/2) / 2
/// (dt_n the mean of the two half steps); each force's work is booked with that du_n, so the
/// terms close to round-off whatever the soil does. The internal work is the energy the soil took
/// from the start (its elastic energy change plus its plastic work, with the initial stress's work
/// against the displacement; weighted by the energy weights), the sheet's interface forces on the
/// soil included; an embedded sheet's own energy is in its ledger (SheetEnergyLedger,
/// EmbeddedSheet::energy_ledger). Supports that move do work on their DoFs that is not booked
/// (fixed supports do none).
struct ExplicitEnergyLedger
{
  double kinetic = 0.0;           ///< 1/2 v.M v of the half-step velocity on the free DoFs, now
  double initial_kinetic = 0.0;   ///< the same before the first step
  double internal_work = 0.0;     ///< sum f_int . du: elastic energy stored and plastic work
  double damping_work = 0.0;      ///< dissipated by the mass-proportional and the local damping
  double gravity_work = 0.0;      ///< of the body force rho g
  double load_work = 0.0;         ///< of the boundary tractions and pressures
  double added_force_work = 0.0;  ///< of the forces added through add_external_force (a coupling's)
  /// Zero to round-off: kinetic energy gained + internal work + dissipated - work supplied.
  double balance() const
  {
    return kinetic - initial_kinetic + internal_work + damping_work - gravity_work - load_work - added_force_work;
  }
};

struct ExplicitSettings
{
  unsigned int element_degree = 1; ///< 1 (Q1) or 2 (Q2); Q1 is cheaper per step and per stable step
  double density = 0.0;            ///< rho, for mass and body force, > 0 [kg/m^3]
  dealii::Tensor<1, dim> gravity;  ///< g [m/s^2] (zero by default: set (0, -9.81) for self-weight)
  double safety_factor = 0.8;      ///< the stable step is this times dt_crit, in (0, 1] [-]
  double time_step = 0.0;          ///< [s]; 0 takes the stable step, a larger one is refused
  ExplicitDamping damping;
  /// OpenMP threads over the cells' internal force; the same numbers on any count (the cells
  /// are coloured: no two of a colour share a node, and each node sums its cells colour by colour).
  unsigned int n_threads = 1;

  /// Throws std::invalid_argument naming `where` and the parameter.
  void validate(const std::string &where) const;
};

/// What an ExplicitSolver changes as it runs, as plain numbers: a checkpoint keeps it to continue
/// the run exactly, bit for bit (the mesh, the soil, the settings, the loads, the energy weights
/// and an attached sheet's geometry are rebuilt from the input first). One rank: the vectors hold
/// the locally owned DoFs in their local order.
struct ExplicitSolverState
{
  double time = 0.0, previous_step = 0.0, time_step = 0.0;
  std::uint64_t n_steps = 0;
  std::vector<double> velocity, displacement, internal_force, external_force, added_force; ///< per owned DoF
  /// Per material point of the locally owned cells, in the cells' order: the committed stress
  /// and plastic strain (6 components each, sigma_zz included), the trial ones (6 + 6), then the
  /// committed and the trial return regions: 26 numbers a point.
  std::vector<double> material_points;
  ExplicitEnergyLedger ledger;
  bool has_sheet = false;
  EmbeddedSheetState sheet;
};

class ExplicitSolver
{
public:
  using Vector = dealii::LinearAlgebra::distributed::Vector<double>;

  /// The mesh must outlive the solver and have no hanging nodes. Throws std::invalid_argument for
  /// bad settings, boundary conditions naming a boundary id the mesh lacks, or a time step above
  /// the stable one (the message names 'time step' and the stable value).
  ExplicitSolver(const dealii::parallel::distributed::Triangulation<dim> &mesh, const SoilModel &soil,
                 const BoundaryConditions &boundary_conditions, const ExplicitSettings &settings);

  /// Sets the stress at every quadrature point (see set_material_point_stress). Collective.
  void set_initial_stress(const std::function<StressTensor(const dealii::Point<dim> &)> &stress,
                          const std::string &description);
  void set_initial_stress(const GeostaticStress &geostatic);
  /// Sets the displacement u(x) (2 components [m]) at the nodes, at time(), before the first
  /// step; the material points take the stress of the strain it makes (from their current
  /// stress) and the internal force follows. Collective.
  void set_initial_displacement(const dealii::Function<dim> &displacement);
  /// Sets the velocity v(x) (2 components [m/s]) at the nodes, at time(). Collective.
  void set_initial_velocity(const dealii::Function<dim> &velocity);

  /// Lays a truss sheet in the soil, tied by its interface (sheet_interface.h), with `clamps`
  /// holding nodes at prescribed displacements. Throws std::invalid_argument naming 'mass scaling'
  /// and the factor needed if the sheet's nodes would be unstable at time_step(), or if a node
  /// lies outside the mesh. Collective.
  void attach_sheet(const TrussSheet &sheet, std::vector<SheetClamp> clamps);
  const EmbeddedSheet *sheet() const { return sheet_.get(); } ///< nullptr without a sheet
  EmbeddedSheet *sheet() { return sheet_.get(); }             ///< nullptr without a sheet

  /// Bridging-domain energy weight of the continuum (Xiao & Belytschko 2004; coupling/): the
  /// continuum carries the share w(x) in [0, 1] of the energy where it overlaps a particle region,
  /// so w multiplies the internal force's integrand, the lumped mass and the body force at every
  /// quadrature point. Applied here once (to the cached JxW and to the mass): the step costs the
  /// same as without. The stable step is recomputed with the weights; an automatic step follows
  /// it, a step the user chose is refused if now unstable. Throws std::invalid_argument if w is
  /// outside [0, 1] at a quadrature point, or if a node is left without mass (a cell where w = 0
  /// everywhere: the mesh must not reach past the band into the particles' own region).
  /// Collective; call before the first step, once.
  void set_energy_weight(const std::function<double(const dealii::Point<dim> &)> &weight);

  /// Degrees of freedom (local indices of owned DoFs) that the damping leaves alone: those whose
  /// velocity a coupling's constraint ties to particles (the bridging domain's multipliers are
  /// solved for the undamped update; the nodes are damped through the particles and the rest of
  /// the mesh). An empty list damps every DoF again. Throws std::invalid_argument for an index
  /// that is not a locally owned DoF.
  void set_undamped_dofs(const std::vector<unsigned int> &local_dofs);

  /// The state between two steps (ExplicitSolverState). Collective.
  ExplicitSolverState export_state() const;
  /// Takes `state`, exported by a solver built from the same input (mesh, soil, conditions,
  /// settings, weights, sheet): its next step is the one the exporter would have taken. Throws
  /// std::invalid_argument if the sizes do not fit this solver or its sheet. Collective.
  void restore_state(const ExplicitSolverState &state);

  /// One step of time_step(). Collective.
  void step();
  /// Steps of at most time_step() until time() == end_time (the last ones evenly shortened).
  /// Returns the number of steps taken. Collective.
  unsigned int advance_to(double end_time);

  double time() const { return time_; }
  unsigned int n_steps() const { return n_steps_; }
  double time_step() const { return time_step_; }
  /// Sets the step of the following steps (a coupled run's common step). Throws
  /// std::invalid_argument naming 'time step' if it is not positive or above stable_time_step().
  void set_time_step(double dt);
  const ExplicitSettings &settings() const { return settings_; }
  const SoilModel &soil() const { return soil_; }
  double critical_time_step() const { return critical_time_step_; } ///< 2 / max element omega [s]
  double stable_time_step() const { return settings_.safety_factor * critical_time_step_; }

  const DisplacementSpace &space() const { return space_; }
  const Vector &displacement() const { return displacement_; } ///< u at time(), with ghosts [m]
  const Vector &velocity() const { return velocity_; }         ///< v at time() - dt/2, owned [m/s]
  const Vector &lumped_mass() const { return mass_; }          ///< per DoF [kg/m]
  MaterialPointHistory &material_points() { return material_points_; }
  const MaterialPointHistory &material_points() const { return material_points_; }
  const Vector &internal_force() const { return internal_force_; } ///< f_int(u_n), owned [N/m]
  const Vector &external_force() const { return external_force_; } ///< f_ext(t_n), owned [N/m]
  /// Whether owned DoF `local_dof` (local index) has a prescribed displacement.
  bool is_constrained(unsigned int local_dof) const { return constrained_[local_dof]; }
  /// Adds `force` [N/m] to the external force at time() on owned DoF `local_dof` (local index):
  /// the next step applies it with the loads (a coupling's force on the continuum). The external
  /// force is rebuilt at every step, so it acts for one step only.
  void add_external_force(unsigned int local_dof, double force)
  {
    external_force_.local_element(local_dof) += force;
    added_force_.local_element(local_dof) += force;
  }

  /// Kinetic energy 1/2 v.M v of the half-step velocity [J/m]. Collective.
  double kinetic_energy() const;
  /// The energy ledger since the first step (ExplicitEnergyLedger). Collective.
  ExplicitEnergyLedger energy_ledger() const;
  /// |f_ext - f_int| over |f_int| + |f_ext| on the free DoFs at the last step (PFC's unbalanced
  /// force ratio, in the l2 norm): zero at static equilibrium [-]. Collective.
  double out_of_balance_ratio() const;
  /// f_int - f_ext summed over the DoFs of `boundary_id` at the last step: the force the supports
  /// and loads there exert on the soil, inertia of those nodes neglected [N/m]. Collective.
  dealii::Tensor<1, dim> boundary_reaction(dealii::types::boundary_id boundary_id) const;

  /// VTU piece per rank plus a PVTU record, for ParaView; returns the PVTU file name. Collective.
  std::string write_vtu(const std::string &directory, const std::string &basename, unsigned int step);

private:
  /// What a step needs of the locally owned cells, computed once (the mesh does not move in small
  /// strain): per quadrature point JxW and the gradients of the scalar shape functions, each
  /// cell's DoFs as local indices of the ghosted vectors, and its material points. All cells in
  /// one array each, cell after cell (not a few small arrays per cell): the step reads them in
  /// order, with no pointer to follow per cell.
  struct CellCache
  {
    unsigned int n_dofs = 0, n_points = 0, n_scalar = 0; ///< per cell
    std::vector<unsigned int> local_dofs;          ///< [cell * n_dofs + i]
    std::vector<MaterialPoint *> points;           ///< [cell * n_points + q]
    std::vector<double> JxW;                       ///< [cell * n_points + q]
    std::vector<dealii::Tensor<1, dim>> gradients; ///< [(cell * n_points + q) * n_scalar + j]
    unsigned int n_cells() const { return n_dofs == 0 ? 0 : local_dofs.size() / n_dofs; }
  };
  /// What the steps need from the mesh, the soil and the energy weights: the lumped mass and body
  /// force, the cell cache, the stable step (refusing a user step above it, naming `where` and
  /// `what_mesh`), and the forces at the current state. From the constructor and set_energy_weight.
  void prepare_steps(const std::string &where, const std::string &what_mesh);
  void build_cell_cache();
  /// w at the quadrature points of `fe_values` (1 without energy weights).
  double energy_weight_at(const dealii::FEValues<dim> &fe_values, unsigned int q) const;
  double compute_critical_time_step() const;
  void assemble_mass_and_body_force();
  /// f_int from the displacement increment du (ghosted), updating and committing the points.
  void assemble_internal_force(const Vector &displacement_increment);
  /// That for cell `cell` of cells_, with n_scalar scalar shape functions (4 for Q1, 9 for Q2:
  /// a constant, so that the compiler keeps the cell's arrays in registers).
  template <unsigned int n_scalar>
  void add_cell_internal_force(unsigned int cell, const Vector &displacement_increment);
  void assemble_external_force(double time);
  /// The prescribed displacements at `time`, on the locally owned constrained DoFs.
  std::map<dealii::types::global_dof_index, double> prescribed_displacements(double time) const;
  void take_step(double dt);

  SoilModel soil_;
  BoundaryConditions boundary_conditions_;
  ExplicitSettings settings_;
  DisplacementSpace space_;
  MaterialPointHistory material_points_;
  std::vector<bool> constrained_;      ///< per locally owned DoF (local index): displacement prescribed
  std::map<dealii::types::global_dof_index, double> prescribed_; ///< the prescribed displacements of the last step
  bool fixed_supports_ = false;        ///< no displacement function: prescribed_ is the same at every step
  std::vector<unsigned int> x_component_; ///< per locally owned DoF: 1 for x, 0 for y
  std::vector<bool> undamped_;         ///< per locally owned DoF (set_undamped_dofs); empty: all damped
  double critical_time_step_ = 0.0;
  double time_step_ = 0.0;

  Vector mass_;               ///< lumped mass, owned
  Vector body_force_;         ///< rho g, owned
  Vector external_force_;     ///< f_ext at the last step, owned
  Vector internal_force_;     ///< f_int at the last step, owned
  Vector added_force_;        ///< the part of external_force_ added through add_external_force, owned
  /// This rank's share of the ledger's accumulated terms (energy_ledger() sums the ranks).
  ExplicitEnergyLedger ledger_;
  Vector velocity_;           ///< v_{n-1/2}, owned
  Vector displacement_;       ///< u_n, ghosted
  Vector increment_;          ///< u_{n+1} - u_n, ghosted
  double time_ = 0.0;
  double previous_step_ = 0.0; ///< dt_{n-1/2}, 0 before the first step
  unsigned int n_steps_ = 0;
  std::unique_ptr<EmbeddedSheet> sheet_;
  CellCache cells_;
  /// cells_ by colour: no two cells of a colour share a DoF (build_cell_cache, greedy in cell order).
  std::vector<std::vector<unsigned int>> colours_;
  std::vector<unsigned int> dof_component_, dof_scalar_; ///< of each cell DoF: its component and scalar shape
  std::function<double(const dealii::Point<dim> &)> energy_weight_; ///< empty without coupling
};
} // namespace geohybrid::fem
