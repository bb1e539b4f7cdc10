#include "signal/euler_kinematics.hpp"

#include <gtest/gtest.h>

#include "recording/attitude.hpp"

namespace rockfit::io {
namespace {

// Central-difference step for Ṙ [s]; the O(h²) error is ≈ 1e-10 for these rates.
constexpr double kStep = 1e-5;
constexpr double kTolerance = 1e-8;  // rad/s

Eigen::Vector3d Unskew(const Eigen::Matrix3d& s) { return {s(2, 1), s(0, 2), s(1, 0)}; }

TEST(EulerKinematics, PositivePitchTiltsTheBodyXAxisDown) {
  // docs/design.md §2: the release φy = −α lifts the +x side.
  const Eigen::Matrix3d Ry = RotationFromEulerZyx({0.0, 0.2, 0.0});
  EXPECT_LT((Ry * Eigen::Vector3d::UnitX()).z(), 0.0);
}

TEST(EulerKinematics, BodyRatesAreTheSkewPartOfRTransposeRDot) {
  // w_B^ = R_WBᵀ·Ṙ_WB, with Ṙ by central differences along a straight line in angle space.
  const Eigen::Vector3d angles(0.4, 0.15, -0.25);
  const Eigen::Vector3d rates(0.7, -1.3, 0.5);
  const Eigen::Matrix3d R = RotationFromEulerZyx(angles);
  const Eigen::Matrix3d R_dot =
      (RotationFromEulerZyx(angles + kStep * rates) - RotationFromEulerZyx(angles - kStep * rates)) / (2 * kStep);
  const Eigen::Vector3d expected = Unskew(R.transpose() * R_dot);
  EXPECT_NEAR((BodyRatesFromEulerZyx(angles, rates) - expected).norm(), 0.0, kTolerance);
}

TEST(EulerKinematics, EulerRatesInvertBodyRates) {
  const Eigen::Vector3d angles(-1.0, 0.3, 0.2);
  const Eigen::Vector3d rates(0.1, 2.0, -0.4);
  const Eigen::Vector3d w_B = BodyRatesFromEulerZyx(angles, rates);
  EXPECT_NEAR((EulerZyxRates(angles, w_B) - rates).norm(), 0.0, 1e-14);
}

TEST(EulerKinematics, PlanarRockingAboutYHasPitchRateEqualToOmegaY) {
  const Eigen::Vector3d rates = EulerZyxRates({0.0, -0.2, 0.0}, {0.0, 1.5, 0.0});
  EXPECT_DOUBLE_EQ(rates[1], 1.5);
  EXPECT_DOUBLE_EQ(rates[0], 0.0);
  EXPECT_DOUBLE_EQ(rates[2], 0.0);
}

}  // namespace
}  // namespace rockfit::io
