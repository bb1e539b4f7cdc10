#include "rockfit/core/general_impact_map.hpp"

#include <random>
#include <string>

#include <gtest/gtest.h>

#include "impact_equations.hpp"

namespace rockfit::core {
namespace {

// ω⁺ from (18) must satisfy (17) to this relative residual (the acceptance level of docs/design.md §12).
constexpr double kBalanceRelTol = 1e-12;

Eigen::Vector3d RandomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Eigen::Vector3d(u(rng), u(rng), u(rng));
}

// A generic geometry: a random symmetric positive definite Θ and random points.
ImpactGeometry RandomGeometry(std::mt19937& rng) {
  ImpactGeometry g;
  g.mass_kg = 1.7;
  const Eigen::Matrix3d a = Eigen::Matrix3d::Identity() * 0.02 + RandomVector(rng, 0.1) * RandomVector(rng, 0.1).transpose();
  g.inertia_C = 0.5 * (a + a.transpose()) + 0.01 * Eigen::Matrix3d::Identity();
  g.p_C = RandomVector(rng, 0.2);
  g.p_b = RandomVector(rng, 0.2);
  g.p_a = RandomVector(rng, 0.2);
  g.p_R = RandomVector(rng, 0.2);
  return g;
}

TEST(GeneralImpactMap, StatusNames) {
  EXPECT_STREQ(ToString(ImpactStatus::kOk), "ok");
  EXPECT_STREQ(ToString(ImpactStatus::kInfeasible), "infeasible");
  EXPECT_STREQ(ToString(ImpactStatus::kAmbiguous), "ambiguous");
  EXPECT_STREQ(ToString(ImpactStatus::kSingular), "singular");
}

TEST(GeneralImpactMap, SkewOfIsTheCrossProductOfEquations11And15) {
  std::mt19937 rng(7);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d p_x = RandomVector(rng, 1.0), p_C = RandomVector(rng, 1.0), w = RandomVector(rng, 3.0);
    const Eigen::Vector3d expected = w.cross(p_C - p_x);  // (11)
    EXPECT_LE((SkewOf(p_x, p_C) * w - expected).norm(), 1e-15 * (1.0 + expected.norm()));
    // (14) written entry by entry from r_x − r_c.
    const Eigen::Vector3d d = p_x - p_C;
    const Eigen::Matrix3d R = SkewOf(p_x, p_C);
    EXPECT_EQ(R(0, 1), -d.z());
    EXPECT_EQ(R(0, 2), d.y());
    EXPECT_EQ(R(1, 2), -d.x());
    EXPECT_EQ(R(1, 0), d.z());
  }
}

TEST(GeneralImpactMap, SatisfiesTheImpulseMomentumBalance17) {
  std::mt19937 rng(11);
  for (int k = 0; k < 200; ++k) {
    const ImpactGeometry g = RandomGeometry(rng);
    const Eigen::Vector3d w_minus = RandomVector(rng, 2.0);
    const double tau = k % 2 == 0 ? 0.0 : 1e-3 * (k % 7 - 3);
    const MapResult r = GeneralImpactMap(g, w_minus, tau);
    if (r.status != ImpactStatus::kOk) continue;  // a random geometry can be near-singular
    EXPECT_LE(testing::MomentumBalanceRelResidual(g, w_minus, r.w_plus, tau), kBalanceRelTol) << "case " << k;
  }
}

TEST(GeneralImpactMap, IsLinearInOmegaMinusWhenTauIsZero) {
  std::mt19937 rng(13);
  const ImpactGeometry g = RandomGeometry(rng);
  const Eigen::Vector3d w1 = RandomVector(rng, 1.0), w2 = RandomVector(rng, 1.0);
  const MapResult r1 = GeneralImpactMap(g, w1, 0.0), r2 = GeneralImpactMap(g, w2, 0.0);
  const MapResult r12 = GeneralImpactMap(g, 2.5 * w1 - 0.75 * w2, 0.0);
  ASSERT_EQ(r12.status, ImpactStatus::kOk);
  const Eigen::Vector3d expected = 2.5 * r1.w_plus - 0.75 * r2.w_plus;
  EXPECT_LE((r12.w_plus - expected).norm(), 1e-13 * expected.norm());
}

TEST(GeneralImpactMap, SingularMatrixIsAStatusNotNaN) {
  // With Θ = 0 the matrix Θ − m R_R R_a = −m R_R R_a has rank ≤ 2: singular for every geometry.
  std::mt19937 rng(17);
  ImpactGeometry g = RandomGeometry(rng);
  g.inertia_C.setZero();
  const MapResult r = GeneralImpactMap(g, Eigen::Vector3d(0.0, 1.0, 0.0), 0.0);
  EXPECT_EQ(r.status, ImpactStatus::kSingular);
  EXPECT_TRUE(r.w_plus.allFinite());
  EXPECT_EQ(r.w_plus, Eigen::Vector3d::Zero());
  // All points coincide with the COM: the matrix is Θ itself, invertible — not a false alarm.
  ImpactGeometry point;
  point.mass_kg = 1.0;
  point.inertia_C = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  const MapResult identity = GeneralImpactMap(point, Eigen::Vector3d(1.0, 2.0, 3.0), 0.0);
  ASSERT_EQ(identity.status, ImpactStatus::kOk);
  EXPECT_LE((identity.w_plus - Eigen::Vector3d(1.0, 2.0, 3.0)).norm(), 1e-15);
}

TEST(GeneralImpactMap, KineticEnergyAboutAPointIsTranslationalPlusRotational) {
  std::mt19937 rng(19);
  for (int k = 0; k < 20; ++k) {
    const ImpactGeometry g = RandomGeometry(rng);
    const Eigen::Vector3d w = RandomVector(rng, 2.0);
    const double expected = testing::KineticEnergyFromComVelocity(g, g.p_a, w);
    EXPECT_NEAR(KineticEnergyAbout(g, g.p_a, w), expected, 1e-14 * expected);
  }
}

}  // namespace
}  // namespace rockfit::core
