// The patch test of methods 1 and 2 in the layout where the energy weights are exact (issue 6:
// "no ghost forces, residual below 1e-10 relative"): the band along the lattice's rows, cells
// commensurate with the lattice, the band's edges on cell sides (coupling_benchmarks.h, "The patch
// test along the lattice's rows", has the argument). Measured figures: coupling/README.md.
#include "test_coupling_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>

using namespace geohybrid;
using namespace geohybrid::coupling;
using namespace geohybrid::coupling::benchmarks;

namespace
{
/// A strain with all three components, large enough for the discs' position round-off (about
/// 1e-17 m against contact displacements eps d = 1e-5 m) to stay below 1e-11 of the forces.
const PlaneStrain general_strain{1.0e-3, -0.4e-3, 0.3e-3};

void print(const char *what, const RowPatchTestResult &r)
{
  std::printf("%s: ghost force at the nodes %.3e (%zu DoFs), on the untied discs %.3e (%zu discs), largest disc "
              "moment %.3e; %zu tied, %zu driven\n",
              what, r.ghost.continuum_nodes, r.n_nodes, r.ghost.particles_outside_band, r.n_discs, r.disc_moments,
              r.n_tied, r.n_driven);
}

void expect_no_ghost_forces(const RowPatchTestResult &r)
{
  // 8 columns of nodes less those near the lattice's ends: 4 columns of nodes on the 6 levels below the
  // mesh's free top; the untied rows 2-4 (rows 0 and 1 at the free bottom, row 5 within a branch
  // of the band, tied) of 12 interior columns.
  EXPECT_EQ(r.n_nodes, 48u);
  EXPECT_EQ(r.n_discs, 36u);
  EXPECT_GT(r.n_driven, 0u);
  EXPECT_LT(r.ghost.continuum_nodes, 1e-10);
  EXPECT_LT(r.ghost.particles_outside_band, 1e-10);
}

TEST(RowPatch, MultipliersLeaveNoGhostForceWhenBothModelsCarryTheLatticesStress)
{
  const RowPatchTestResult r = row_patch_test(LagrangeMultiplierCoupling{}, general_strain, PatchContinuumStress::lattice);
  print("row patch, multipliers, the lattice's stress", r);
  expect_no_ghost_forces(r);
}

TEST(RowPatch, PenaltyLeavesNoGhostForceWhenBothModelsCarryTheLatticesStress)
{
  // The springs are slack under the uniform strain: the same residual as the multipliers'.
  const RowPatchTestResult r = row_patch_test(PenaltyCoupling{}, general_strain, PatchContinuumStress::lattice);
  print("row patch, penalty, the lattice's stress", r);
  expect_no_ghost_forces(r);
}

TEST(RowPatch, OtherCommensurateLayoutsAreExactToo)
{
  // The default is the layout nearest a band of 4 spacings and cells of 2; a wider band on cells
  // of one spacing, and the narrowest band (2 rows) on cells of 3, pass as well.
  const RowPatchLayout nearest = commensurate_row_patch(4.0, 2.0), standard;
  EXPECT_EQ(nearest.cells_x, standard.cells_x);
  EXPECT_EQ(nearest.cells_y, standard.cells_y);
  EXPECT_DOUBLE_EQ(nearest.band_width, standard.band_width);
  EXPECT_DOUBLE_EQ(nearest.mesh_right, standard.mesh_right);
  for (const auto &[band, cell] : {std::pair{8.0, 1.0}, std::pair{2.0, 3.0}})
    {
      const RowPatchTestResult r = row_patch_test(LagrangeMultiplierCoupling{}, general_strain, PatchContinuumStress::lattice,
                                                  {}, commensurate_row_patch(band, cell));
      std::printf("band %.0f d, cells %.0f d: ", band, cell);
      print("row patch", r);
      EXPECT_GT(r.n_nodes, 10u);
      EXPECT_LT(r.ghost.continuum_nodes, 1e-10);
      EXPECT_LT(r.ghost.particles_outside_band, 1e-10);
    }
  EXPECT_THROW(commensurate_row_patch(0.0, 2.0), std::invalid_argument);
  EXPECT_THROW(commensurate_row_patch(4.0, -1.0), std::invalid_argument);
}

TEST(RowPatch, ClosedFormModuliLeaveOnlyTheLatticesNonLinearity)
{
  // The continuum's C : eps is the lattice's tangent at zero strain: the residual is the
  // lattice's geometric non-linearity, of order eps (it falls tenfold with the strain), not the
  // coupling's (which is round-off, above).
  const auto scaled = [](double s) { return PlaneStrain{1.0 * s, -0.4 * s, 0.3 * s}; };
  const RowPatchTestResult large = row_patch_test(LagrangeMultiplierCoupling{}, scaled(1e-3), PatchContinuumStress::matching_moduli);
  const RowPatchTestResult small = row_patch_test(LagrangeMultiplierCoupling{}, scaled(1e-4), PatchContinuumStress::matching_moduli);
  print("row patch, closed-form moduli, strain 1e-3", large);
  print("row patch, closed-form moduli, strain 1e-4", small);
  EXPECT_GT(large.ghost.continuum_nodes, 1e-5);
  EXPECT_LT(large.ghost.continuum_nodes, 1e-3);
  EXPECT_NEAR(large.ghost.continuum_nodes / small.ghost.continuum_nodes, 10.0, 0.5);
}

TEST(RowPatch, CellsOutOfStepWithTheLatticeLeaveTheQuadratureError)
{
  // The same band on cells 2.4 spacings wide from x = -0.25 d (their sides between the lattice's
  // points): each row's sum of a hat is no longer its integral.
  RowPatchLayout layout;
  layout.mesh_left = -0.25;
  layout.mesh_right = 16.55;
  layout.cells_x = 7;
  const RowPatchTestResult r =
    row_patch_test(LagrangeMultiplierCoupling{}, general_strain, PatchContinuumStress::lattice, {}, layout);
  print("row patch, cells 2.4 d wide", r);
  EXPECT_GT(r.ghost.continuum_nodes, 1e-4);
  EXPECT_LT(r.ghost.particles_outside_band, 1e-10); // the untied discs are the lattice's alone
}

TEST(RowPatch, ShearLeavesAMomentOnTheBandsEdgeRowAsInClosedForm)
{
  // At the band's particle edge (s = 0, the weight's kink) a disc's horizontal contacts and lower
  // ones have weight 1, its upper ones W = 1 - h / (2 w): of the six contact moments, which cancel
  // in the lattice (m_60 + m_120 = -m_0 for each opposite pair), (1 - W) m_0 is left, m_0 = r ks
  // eps_xy d the moment of a horizontal contact's tangential force (small strain). Elsewhere the
  // weight is linear over a disc's rows and the moments cancel; without shear there are none.
  const PatchGeometry g;
  const PlaneStrain shear{0.0, 0.0, 1e-4};
  const RowPatchTestResult r = row_patch_test(LagrangeMultiplierCoupling{}, shear, PatchContinuumStress::lattice);
  const RowPatchTestResult no_shear =
    row_patch_test(LagrangeMultiplierCoupling{}, {1e-4, -0.4e-4, 0.0}, PatchContinuumStress::lattice);
  const RowPatchLayout layout;
  const double h = std::sqrt(3.0) / 2.0, d = g.spacing();
  const double m0 = (g.radius - 0.5 * (2.0 * g.radius - d)) * g.ks * shear.xy * d;
  const double closed_form = h / (2.0 * layout.band_width) * m0 / (stress_norm(g, shear) * d * d);
  print("row patch, pure shear", r);
  std::printf("largest moment %.6e, closed form %.6e; without shear %.3e\n", r.disc_moments, closed_form, no_shear.disc_moments);
  EXPECT_NEAR(r.disc_moments, closed_form, 1e-3 * closed_form); // the strain's non-linearity, 1e-4
  EXPECT_LT(r.ghost.continuum_nodes, 1e-9);                     // the forces still balance
  EXPECT_LT(no_shear.disc_moments, 1e-12);
}

TEST(RowPatch, RefusesTheInterfaceCoupling)
{
  EXPECT_THROW(row_patch_test(InterfaceCoupling{}, general_strain, PatchContinuumStress::lattice), std::invalid_argument);
}
} // namespace
