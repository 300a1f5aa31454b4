#include "coupled_stepper.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace geohybrid::coupling
{
namespace
{
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Checks what the stepper needs of both sides before it touches them.
void check_sides(const fem::ExplicitSolver &continuum)
{
  const std::string where = "coupled stepper: ";
  // The particles may have run before (a packing made, a strain applied): between two steps their
  // velocities are full-step ones, which the forces at t = 0 of the coupling expect. The
  // continuum's are half-step ones after a step.
  if (continuum.n_steps() > 0)
    throw std::invalid_argument(where + "set the coupling up before the continuum takes a step");
}

const OverlapBand &checked(const fem::ExplicitSolver &continuum, const OverlapBand &band, const CouplingMethod &method)
{
  check_sides(continuum);
  if (!has_band(method))
    throw std::invalid_argument("coupled stepper: the interface coupling (method 3) has no overlap band: "
                                "construct the stepper without one");
  return band;
}

const InterfaceCoupling &checked(const fem::ExplicitSolver &continuum, const InterfaceCoupling &method)
{
  check_sides(continuum);
  return method;
}

/// The weights go on before the band's particles are gathered: the multipliers' matrix needs the
/// weighted masses.
BandParticles weighted_band(dem::DemSystem &particles, fem::ExplicitSolver &continuum, const OverlapBand &band,
                            const BandTreatment &treatment, dem::CouplingAttachment &attachment)
{
  const double driven_below_weight = treatment.driven_below_weight;
  // The particles past the band (and the band's lightest, on request) are moved by the
  // continuum: fixed bodies (no mass, no weight).
  const double driven_from = band.driven_from(driven_below_weight);
  dem::ParticleSet &movable = particles.particles();
  for (std::size_t b = 0; b < movable.n_bodies(); ++b)
    if (band.coordinate(Vec2(movable.x[b], movable.y[b])) >= driven_from)
      movable.fix_body(b);
  attachment.set_energy_weights(movable, band.energy_weights(movable));
  // Before the band's particles are gathered: the multipliers' matrix takes the inertial masses.
  if (treatment.scale_inertia)
    attachment.scale_band_inertia(movable);
  continuum.set_energy_weight(
    [band](const dealii::Point<fem::dim> &x) { return band.continuum_weight(Vec2(x[0], x[1])); });
  // The longest branch: twice the largest distance from a body's centre to its discs' far edge.
  const dem::ParticleSet &p = particles.particles();
  double extent = 0.0;
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    extent = std::max(extent, std::hypot(p.disc_offset_x[d], p.disc_offset_y[d]) + p.disc_radius[d]);
  return BandParticles(band, p, continuum.space(), continuum.displacement(), 2.0 * extent, driven_below_weight);
}

/// The tie of a band's method (checked() has refused method 3).
CouplingTie band_tie(const CouplingMethod &method, const BandParticles &band, const dem::DemSystem &particles,
                     const fem::ExplicitSolver &continuum, const OverlapBand &geometry)
{
  return std::visit(
    [&](const auto &parameters) -> CouplingTie {
      using Method = std::decay_t<decltype(parameters)>;
      if constexpr (std::is_same_v<Method, PenaltyCoupling>)
        return PenaltyTie(parameters, band, particles.particles(), continuum, geometry.width());
      else if constexpr (std::is_same_v<Method, LagrangeMultiplierCoupling>)
        return LagrangeTie(band, particles.particles(), continuum);
      else
        {
          static_assert(!Method::has_band, "a band's method without its tie here");
          throw std::logic_error("coupled stepper: method '" + std::string(Method::name) + "' has no band");
        }
    },
    method);
}
} // namespace

CoupledStepper::CoupledStepper(dem::DemSystem &particles, fem::ExplicitSolver &continuum, const OverlapBand &band,
                               const CouplingMethod &method, const BandTreatment &treatment, const MultiRate &rate)
  : particles_(particles)
  , continuum_(continuum)
  , band_geometry_(checked(continuum, band, method))
  , band_(weighted_band(particles, continuum, band, treatment, attachment_))
  , tie_(band_tie(method, *band_, particles, continuum, band))
{
  // The multipliers set the tied particles' translation (CouplingAttachment::set_constrained_bodies):
  // it and the nodes they interpolate from are left out of the local and mass-proportional
  // damping (the multipliers are solved for the undamped kicks; both are damped through the rest
  // of the models, which they move with). The penalty springs are forces like any other:
  // damping stays everywhere.
  if (std::holds_alternative<LagrangeTie>(tie_))
    {
      attachment_.set_constrained_bodies(particles.particles(), band_->body);
      std::vector<unsigned int> tied_dofs;
      const BandPoints &points = band_->points;
      for (std::size_t p = 0; p < band_->size(); ++p)
        for (unsigned int k = 0; k < points.nodes_per_point(); ++k)
          if (points.shape_value(p, k) != 0.0)
            {
              tied_dofs.push_back(points.x_dof(p, k));
              tied_dofs.push_back(points.y_dof(p, k));
            }
      continuum.set_undamped_dofs(tied_dofs);
    }
  for (std::size_t q = 0; q < band_->driven_body.size(); ++q)
    driven_tied_displacement_.push_back(band_->driven_points.interpolate(continuum.displacement(), q));
  if (rate.continuum_step_ratio != 1 && !std::holds_alternative<LagrangeTie>(tie_))
    throw std::invalid_argument("coupled stepper: 'continuum step ratio' = " + std::to_string(rate.continuum_step_ratio) +
                                ": multi-rate stepping needs the multipliers (coupling method '" +
                                std::string(LagrangeTie::name) + "'); give 1 for the others");
  start(rate.continuum_step_ratio);
}

CoupledStepper::CoupledStepper(dem::DemSystem &particles, fem::ExplicitSolver &continuum, const InterfaceCoupling &method)
  : particles_(particles)
  , continuum_(continuum)
  , tie_(std::in_place_type<InterfaceWall>, checked(continuum, method), particles.particles(), continuum,
         particles.skin())
{
  start();
}

void CoupledStepper::start(unsigned int requested_ratio)
{
  // From here on the particles read the attachment (their weighted step first): detached again if
  // the stepper is not made.
  particles_.attach(attachment_);
  try
    {
      double particle_step = 0.0;
      if (requested_ratio != 1)
        {
          const double limit = particle_stable_step();
          particle_step = choose_ratio(requested_ratio);
          // The tied particles move with the continuum through a window (at its half-step
          // velocity; their contacts' forces reach them at the window's start): an explicit step
          // of the window's length for them, stable once their inertia is (window / limit)^2
          // times higher, if the window is longer than the particles' stable step (a density
          // scaling of the band, as scale_band_inertia's: its statics unchanged).
          tied_inertia_factor_ = std::max(1.0, std::pow(ratio_ * particle_step / limit, 2));
          if (ratio_ > 1 && tied_inertia_factor_ > 1.0)
            {
              particles_.detach();
              attachment_.scale_inertia(particles_.particles(), band_->body, tied_inertia_factor_);
              tie_.emplace<LagrangeTie>(*band_, particles_.particles(), continuum_); // the new masses
              particles_.attach(attachment_);
            }
        }
      start_attached(particle_step);
    }
  catch (...)
    {
      particles_.detach();
      throw;
    }
}

double CoupledStepper::particle_stable_step() const
{
  // No margin for the band's scaled inertia (start_attached's 0.8): multi-rate raises every tied
  // particle's inertia, its rotation's too, by (ratio step / this)^2, so a ratio of 2 or more
  // either raises it at least 4 x (what removed the geostatic column's divergence) or keeps the
  // step at half of this or less. The band's scaled particles are all tied (0 < w < 1).
  const dem::DemSystem &particles = particles_;
  return particles.settings().time_step_safety * particles.critical_time_step();
}

double CoupledStepper::choose_ratio(unsigned int requested_ratio)
{
  // The particles at their own stable step (the multipliers add no stiffness and only join
  // masses), the continuum at ratio of them, within its own.
  const double step = std::min(particle_stable_step(), particles_.time_step());
  const double stable = continuum_.stable_time_step();
  const auto most = static_cast<unsigned int>(std::max(1.0, std::floor(stable / step * (1.0 + 1e-12))));
  ratio_ = requested_ratio == 0 ? std::min(most, MultiRate::largest_automatic_ratio) : requested_ratio;
  if (ratio_ * step > stable * (1.0 + 1e-12))
    {
      std::ostringstream message;
      message << "coupled stepper: 'continuum step ratio' = " << ratio_ << " gives the continuum a step of "
              << ratio_ * step << " s, above its stable step " << stable << " s; at most " << most
              << " with the particles' step " << step << " s (0 chooses it)";
      ratio_ = 1;
      throw std::invalid_argument(message.str());
    }
  return step;
}

void CoupledStepper::start_attached(double multi_rate_step)
{
  dem::DemSystem &particles = particles_;
  fem::ExplicitSolver &continuum = continuum_;
  if (ratio_ > 1)
    {
      time_step_ = multi_rate_step;
      particles.set_time_step(time_step_);
      continuum.set_time_step(ratio_ * time_step_);
      attachment_.set_force_hook([this](dem::ParticleSet &p, double impulse_time) { apply_coupling(p, impulse_time); });
      phase_ = 0;
      hook_starts_window_ = true;
      if (particles.forces_initialised())
        apply_coupling(particles.particles(), 0.5 * time_step_);
      else
        particles.initialise_forces();
      return;
    }
  // One step for both: the smaller stable step, lowered by the penalty or interface springs (Weyl:
  // the squared frequencies of the uncoupled sides and of the springs add at most).
  const double particles_omega = 2.0 / particles.critical_time_step();
  const double continuum_omega = 2.0 / continuum.critical_time_step();
  const double springs =
    std::visit([&](const auto &tie) { return tie.squared_frequency_bound(particles.particles(), continuum); }, tie_);
  const double omega = std::sqrt(std::pow(std::max(particles_omega, continuum_omega), 2) + springs);
  const double safety = std::min(particles.settings().time_step_safety, continuum.settings().safety_factor);
  time_step_ = std::min({safety * 2.0 / omega, particles.time_step(), continuum.time_step()});
  // With the band's inertia scaled the estimates above are not bounds any more: the geostatic
  // column (tests/test_coupling_column.cc) diverged at the step they give and settled at 0.95 of
  // it; scaling the band's rotational inertia 4 x more removed the divergence, so a rotational
  // mode of the tied discs, whose translation the multipliers hold, is underestimated. Not
  // derived: a measured margin, 0.8 (1.19 below the divergence).
  if (attachment_.band_inertia_scaled())
    time_step_ *= scaled_band_step_fraction;
  particles.set_time_step(time_step_);
  continuum.set_time_step(time_step_);
  attachment_.set_force_hook([this](dem::ParticleSet &p, double impulse_time) { apply_coupling(p, impulse_time); });
  // The forces at t = 0, the coupling's included. The weights of methods 1 and 2 made the
  // particles' forces stale; without weights (method 3) particles evaluated before keep theirs,
  // and the coupling's are added here as the hook would (no drift yet: impulse time dt / 2).
  if (particles.forces_initialised())
    apply_coupling(particles.particles(), 0.5 * time_step_);
  else
    particles.initialise_forces();
}

const BandParticles &CoupledStepper::band_particles() const
{
  if (!band_)
    throw std::logic_error("coupled stepper: the interface coupling (method 3) has no band particles");
  return *band_;
}

void CoupledStepper::cross_sheet(std::size_t dem_sheet_index, double rest_length)
{
  if (crossing_)
    throw std::logic_error("coupled stepper: the sheet already crosses into the continuum");
  if (ratio_ > 1)
    throw std::invalid_argument("coupled stepper: the sheet cannot cross into the continuum with multi-rate "
                                "stepping ('continuum step ratio' = " + std::to_string(ratio_) + "): give 1");
  fem::EmbeddedSheet *continuum_sheet = continuum_.sheet();
  if (!continuum_sheet)
    throw std::invalid_argument("coupled stepper: the continuum has no sheet to join the particles' sheet to "
                                "(ExplicitSolver::attach_sheet)");
  dem::SparSheet &dem_sheet = particles_.sheets().at(dem_sheet_index);
  crossing_.emplace(dem_sheet, dem_sheet_index, *continuum_sheet, rest_length);
  // The forces at the current time: the particles' are evaluated (start()), so the segment's
  // force joins them directly; the continuum's sheet takes its share in its next step.
  crossing_->apply(dem_sheet, *continuum_sheet);
  attachment_.set_sheet_force_hook([this](std::vector<dem::SparSheet> &sheets) {
    const Clock::time_point start = Clock::now();
    crossing_->apply(sheets[crossing_->dem_sheet_index()], *continuum_.sheet());
    times_.coupling += seconds_since(start);
  });
}

CoupledStepper::~CoupledStepper()
{
  particles_.detach();
  continuum_.set_undamped_dofs({});
}

void CoupledStepper::pass_driven_forces(const dem::ParticleSet &particles)
{
  const unsigned int n_nodes = band_->driven_points.nodes_per_point();
  for (std::size_t q = 0; q < band_->driven_body.size(); ++q)
    {
      const std::uint32_t b = band_->driven_body[q];
      for (unsigned int k = 0; k < n_nodes; ++k)
        {
          const double N = band_->driven_points.shape_value(q, k);
          continuum_.add_external_force(band_->driven_points.x_dof(q, k), N * particles.fx[b]);
          continuum_.add_external_force(band_->driven_points.y_dof(q, k), N * particles.fy[b]);
        }
    }
}

void CoupledStepper::apply_coupling(dem::ParticleSet &particles, double impulse_time)
{
  const Clock::time_point start = Clock::now();
  forces_ = CouplingForceSums{};
  if (ratio_ > 1)
    {
      // The driven particles' forces now, as the continuum's own, at the window's start only.
      if (band_ && hook_starts_window_)
        pass_driven_forces(particles);
      LagrangeTie &tie = std::get<LagrangeTie>(tie_);
      if (hook_starts_window_)
        tie.apply_window_start(particles, continuum_, impulse_time, ratio_ * impulse_time, time_step_, ratio_, forces_);
      else
        tie.apply_within_window(particles, continuum_, time_step_, forces_);
      times_.coupling += seconds_since(start);
      return;
    }
  // The driven particles' contact forces go to the continuum's nodes first: the multipliers'
  // predictors must see every force the continuum will feel.
  if (band_)
    pass_driven_forces(particles);
  // The first evaluation (impulse time dt / 2) follows no drift.
  const TieTiming timing{impulse_time, impulse_time < time_step_ ? 0.0 : time_step_};
  std::visit([&](auto &tie) { tie.apply(particles, continuum_, timing, forces_); }, tie_);
  times_.coupling += seconds_since(start);
}

void CoupledStepper::step_in_window()
{
  Clock::time_point start = Clock::now();
  if (phase_ == 0)
    continuum_.step(); // to the window's end
  times_.continuum += seconds_since(start);
  start = Clock::now();
  // The driven particles drift to the continuum's displacement at the particles' next time,
  // linear over the window: u(T_end) less the rest of the window at its half-step velocity.
  dem::ParticleSet &p = particles_.particles();
  const double dt = time_step_, before_end = (ratio_ - phase_ - 1) * dt;
  for (std::size_t q = 0; band_ && q < band_->driven_body.size(); ++q)
    {
      const std::uint32_t b = band_->driven_body[q];
      const Vec2 target = band_->driven_reference_position[q] +
                          band_->driven_points.interpolate(continuum_.displacement(), q) -
                          before_end * band_->driven_points.interpolate(continuum_.velocity(), q) -
                          driven_tied_displacement_[q];
      p.vx[b] = (target.x() - p.x[b]) / dt;
      p.vy[b] = (target.y() - p.y[b]) / dt;
    }
  times_.band_drive += seconds_since(start);
  start = Clock::now();
  hook_starts_window_ = phase_ + 1 == ratio_;
  const double coupling_before = times_.coupling;
  particles_.step();
  times_.particles += seconds_since(start) - (times_.coupling - coupling_before);
  phase_ = hook_starts_window_ ? 0 : phase_ + 1;
}

void CoupledStepper::restore_window_phase(unsigned int phase)
{
  if (phase >= ratio_)
    throw std::invalid_argument("coupled stepper: the saved window phase " + std::to_string(phase) +
                                " does not fit the continuum step ratio " + std::to_string(ratio_));
  phase_ = phase;
}

void CoupledStepper::step()
{
  if (ratio_ > 1)
    {
      step_in_window();
      return;
    }
  Clock::time_point start = Clock::now();
  continuum_.step();
  times_.continuum += seconds_since(start);
  start = Clock::now();
  // The driven particles drift (fixed bodies keep their velocity) to where the continuum now is.
  dem::ParticleSet &p = particles_.particles();
  const double dt = particles_.time_step();
  for (std::size_t q = 0; band_ && q < band_->driven_body.size(); ++q)
    {
      const std::uint32_t b = band_->driven_body[q];
      const Vec2 target = band_->driven_reference_position[q] +
                          band_->driven_points.interpolate(continuum_.displacement(), q) - driven_tied_displacement_[q];
      p.vx[b] = (target.x() - p.x[b]) / dt;
      p.vy[b] = (target.y() - p.y[b]) / dt;
    }
  times_.band_drive += seconds_since(start);
  start = Clock::now();
  const double coupling_before = times_.coupling; // the hook's time is the coupling's
  particles_.step();
  times_.particles += seconds_since(start) - (times_.coupling - coupling_before);
}

void CoupledStepper::run_steps(unsigned int n)
{
  for (unsigned int k = 0; k < n; ++k)
    step();
}

double CoupledStepper::largest_velocity_gap() const
{
  const auto *tie = std::get_if<LagrangeTie>(&tie_);
  return tie ? tie->largest_velocity_gap() : 0.0;
}

CouplingDiagnostics CoupledStepper::diagnostics() const
{
  CouplingDiagnostics d;
  const dem::EnergyBudget budget = particles_.energy();
  d.particle_energy = budget.total();
  d.particle_kinetic = budget.kinetic;
  // The continuum's velocity at t_n: its half-step velocity plus half a step of its forces at t_n
  // (the coupling's included), as the DEM's full-step velocity (before its first step: v_0 itself).
  const auto &v = continuum_.velocity(), &u = continuum_.displacement(), &M = continuum_.lumped_mass();
  const auto &f_ext = continuum_.external_force(), &f_int = continuum_.internal_force();
  const double half = continuum_.n_steps() > 0 ? 0.5 * continuum_.time_step() : 0.0;
  for (unsigned int i = 0; i < v.locally_owned_size(); ++i)
    {
      const double force = continuum_.is_constrained(i) ? 0.0 : f_ext.local_element(i) - f_int.local_element(i);
      const double v_now = v.local_element(i) + half * force / M.local_element(i);
      d.continuum_kinetic += 0.5 * M.local_element(i) * v_now * v_now;
      d.continuum_elastic += 0.5 * u.local_element(i) * f_int.local_element(i);
    }
  d.coupling_energy = std::visit([](const auto &tie) { return tie.energy(); }, tie_) +
                      (crossing_ ? crossing_->energy() : 0.0);
  d.forces = forces_;
  d.particle_budget = budget;
  d.continuum_ledger = continuum_.energy_ledger();
  if (const fem::EmbeddedSheet *sheet = continuum_.sheet())
    d.continuum_sheet_ledger = sheet->energy_ledger();
  return d;
}

namespace
{
double dissipated(const dem::EnergyBudget &e)
{
  return e.friction_dissipated + e.viscous_dissipated + e.local_damping_dissipated + e.interface_friction_dissipated;
}
} // namespace

double energy_balance_error(const CouplingDiagnostics &start, const CouplingDiagnostics &now)
{
  const dem::EnergyBudget &a = start.particle_budget, &b = now.particle_budget;
  const fem::ExplicitEnergyLedger &c0 = start.continuum_ledger, &c = now.continuum_ledger;
  const double scale = std::max({std::abs(b.gravitational - a.gravitational), std::abs(b.elastic - a.elastic),
                                 std::abs(b.kinetic - a.kinetic), std::abs(b.sheet_elastic - a.sheet_elastic),
                                 std::abs(dissipated(b) - dissipated(a)), std::abs(b.boundary_work - a.boundary_work),
                                 std::abs(c.internal_work - c0.internal_work), std::abs(c.gravity_work - c0.gravity_work),
                                 std::abs(c.load_work - c0.load_work), std::abs(c.damping_work - c0.damping_work),
                                 std::abs(c.added_force_work - c0.added_force_work),
                                 std::abs(now.continuum_sheet_ledger.truss_work - start.continuum_sheet_ledger.truss_work),
                                 std::abs(now.continuum_sheet_ledger.interface_work - start.continuum_sheet_ledger.interface_work),
                                 std::abs(now.continuum_sheet_ledger.load_work - start.continuum_sheet_ledger.load_work)});
  const double change = now.ledger_total() - start.ledger_total();
  return scale > 0.0 ? change / scale : change;
}
} // namespace geohybrid::coupling
