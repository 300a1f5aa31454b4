// The coupled stepper (issue 6): the patch test of the bridging domain method with Lagrange
// multipliers and of the penalty overlap, the coupling's force balance, the constraint held.
#include "test_coupling_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::testing;

namespace
{
// strained_patch and ghost_forces are the library's (apps/coupling_benchmarks/coupling_benchmarks.h), the same
// functions `geohybrid coupling-test` reports from.
const PlaneStrain patch_strain{1.0e-7, -0.4e-7, 0.3e-7}; // xx, yy, xy

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
