// The soil models of fem/constitutive against closed forms: Hooke's law, the Mohr-Coulomb limit
// of a plane-strain biaxial test, the dilatancy of plastic flow, the apex in tension, the
// consistent tangents against finite differences in every return region, the explicit solver's
// update without the tangent against the full one (bit for bit), and bad parameters.
#include "fem/constitutive/biaxial_path.h"
#include "fem/constitutive/plane_strain_tensors.h"
#include "fem/constitutive/soil_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <utility>

using namespace geohybrid::fem;

namespace
{
SoilParameters sand(SoilModelKind kind, double phi_deg, double cohesion, double psi_deg)
{
  SoilParameters p;
  p.kind = kind;
  p.young_modulus = 20e6;
  p.poisson_ratio = 0.3;
  p.strength.friction_angle_deg = phi_deg;
  p.strength.cohesion = cohesion;
  p.strength.dilatancy_angle_deg = psi_deg;
  return p;
}

StressTensor plane_strain_stress(double xx, double yy, double xy, double zz)
{
  StressTensor s;
  s[0][0] = xx;
  s[1][1] = yy;
  s[0][1] = xy;
  s[2][2] = zz;
  return s;
}

StrainTensor strain(double xx, double yy, double xy)
{
  StrainTensor e;
  e[0][0] = xx;
  e[1][1] = yy;
  e[0][1] = xy;
  return e;
}

/// Central differences of the in-plane stress with respect to the strain increment. A perturbation
/// of the symmetric eps_xy moves eps_xy and eps_yx together, so it measures 2 C_ijxy.
TangentTensor finite_difference_tangent(const SoilModel &model, const StressTensor &stress,
                                        const StrainTensor &increment, double step)
{
  TangentTensor tangent;
  const unsigned int pairs[3][2] = {{0, 0}, {1, 1}, {0, 1}};
  for (const auto &kl : pairs)
    {
      StrainTensor plus = increment, minus = increment;
      plus[kl[0]][kl[1]] += step;
      minus[kl[0]][kl[1]] -= step;
      const auto derivative =
        (model.update(stress, plus).stress - model.update(stress, minus).stress) / (2.0 * step);
      const double factor = kl[0] == kl[1] ? 1.0 : 0.5;
      for (const auto &ij : pairs)
        tangent[ij[0]][ij[1]][kl[0]][kl[1]] = factor * derivative[ij[0]][ij[1]];
    }
  return tangent;
}

struct TangentCase
{
  const char *name;
  StressTensor stress;
  StrainTensor increment;
  ReturnRegion expected_region;
};
} // namespace

TEST(LinearElastic, HookesLawInPlaneStrain)
{
  const SoilModel model(sand(SoilModelKind::linear_elastic, 30, 0, 0));
  const double E = 20e6, nu = 0.3;
  const auto r = model.update(StressTensor(), strain(1e-4, -2e-4, 3e-5));
  // sigma_xx = E/((1+nu)(1-2nu)) ((1-nu) eps_xx + nu eps_yy), sigma_zz = nu (sigma_xx + sigma_yy)
  const double c = E / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(r.stress[0][0], c * ((1 - nu) * 1e-4 + nu * -2e-4), 1e-9);
  EXPECT_NEAR(r.stress[1][1], c * (nu * 1e-4 + (1 - nu) * -2e-4), 1e-9);
  EXPECT_NEAR(r.stress[0][1], E / (1 + nu) * 3e-5, 1e-9);
  EXPECT_NEAR(r.stress[2][2], nu * (r.stress[0][0] + r.stress[1][1]), 1e-9);
  EXPECT_EQ(r.region, ReturnRegion::elastic);
  const auto fd = finite_difference_tangent(model, StressTensor(), strain(1e-4, -2e-4, 3e-5), 1e-7);
  EXPECT_LT((fd - r.tangent).norm(), 1e-8 * r.tangent.norm());
  EXPECT_NEAR(model.default_k0(), nu / (1 - nu), 1e-15);
}

// Plane-strain biaxial compression of one material point: confinement p0, then axial strain at
// constant lateral stress. At failure the Mohr-Coulomb criterion gives
//   sigma_axial / sigma_lateral = (1 + sin phi)/(1 - sin phi) + 2 c cos(phi)/(1 - sin phi) / p0.
TEST(MohrCoulomb, BiaxialCompressionReachesTheMohrCoulombLimit)
{
  for (const double phi : {20.0, 30.0, 40.0})
    for (const double c : {0.0, 15e3})
      for (const double psi : {0.0, 0.5 * phi, phi})
        for (const double p0 : {50e3, 200e3})
          {
            const SoilModel model(sand(SoilModelKind::mohr_coulomb, phi, c, psi));
            BiaxialPathSpec spec;
            spec.confining_pressure = p0;
            spec.final_axial_strain = -0.10;
            spec.n_axial_increments = 100;
            const auto path = run_plane_strain_biaxial(model, spec);
            const auto &end = path.back();
            const double s = std::sin(phi * pi / 180.0);
            const double expected = (1 + s) / (1 - s) + 2 * c * std::cos(phi * pi / 180.0) / (1 - s) / p0;
            SCOPED_TRACE("phi " + std::to_string(phi) + " c " + std::to_string(c) + " psi " +
                         std::to_string(psi) + " p0 " + std::to_string(p0));
            EXPECT_NEAR(end.stress[0][0], -p0, 1e-9 * p0);
            EXPECT_NEAR(end.stress[1][1] / end.stress[0][0], expected, 1e-10 * expected);
            // Before failure the response is elastic, and the confinement stage left sigma_zz =
            // -2 nu p0: less compressive than the confinement. With a low friction angle the
            // out-of-plane Mohr circle fails first and plastic flow in z lowers sigma_zz to the
            // lateral stress, where the state sits on the triaxial-compression edge.
            EXPECT_NEAR(path.front().stress[2][2], -2 * 0.3 * p0, 1e-9 * p0);
            EXPECT_TRUE(end.region == ReturnRegion::surface ||
                        end.region == ReturnRegion::edge_triaxial_compression)
              << to_string(end.region);
            EXPECT_GE(end.stress[2][2], end.stress[1][1]);
            EXPECT_LE(end.stress[2][2], end.stress[0][0] + 1e-9 * p0);
          }
}

// In steady plastic flow the stress no longer changes, so the strain rates are plastic and their
// ratio is set by the potential g = m sigma_1 - sigma_3:
//   d eps_v / (d eps_1 - d eps_3) = (m - 1)/(m + 1) = sin(psi).
// The lateral direction x carries sigma_1 (least compressive), the axial y sigma_3.
TEST(MohrCoulomb, PlasticFlowDilatesAtTheDilatancyAngle)
{
  for (const double psi : {0.0, 5.0, 15.0, 35.0})
    {
      const SoilModel model(sand(SoilModelKind::mohr_coulomb, 35.0, 5e3, psi));
      BiaxialPathSpec spec;
      spec.final_axial_strain = -0.04;
      spec.n_axial_increments = 80;
      const auto path = run_plane_strain_biaxial(model, spec);
      const auto &a = path[path.size() - 11], &b = path.back();
      const double dv = b.volumetric_strain - a.volumetric_strain;
      const double d13 = (b.lateral_strain - a.lateral_strain) - (b.axial_strain - a.axial_strain);
      EXPECT_NEAR(dv / d13, std::sin(psi * pi / 180.0), 1e-9) << "psi " << psi;
      // The consistent tangent makes the mixed-control Newton iterations converge at once: a
      // linear yield surface and a linear elastic law leave nothing for a second iteration.
      unsigned int max_iterations = 0;
      for (const auto &p : path)
        max_iterations = std::max(max_iterations, p.n_iterations);
      EXPECT_LE(max_iterations, 3u) << "psi " << psi;
    }
}

// Stretching a cohesive soil equally in every direction takes it to the apex of the yield
// surface, the hydrostatic tension c cot(phi), whatever the dilatancy.
TEST(MohrCoulomb, PureTensionReturnsToTheApex)
{
  for (const double psi : {0.0, 10.0, 30.0})
    {
      const SoilModel model(sand(SoilModelKind::mohr_coulomb, 30.0, 20e3, psi));
      const auto r = model.update(StressTensor(), strain(5e-3, 5e-3, 0.0));
      const double apex = 20e3 / std::tan(30.0 * pi / 180.0);
      EXPECT_EQ(r.region, ReturnRegion::apex) << "psi " << psi;
      for (unsigned int i = 0; i < 3; ++i)
        EXPECT_NEAR(r.stress[i][i], apex, 1e-10 * apex) << "psi " << psi;
      EXPECT_NEAR(r.stress[0][1], 0.0, 1e-10 * apex);
      EXPECT_NEAR(r.tangent.norm(), 0.0, 1e-20);
    }
}

// The consistent tangent is the derivative of the stress update: central differences agree to
// 1e-5 in each region of the return mapping, for non-associated and associated flow. The trial
// states carry an in-plane shear, so the rotation of the principal axes is part of the check.
// (The update is a function of any start stress; the edge cases start outside the surface so
// that the trial stress has two nearly equal principal values.)
TEST(MohrCoulomb, ConsistentTangentMatchesFiniteDifferences)
{
  const TangentCase cases[] = {
    {"elastic", plane_strain_stress(-100e3, -150e3, 10e3, -80e3), strain(1e-5, -2e-5, 5e-6),
     ReturnRegion::elastic},
    {"main plane", plane_strain_stress(-100e3, -250e3, 5e3, -150e3), strain(3e-3, -3e-3, 2e-4),
     ReturnRegion::surface},
    {"triaxial compression edge", plane_strain_stress(-50e3, -250e3, 0.0, -50e3),
     strain(0.0, -1e-4, 1e-4), ReturnRegion::edge_triaxial_compression},
    {"triaxial extension edge", plane_strain_stress(-200e3, -200e3, 0.0, -200e3),
     strain(8e-3, 0.0, 1e-4), ReturnRegion::edge_triaxial_extension},
    {"apex", StressTensor(), strain(2e-3, 2.5e-3, 1e-4), ReturnRegion::apex},
  };
  for (const double psi : {0.0, 10.0, 30.0})
    {
      const SoilModel model(sand(SoilModelKind::mohr_coulomb, 30.0, 10e3, psi));
      const double elastic_norm = model.elasticity().plane_strain_stiffness().norm();
      for (const auto &c : cases)
        {
          SCOPED_TRACE(std::string(c.name) + ", psi " + std::to_string(psi));
          const auto r = model.update(c.stress, c.increment);
          ASSERT_EQ(r.region, c.expected_region) << to_string(r.region);
          EXPECT_LE(model.yield_function(r.stress),
                    1e-10 * (std::abs(r.stress[1][1]) + std::abs(r.stress[0][0]) + 1e3));
          const auto fd = finite_difference_tangent(model, c.stress, c.increment, 1e-8);
          EXPECT_LE((fd - r.tangent).norm(), 1e-5 * std::max(r.tangent.norm(), 1e-3 * elastic_norm));
        }
    }
}

// The same check over random states, with the soil of the implicit pull-out bench (sand 1:
// phi = 38.4 deg, c = 1 kPa, psi = 10 deg, apex at 1.26 kPa) at the low confinement of the
// run-out tank near its clamp (mean stress 0 to -20 kPa), where Newton converged only linearly:
// in every return region, the algorithmic tangent agrees with central differences to 1e-5 of
// max(|C_ep|, 1e-3 |C_el|). A sample whose stencil leaves the region of its centre is skipped
// (across a region boundary the update is only continuous, and a difference quotient measures
// nothing there); at least 200 samples per region must remain.
TEST(MohrCoulomb, ConsistentTangentAtLowConfinementMatchesFiniteDifferences)
{
  std::mt19937 random(2026);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const SoilModel model(sand(SoilModelKind::mohr_coulomb, 38.4, 1e3, 10.0));
  const double elastic_norm = model.elasticity().plane_strain_stiffness().norm();
  const double step = 1e-9;
  unsigned int checked[5] = {0, 0, 0, 0, 0};
  double worst[5] = {0, 0, 0, 0, 0};
  for (unsigned int n = 0; n < 40000; ++n)
    {
      const double mean = -10e3 + 10e3 * uniform(random);
      const StressTensor start = plane_strain_stress(mean + 5e3 * uniform(random), mean + 5e3 * uniform(random),
                                                     3e3 * uniform(random), mean + 5e3 * uniform(random));
      const StrainTensor increment = strain(1e-3 * uniform(random), 1e-3 * uniform(random), 5e-4 * uniform(random));
      const auto r = model.update(start, increment);
      bool same_region = true;
      for (const auto &kl : {std::pair{0, 0}, std::pair{1, 1}, std::pair{0, 1}})
        for (const double sign : {-1.0, 1.0})
          {
            StrainTensor perturbed = increment;
            perturbed[kl.first][kl.second] += sign * step;
            same_region = same_region && model.update(start, perturbed).region == r.region;
          }
      if (!same_region)
        continue;
      const auto fd = finite_difference_tangent(model, start, increment, step);
      const double error = (fd - r.tangent).norm() / std::max(r.tangent.norm(), 1e-3 * elastic_norm);
      const auto region = static_cast<unsigned int>(r.region);
      ++checked[region];
      worst[region] = std::max(worst[region], error);
    }
  for (unsigned int region = 0; region < 5; ++region)
    {
      SCOPED_TRACE(to_string(static_cast<ReturnRegion>(region)));
      std::cout << "low confinement, " << to_string(static_cast<ReturnRegion>(region)) << ": " << checked[region]
                << " samples, worst relative tangent error " << worst[region] << std::endl;
      EXPECT_GE(checked[region], 200u);
      EXPECT_LE(worst[region], 1e-5);
    }
}

// Every return lands on the yield surface, in the ordered sextant, with a plastic strain that
// follows the flow rule: for a main-plane return delta eps^p is parallel to b = (m, 0, -1) in the
// principal frame, so its principal values satisfy (e_1 + e_3) / (e_1 - e_3) = sin(psi), e_2 = 0.
TEST(MohrCoulomb, RandomTrialStatesReturnConsistently)
{
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const SoilModel model(sand(SoilModelKind::mohr_coulomb, 32.0, 8e3, 12.0));
  const double sin_psi = std::sin(12.0 * pi / 180.0);
  unsigned int count[5] = {0, 0, 0, 0, 0};
  for (unsigned int n = 0; n < 20000; ++n)
    {
      const StressTensor start = plane_strain_stress(-100e3 + 50e3 * uniform(random), -100e3 + 50e3 * uniform(random),
                                                     20e3 * uniform(random), -100e3 + 50e3 * uniform(random));
      const StrainTensor increment = strain(8e-3 * uniform(random), 8e-3 * uniform(random), 4e-3 * uniform(random));
      const auto r = model.update(start, increment);
      ++count[static_cast<int>(r.region)];
      const double scale = r.stress.norm() + 1e4;
      if (r.region == ReturnRegion::elastic)
        continue;
      EXPECT_NEAR(model.yield_function(r.stress), 0.0, 1e-10 * scale);
      if (r.region == ReturnRegion::surface)
        {
          auto e = principal_frame(r.plastic_strain_increment).values; // (a, b, zz)
          std::sort(e.begin(), e.end());
          EXPECT_NEAR(e[1], 0.0, 1e-9 * (e[2] - e[0]));
          EXPECT_NEAR((e[2] + e[0]) / (e[2] - e[0]), sin_psi, 1e-7);
        }
    }
  // The sampling must reach every region, or the checks above prove little.
  for (unsigned int region = 0; region < 5; ++region)
    EXPECT_GT(count[region], 20u) << to_string(static_cast<ReturnRegion>(region));
}

// The explicit solver's update_stress skips the tangent: its stress, plastic strain increment and
// region must be the full update's to the last bit (the explicit run's results must not move), in
// every return region of every model.
TEST(SoilModel, UpdateWithoutTangentIsTheFullUpdateBitForBit)
{
  const auto same_bits = [](const dealii::SymmetricTensor<2, 3> &a, const dealii::SymmetricTensor<2, 3> &b) {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        {
          const double x = a[i][j], y = b[i][j];
          if (std::memcmp(&x, &y, sizeof(double)) != 0)
            return false;
        }
    return true;
  };
  for (const SoilModelKind kind : {SoilModelKind::mohr_coulomb, SoilModelKind::drucker_prager, SoilModelKind::linear_elastic})
    {
      SCOPED_TRACE(to_string(kind));
      const SoilModel model(sand(kind, 32.0, 8e3, 12.0));
      std::mt19937 random(777);
      std::uniform_real_distribution<double> uniform(-1.0, 1.0);
      unsigned int count[5] = {0, 0, 0, 0, 0};
      for (unsigned int n = 0; n < 20000; ++n)
        {
          const StressTensor start = plane_strain_stress(-100e3 + 50e3 * uniform(random), -100e3 + 50e3 * uniform(random),
                                                         20e3 * uniform(random), -100e3 + 50e3 * uniform(random));
          const StrainTensor increment = strain(8e-3 * uniform(random), 8e-3 * uniform(random), 4e-3 * uniform(random));
          const StressUpdate full = model.update(start, increment);
          const StressOnlyUpdate fast = model.update_stress(start, increment);
          ++count[static_cast<int>(full.region)];
          ASSERT_EQ(fast.region, full.region) << "sample " << n;
          ASSERT_TRUE(same_bits(fast.stress, full.stress)) << "sample " << n << ", " << to_string(full.region);
          ASSERT_TRUE(same_bits(fast.plastic_strain_increment, full.plastic_strain_increment))
            << "sample " << n << ", " << to_string(full.region);
        }
      // Mohr-Coulomb's sampling reaches all of its regions (RandomTrialStatesReturnConsistently).
      if (kind == SoilModelKind::mohr_coulomb)
        for (unsigned int region = 0; region < 5; ++region)
          EXPECT_GT(count[region], 20u) << to_string(static_cast<ReturnRegion>(region));
    }
}

// Drucker-Prager matched in plane strain: once sigma_zz has settled (no plastic eps_zz), the
// in-plane strength and dilatancy are Mohr-Coulomb's. sigma_zz settles exponentially with the
// axial strain (the ratio's error falls about tenfold per 2 % of strain here), hence the long path.
TEST(DruckerPrager, PlaneStrainMatchReproducesMohrCoulomb)
{
  for (const double psi : {0.0, 10.0, 30.0})
    {
      const double phi = 30.0, c = 10e3, p0 = 100e3;
      const SoilModel model(sand(SoilModelKind::drucker_prager, phi, c, psi));
      BiaxialPathSpec spec;
      spec.confining_pressure = p0;
      spec.final_axial_strain = -0.35;
      spec.n_axial_increments = 350;
      const auto path = run_plane_strain_biaxial(model, spec);
      const auto &a = path[path.size() - 11], &b = path.back();
      const double s = std::sin(phi * pi / 180.0);
      const double expected = (1 + s) / (1 - s) + 2 * c * std::cos(phi * pi / 180.0) / (1 - s) / p0;
      EXPECT_NEAR(b.stress[1][1] / b.stress[0][0], expected, 1e-12 * expected) << "psi " << psi;
      const double dv = b.volumetric_strain - a.volumetric_strain;
      const double d13 = (b.lateral_strain - a.lateral_strain) - (b.axial_strain - a.axial_strain);
      EXPECT_NEAR(dv / d13, std::sin(psi * pi / 180.0), 1e-10) << "psi " << psi;
      EXPECT_EQ(b.region, ReturnRegion::surface);
      // The cone is curved, so the mixed-control Newton needs a few iterations; quadratic
      // convergence with the consistent tangent keeps them few.
      EXPECT_LE(b.n_iterations, 5u);
    }
}

TEST(DruckerPrager, ConsistentTangentAndApex)
{
  for (const double psi : {0.0, 10.0, 30.0})
    {
      const SoilModel model(sand(SoilModelKind::drucker_prager, 30.0, 10e3, psi));
      const auto cone = model.update(plane_strain_stress(-100e3, -250e3, 5e3, -150e3), strain(3e-3, -3e-3, 2e-4));
      ASSERT_EQ(cone.region, ReturnRegion::surface);
      EXPECT_NEAR(model.yield_function(cone.stress), 0.0, 1e-9 * cone.stress.norm());
      const auto fd = finite_difference_tangent(model, plane_strain_stress(-100e3, -250e3, 5e3, -150e3),
                                                strain(3e-3, -3e-3, 2e-4), 1e-8);
      EXPECT_LE((fd - cone.tangent).norm(), 1e-5 * cone.tangent.norm()) << "psi " << psi;
      // The matched cone keeps the Mohr-Coulomb apex c cot(phi).
      const auto apex = model.update(StressTensor(), strain(5e-3, 5e-3, 0.0));
      ASSERT_EQ(apex.region, ReturnRegion::apex);
      for (unsigned int i = 0; i < 3; ++i)
        EXPECT_NEAR(apex.stress[i][i], 10e3 / std::tan(30.0 * pi / 180.0), 1e-6);
    }
}

// Bad parameters stop at construction with a message naming the parameter.
TEST(SoilParameters, OutOfRangeValuesAreRefusedByName)
{
  auto expect_refused = [](SoilParameters p, const std::string &name) {
    for (const auto kind : {SoilModelKind::linear_elastic, SoilModelKind::mohr_coulomb, SoilModelKind::drucker_prager})
      {
        p.kind = kind;
        const bool strength_only = name.find("angle") != std::string::npos || name == "cohesion";
        if (strength_only && kind == SoilModelKind::linear_elastic)
          continue; // an elastic soil has no strength to check
        try
          {
            SoilModel model(p, "test soil");
            ADD_FAILURE() << name << " accepted for " << to_string(kind);
          }
        catch (const std::invalid_argument &e)
          {
            EXPECT_NE(std::string(e.what()).find("'" + name + "'"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("test soil"), std::string::npos) << e.what();
          }
      }
  };
  const SoilParameters good = sand(SoilModelKind::mohr_coulomb, 30, 0, 0);
  for (const double E : {-1e6, 0.0})
    {
      auto p = good;
      p.young_modulus = E;
      expect_refused(p, "Young's modulus");
    }
  for (const double nu : {-1.0, 0.5, 0.6})
    {
      auto p = good;
      p.poisson_ratio = nu;
      expect_refused(p, "Poisson's ratio");
    }
  for (const double phi : {0.0, 90.0, 95.0, -10.0})
    {
      auto p = good;
      p.strength.friction_angle_deg = phi;
      expect_refused(p, "friction angle");
    }
  auto p = good;
  p.strength.cohesion = -1.0;
  expect_refused(p, "cohesion");
  p = good;
  p.strength.dilatancy_angle_deg = 31.0;
  expect_refused(p, "dilatancy angle");
  p.strength.dilatancy_angle_deg = -1.0;
  expect_refused(p, "dilatancy angle");
  EXPECT_THROW(soil_model_kind_from_string("Cam-Clay"), std::invalid_argument);
}
