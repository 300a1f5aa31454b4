// The coupled stepper (issue 6): the patch test of the bridging domain method with Lagrange
// multipliers and of the penalty overlap, the coupling's force balance, the constraint held.
#include "test_coupling_patch.h"

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
/// u(x) = eps x.
class UniformStrain : public dealii::Function<2>
{
public:
  explicit UniformStrain(const double (&eps)[2][2]) : dealii::Function<2>(2)
  {
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        eps_[a][b] = eps[a][b];
  }
  double value(const dealii::Point<2> &x, unsigned int c) const override { return eps_[c][0] * x[0] + eps_[c][1] * x[1]; }

private:
  double eps_[2][2];
};

/// The patch strained uniformly by eps on both sides and coupled by `method`: the discs moved
/// affinely (held, at constant velocity over 20 steps, so that their bonded contacts' tangential
/// springs load), then released at rest; the continuum given u = eps x and the lattice's prestress
/// -sqrt(3) kn delta0 / d (isotropic), then the coupled forces at t = 0 evaluated.
CoupledPatch strained_patch(const CouplingMethod &method, const double (&eps)[2][2], const PatchGeometry &geometry = {})
{
  CoupledPatch patch;
  patch.geometry = geometry;
  const PatchGeometry &g = patch.geometry;
  dem::ParticleSet discs = patch_particles(g);
  for (std::size_t b = 0; b < discs.n_bodies(); ++b)
    discs.fix_body(b);
  patch.particles = std::make_unique<dem::DemSystem>(std::move(discs), bonded_lattice_law(g.kn, g.ks),
                                                     undamped_settings(2e-7));
  dem::DemSystem &system = *patch.particles;
  system.initialise_forces();
  system.bond_touching_contacts();
  const unsigned int n_steps = 20;
  const double duration = n_steps * system.time_step();
  dem::ParticleSet &p = system.particles();
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      p.vx[b] = (eps[0][0] * p.x[b] + eps[0][1] * p.y[b]) / duration;
      p.vy[b] = (eps[1][0] * p.x[b] + eps[1][1] * p.y[b]) / duration;
    }
  system.run_steps(n_steps);
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      p.inverse_mass[b] = 1.0 / p.mass[b];
      p.inverse_inertia[b] = 1.0 / p.inertia[b];
      p.vx[b] = p.vy[b] = p.omega[b] = 0.0;
    }

  patch.mesh = patch_mesh(g);
  const fem::SoilModel soil = matching_soil(g);
  patch.continuum = std::make_unique<fem::ExplicitSolver>(*patch.mesh, soil, fem::BoundaryConditions{},
                                                          patch_continuum_settings(g));
  const double prestress = -std::sqrt(3.0) * g.kn * (2.0 * g.radius - g.spacing()) / g.spacing();
  const double nu = soil.elasticity().poisson_ratio();
  patch.continuum->set_initial_stress(
    [&](const dealii::Point<2> &) {
      fem::StressTensor s;
      s[0][0] = s[1][1] = prestress;
      s[2][2] = 2.0 * nu * prestress;
      return s;
    },
    "the lattice's prestress");
  patch.continuum->set_initial_displacement(UniformStrain(eps));

  const double d = g.spacing();
  const OverlapBand band(Vec2(g.band_start * d, 0.0), Vec2(1.0, 0.0), g.band_width * d);
  patch.stepper = std::make_unique<CoupledStepper>(system, *patch.continuum, band, method);
  return patch;
}

struct GhostForces
{
  double particles_outside_band = 0.0; ///< largest |F| on an interior disc of the particle-only region
  double continuum_nodes = 0.0;        ///< largest |r_I| at an interior node, particles' forces projected
  double band_particles = 0.0;         ///< largest |F| a band disc's own tie must carry
};

/// The largest residual forces of the strained patch, relative to |sigma| times the length each
/// carries (the spacing d for a disc, the cell size for a node). The residual of the constrained
/// system at node I is r_I = f_ext,I - f_int,I + sum_p N_I(X_p) F_p: the forces on the band's
/// discs reach the continuum through the constraint (the multipliers cancel in it), and it is the
/// same for both methods. Discs and nodes whose neighbourhood reaches the patch's free surfaces
/// (where the uniform stress has no traction to balance it) are left out.
GhostForces ghost_forces(const CoupledPatch &patch, const double (&eps)[2][2])
{
  const PatchGeometry &g = patch.geometry;
  const HexagonalLatticeModuli m = hexagonal_lattice_moduli(g.kn, g.ks);
  const double tr = eps[0][0] + eps[1][1];
  const double sxx = m.lame_lambda * tr + 2 * m.shear_modulus * eps[0][0],
               syy = m.lame_lambda * tr + 2 * m.shear_modulus * eps[1][1], sxy = 2 * m.shear_modulus * eps[0][1];
  const double stress = std::sqrt(sxx * sxx + syy * syy + 2 * sxy * sxy);
  const double d = g.spacing(), h = g.row_height();
  const double cell_x = (g.continuum_end - g.band_start) * d / g.cells_x, cell_y = g.rows * h / g.cells_y;
  const double y_bottom = -0.5 * h, y_top = (g.rows - 0.5) * h;

  GhostForces ghost;
  const dem::ParticleSet &p = patch.particles->particles();
  const BandParticles &band = patch.stepper->band_particles();
  std::vector<bool> tied(p.n_bodies(), false);
  for (const std::uint32_t b : band.body)
    tied[b] = true;
  for (std::size_t b = 0; b < p.n_bodies(); ++b)
    {
      const bool surface = p.y[b] < 0.5 * h || p.y[b] > (g.rows - 1.5) * h || p.x[b] < 1.2 * d;
      if (!surface && !tied[b] && p.inverse_mass[b] > 0.0) // driven particles: projected with the continuum's force
        ghost.particles_outside_band = std::max(ghost.particles_outside_band, std::hypot(p.fx[b], p.fy[b]) / (stress * d));
    }
  const auto &continuum = *patch.continuum;
  std::vector<double> residual(continuum.internal_force().locally_owned_size());
  for (unsigned int i = 0; i < residual.size(); ++i)
    residual[i] = continuum.external_force().local_element(i) - continuum.internal_force().local_element(i);
  for (std::size_t q = 0; q < band.size(); ++q)
    {
      const std::uint32_t b = band.body[q];
      const bool surface = p.y[b] < 0.5 * h || p.y[b] > (g.rows - 1.5) * h;
      if (!surface)
        ghost.band_particles = std::max(ghost.band_particles, std::hypot(p.fx[b], p.fy[b]) / (stress * d));
      for (unsigned int k = 0; k < band.points.nodes_per_point(); ++k)
        {
          residual[band.points.x_dof(q, k)] += band.points.shape_value(q, k) * p.fx[b];
          residual[band.points.y_dof(q, k)] += band.points.shape_value(q, k) * p.fy[b];
        }
    }
  std::map<dealii::types::global_dof_index, dealii::Point<2>> support;
  dealii::DoFTools::map_dofs_to_support_points(continuum.space().mapping(), continuum.space().dof_handler(), support);
  for (const auto &[dof, x] : support)
    {
      const bool near_surface = x[1] < y_bottom + 1.5 * cell_y || x[1] > y_top - 1.5 * cell_y ||
                                x[0] > g.continuum_end * d - 0.5 * cell_x;
      if (!near_surface)
        {
          ghost.continuum_nodes = std::max(ghost.continuum_nodes, std::abs(residual[dof]) / (stress * cell_x));
        }
    }
  return ghost;
}

const double patch_strain[2][2] = {{1.0e-7, 0.3e-7}, {0.3e-7, -0.4e-7}};

// The patch test of the bridging domain method (issue 6 asks for ghost forces below 1e-10 of the
// forces the stress makes; NOT met, see coupling/README.md). Measured on the default patch (spacing
// d = 10 mm, band 4 d, Q1 cells 2 d, 12 rows):
//   - untied discs of the particle region: 4.5e-7 of |sigma| d, scattered from disc to disc: the
//     round-off of the strained positions (coordinates ~0.05 m, an ulp 7e-18 m, about twenty
//     accumulated by the 20 straining steps, times kn, against contact forces of 0.1 N/m at this
//     strain; a larger strain would trade it for the lattice's geometric non-linearity, ~eps), so
//     a 1e-10 figure is out of reach of the real, geometrically exact DEM. The tie margin and the driven discs past the
//     band remove the ghost forces the branch weights would put on the discs near the band's edges
//     (before them: 4.2e-2 on the untied discs next to the band, 2.4e-2 at the nodes);
//   - the continuum's nodes in and next to the band: 1.86e-2 of |sigma| h. The constrained
//     system's residual r_I = f_ext - f_int + sum_p N_I(X_p) F_p is the difference between the
//     lattice sum of the discs' weighted virtual work under N_I and the continuum's integral of
//     (1 - w) sigma : grad N_I: exact for a linear N_I along every branch, not for Q1's bilinear
//     N_I on a hexagonal lattice's diagonal branches (nor for lattice rows out of step with the
//     cells). It falls as the band widens (about as d / w, second test): a quadrature error of
//     the method on this lattice, not round-off.
TEST(CoupledPatchTest, LagrangeMultipliersGhostForces)
{
  const CoupledPatch patch = strained_patch(LagrangeMultiplierCoupling{}, patch_strain);
  const GhostForces ghost = ghost_forces(patch, patch_strain);
  std::cout << "Lagrange patch: untied discs " << ghost.particles_outside_band << ", continuum nodes "
            << ghost.continuum_nodes << ", tied discs (net, multipliers applied) " << ghost.band_particles << std::endl;
  EXPECT_LT(ghost.particles_outside_band, 1e-6);
  EXPECT_NEAR(ghost.continuum_nodes, 1.86e-2, 0.05 * 1.86e-2); // stored reference (regression), not the goal
  // Newton's third law for the multipliers: the two sides' sums cancel.
  const auto forces = patch.stepper->diagnostics().forces;
  EXPECT_LT((forces.on_particles + forces.on_continuum).norm(), 1e-12 * std::max(1e-30, forces.on_particles.norm()) + 1e-20);
}

TEST(CoupledPatchTest, GhostForcesFallAsTheBandWidens)
{
  // Cells of one spacing, 24 rows: band 2 d -> 7.1e-2, 4 d -> 2.6e-2, 8 d -> 1.3e-2 (measured).
  const auto nodes_ghost = [](double width) {
    PatchGeometry g;
    g.band_width = width;
    g.continuum_end = g.band_start + width + 4.0;
    g.cells_x = static_cast<unsigned int>(width + 4.0);
    g.rows = 24;
    g.cells_y = 20;
    const CoupledPatch patch = strained_patch(LagrangeMultiplierCoupling{}, patch_strain, g);
    return ghost_forces(patch, patch_strain).continuum_nodes;
  };
  const double narrow = nodes_ghost(2.0), wide = nodes_ghost(8.0);
  std::cout << "ghost forces at the nodes, band 2 d: " << narrow << ", band 8 d: " << wide << std::endl;
  EXPECT_LT(wide, 0.25 * narrow); // d / w would give 0.25
}

TEST(CoupledPatchTest, PenaltySpringsAreSlackUnderUniformStrain)
{
  // The penalty ties the increments from the moment they are tied, so under the uniform strain the
  // springs are slack: no energy, no force, and the constrained system's residual at the nodes is
  // the multipliers' (the same projection). Each tied disc's own net force (2.0e-1 |sigma| d,
  // measured) is what the springs must take up by stretching: a displacement error of
  // F / k_p, the penalty's price.
  const CoupledPatch penalty = strained_patch(PenaltyCoupling{}, patch_strain);
  const CoupledPatch lagrange = strained_patch(LagrangeMultiplierCoupling{}, patch_strain);
  const GhostForces ghost = ghost_forces(penalty, patch_strain);
  std::cout << "penalty patch: untied discs " << ghost.particles_outside_band << ", continuum nodes "
            << ghost.continuum_nodes << ", tied discs' own " << ghost.band_particles << std::endl;
  EXPECT_EQ(penalty.stepper->diagnostics().coupling_energy, 0.0);
  EXPECT_EQ(penalty.stepper->diagnostics().forces.on_particles.norm(), 0.0);
  EXPECT_LT(ghost.particles_outside_band, 1e-6);
  EXPECT_NEAR(ghost.continuum_nodes, ghost_forces(lagrange, patch_strain).continuum_nodes, 1e-12);
}
} // namespace
