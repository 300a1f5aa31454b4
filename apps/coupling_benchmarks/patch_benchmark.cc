// The patch test and the undamped energy run (coupling_benchmarks.h).
#include "coupling_benchmarks.h"

#include "apps/coupling_benchmarks/hexagonal_lattice.h"

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace geohybrid::coupling::benchmarks
{
namespace
{
/// u(x) = eps x.
class UniformStrain : public dealii::Function<2>
{
public:
  explicit UniformStrain(const PlaneStrain &eps) : dealii::Function<2>(2), eps_(eps) {}
  double value(const dealii::Point<2> &x, unsigned int c) const override
  {
    return c == 0 ? eps_.xx * x[0] + eps_.xy * x[1] : eps_.xy * x[0] + eps_.yy * x[1];
  }

private:
  PlaneStrain eps_;
};
} // namespace

std::unique_ptr<dem::DemSystem> strained_lattice(dem::ParticleSet discs, const PatchGeometry &g, const PlaneStrain &eps)
{
  for (std::size_t b = 0; b < discs.n_bodies(); ++b)
    discs.fix_body(b);
  auto system = std::make_unique<dem::DemSystem>(std::move(discs), bonded_lattice_law(g.kn, g.ks), undamped_settings(2e-7));
  system->initialise_forces();
  system->bond_touching_contacts();
  const unsigned int n_steps = 20;
  const double duration = n_steps * system->time_step();
  dem::ParticleSet &p = system->particles();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      p.vx[b] = (eps.xx * p.x[b] + eps.xy * p.y[b]) / duration;
      p.vy[b] = (eps.xy * p.x[b] + eps.yy * p.y[b]) / duration;
    }
  system->run_steps(n_steps);
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      p.inverse_mass[b] = 1.0 / p.mass[b];
      p.inverse_inertia[b] = 1.0 / p.inertia[b];
      p.vx[b] = p.vy[b] = p.omega[b] = 0.0;
    }
  return system;
}

void strain_continuum(fem::ExplicitSolver &continuum, const PatchGeometry &g, const PlaneStrain &eps)
{
  const double prestress = -std::sqrt(3.0) * g.kn * (2.0 * g.radius - g.spacing()) / g.spacing();
  const double nu = continuum.soil().elasticity().poisson_ratio();
  continuum.set_initial_stress(
    [&](const dealii::Point<2> &) {
      fem::StressTensor s;
      s[0][0] = s[1][1] = prestress;
      s[2][2] = 2.0 * nu * prestress;
      return s;
    },
    "the lattice's prestress");
  continuum.set_initial_displacement(UniformStrain(eps));
}

double stress_norm(const PatchGeometry &g, const PlaneStrain &eps)
{
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(g.kn, g.ks);
  const double tr = eps.xx + eps.yy;
  const double sxx = m.lame_lambda * tr + 2 * m.shear_modulus * eps.xx,
               syy = m.lame_lambda * tr + 2 * m.shear_modulus * eps.yy, sxy = 2 * m.shear_modulus * eps.xy;
  return std::sqrt(sxx * sxx + syy * syy + 2 * sxy * sxy);
}

CoupledPatch strained_patch(const CouplingMethod &method, const PlaneStrain &eps, const PatchGeometry &geometry)
{
  return strained_patch(method, eps, geometry, patch_band(geometry));
}

CoupledPatch strained_patch(const CouplingMethod &method, const PlaneStrain &eps, const PatchGeometry &geometry,
                            const OverlapBand &band)
{
  CoupledPatch patch;
  patch.geometry = geometry;
  const PatchGeometry &g = patch.geometry;
  patch.particles = strained_lattice(patch_particles(g), g, eps);
  patch.mesh = patch_mesh(g);
  patch.continuum = std::make_unique<fem::ExplicitSolver>(*patch.mesh, matching_soil(g), fem::BoundaryConditions{},
                                                          patch_continuum_settings(g));
  strain_continuum(*patch.continuum, g, eps);
  patch.stepper = std::make_unique<CoupledStepper>(*patch.particles, *patch.continuum, band, method);
  return patch;
}

GhostForceMeasure measure_ghost_forces(const dem::ParticleSet &p, const fem::ExplicitSolver &continuum,
                                       const BandParticles &band, double stress, double disc_length,
                                       double node_length, const std::function<bool(std::size_t)> &interior_disc,
                                       const std::function<bool(const dealii::Point<2> &)> &interior_node)
{
  GhostForceMeasure measure;
  GhostForces &ghost = measure.ghost;
  std::vector<bool> tied(p.n_bodies(), false);
  for (const std::uint32_t b : band.body)
    tied[b] = true;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (interior_disc(b) && !tied[b] && p.inverse_mass[b] > 0.0) // driven particles: projected with the continuum's force
      {
        ghost.particles_outside_band =
          std::max(ghost.particles_outside_band, std::hypot(p.fx[b], p.fy[b]) / (stress * disc_length));
        ++measure.n_discs;
      }
  std::vector<double> residual(continuum.internal_force().locally_owned_size());
  for (unsigned int i = 0; i < residual.size(); ++i)
    residual[i] = continuum.external_force().local_element(i) - continuum.internal_force().local_element(i);
  for (std::size_t q = 0; q < band.size(); ++q)
    {
      const std::uint32_t b = band.body[q];
      if (interior_disc(b))
        ghost.band_particles = std::max(ghost.band_particles, std::hypot(p.fx[b], p.fy[b]) / (stress * disc_length));
      for (unsigned int k = 0; k < band.points.nodes_per_point(); ++k)
        {
          residual[band.points.x_dof(q, k)] += band.points.shape_value(q, k) * p.fx[b];
          residual[band.points.y_dof(q, k)] += band.points.shape_value(q, k) * p.fy[b];
        }
    }
  std::map<dealii::types::global_dof_index, dealii::Point<2>> support;
  dealii::DoFTools::map_dofs_to_support_points(continuum.space().mapping(), continuum.space().dof_handler(), support);
  for (const auto &[dof, x] : support)
    if (interior_node(x))
      {
        ghost.continuum_nodes = std::max(ghost.continuum_nodes, std::abs(residual[dof]) / (stress * node_length));
        ++measure.n_nodes;
      }
  return measure;
}

GhostForces ghost_forces(const CoupledPatch &patch, const PlaneStrain &eps)
{
  const PatchGeometry &g = patch.geometry;
  const double d = g.spacing(), h = g.row_height();
  const double cell_x = (g.continuum_end - g.band_start) * d / g.cells_x, cell_y = g.rows * h / g.cells_y;
  const double y_bottom = -0.5 * h, y_top = (g.rows - 0.5) * h;
  const dem::ParticleSet &p = patch.particles->particles();
  // Away from the lattice's free rows and its free left end (the band's discs are far from it).
  const auto interior_disc = [&](std::size_t b) {
    return !(p.y[b] < 0.5 * h || p.y[b] > (g.rows - 1.5) * h || p.x[b] < 1.2 * d);
  };
  const auto interior_node = [&](const dealii::Point<2> &x) {
    return !(x[1] < y_bottom + 1.5 * cell_y || x[1] > y_top - 1.5 * cell_y || x[0] > g.continuum_end * d - 0.5 * cell_x);
  };
  return measure_ghost_forces(p, *patch.continuum, patch.stepper->band_particles(), stress_norm(g, eps), d, cell_x,
                              interior_disc, interior_node)
    .ghost;
}

PatchTestResult patch_test(const CouplingMethod &method, const PlaneStrain &strain, const PatchGeometry &geometry)
{
  return patch_test(method, strain, geometry, patch_band(geometry));
}

PatchTestResult patch_test(const CouplingMethod &method, const PlaneStrain &strain, const PatchGeometry &geometry,
                           const OverlapBand &band)
{
  const CoupledPatch patch = strained_patch(method, strain, geometry, band);
  PatchTestResult result;
  result.ghost = ghost_forces(patch, strain);
  result.n_particles = patch.particles->particles().n_bodies();
  result.n_cells = patch.mesh->n_active_cells();
  return result;
}

void launch_energy_pulse(CoupledPatch &patch, double amplitude)
{
  const double d = patch.geometry.spacing();
  dem::ParticleSet &p = patch.particles->particles();
  std::vector<bool> tied(p.n_bodies(), false);
  for (const auto b : patch.stepper->band_particles().body)
    tied[b] = true;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    if (!tied[b] && p.inverse_mass[b] > 0.0)
      p.vx[b] = amplitude * std::exp(-std::pow((p.x[b] - 2.0 * d) / (2.0 * d), 2));
}

EnergyRecord undamped_energy_record(CoupledStepper &stepper, unsigned int n_steps)
{
  if (n_steps < 40)
    throw std::invalid_argument("energy run: " + std::to_string(n_steps) +
                                " steps leave a quarter of the run without a sample (one every 10 steps); run at least 40");
  if (10 % stepper.continuum_step_ratio() != 0)
    throw std::invalid_argument("energy run: its samples, every 10 steps, must fall between windows: a continuum "
                                "step ratio of 1, 2, 5 or 10");
  const double initial = stepper.diagnostics().total();
  EnergyRecord record;
  record.time_step = stepper.time_step();
  const auto sample = [&](const CouplingDiagnostics &d) {
    record.history.push_back({stepper.time(), (d.total() - initial) / initial, d.particle_energy, d.continuum_kinetic,
                              d.continuum_elastic, d.coupling_energy});
  };
  sample(stepper.diagnostics());
  double first = 0.0, last = 0.0;
  unsigned int n_first = 0, n_last = 0;
  for (unsigned int n = 1; n <= n_steps; ++n)
    {
      stepper.step();
      // The force sums every step (cheap: the stepper keeps them), the energies every 10 steps.
      // (In lockstep only: with multi-rate the continuum receives a window's impulses at its start.)
      const CouplingForceSums &forces = stepper.coupling_forces();
      if (stepper.continuum_step_ratio() == 1)
        record.largest_force_imbalance = std::max(record.largest_force_imbalance, (forces.on_particles + forces.on_continuum).norm());
      record.largest_coupling_force = std::max(record.largest_coupling_force, forces.on_particles.norm());
      if (n % 10 == 0)
        {
          const CouplingDiagnostics d = stepper.diagnostics();
          sample(d);
          const double relative = record.history.back().relative_change;
          record.largest_deviation = std::max(record.largest_deviation, std::abs(relative));
          record.continuum_share = std::max(record.continuum_share, (d.continuum_kinetic + d.continuum_elastic) / initial);
          if (4 * n <= n_steps)
            first += relative, ++n_first;
          if (4 * n > 3 * n_steps)
            last += relative, ++n_last;
        }
    }
  record.drift = last / n_last - first / n_first;
  return record;
}

EnergyRecord energy_record(const CouplingMethod &method, unsigned int n_steps, double time_step,
                           const PatchGeometry &geometry, const MultiRate &rate)
{
  CoupledPatch patch = coupled_patch_at_rest(method, geometry, undamped_settings(time_step), {}, rate);
  launch_energy_pulse(patch, 1e-3);
  return undamped_energy_record(*patch.stepper, n_steps);
}
} // namespace geohybrid::coupling::benchmarks
