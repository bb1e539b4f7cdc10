// io's attitude helpers: the x-IMU reading of core's Euler conversions, nearest rotation, unwrapping
// (the conversions themselves are tested in tests/core/attitude_test.cpp).
#include "recording/attitude.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/io/units.hpp"

namespace rockfit::io {
namespace {

constexpr double kRoundoff = 1e-12;  // rad; a few ulps of the trigonometric round trip

Eigen::Matrix3d Rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
Eigen::Matrix3d Ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }

TEST(Attitude, MatchesTheXimuEulerFormulasOfItsQuaternion) {
  // docs/file-formats.md §1.6: from the file quaternion q (Earth relative to sensor), φ = atan2(2(q2q3 − q0q1),
  // 2q0² − 1 + 2q3²), θ = −asin(2(q1q3 + q0q2)), ψ = atan2(2(q1q2 − q0q3), 2q0² − 1 + 2q1²); R_WS = R(conj q).
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.9, -0.2, 0.3, 0.25).normalized();
  const double phi = std::atan2(2 * (q.y() * q.z() - q.w() * q.x()), 2 * q.w() * q.w() - 1 + 2 * q.z() * q.z());
  const double theta = -std::asin(2 * (q.x() * q.z() + q.w() * q.y()));
  const double psi = std::atan2(2 * (q.x() * q.y() - q.w() * q.z()), 2 * q.w() * q.w() - 1 + 2 * q.x() * q.x());
  EXPECT_TRUE(EulerZyxFromQuaternion(q.conjugate()).isApprox(Eigen::Vector3d(psi, theta, phi), kRoundoff));
}

TEST(Attitude, NearestRotationRepairsPrintedMatricesAndReportsReflections) {
  const Eigen::Matrix3d R = Rz(0.3) * Ry(0.1);
  double error = 0.0;
  double determinant = 0.0;
  EXPECT_TRUE(NearestRotation(1.000486 * R, &error, &determinant).isApprox(R, 1e-12));
  EXPECT_NEAR(error, 1.000486 * 1.000486 - 1.0, 1e-12);
  Eigen::Matrix3d mirror = R;
  mirror.col(2) *= -1.0;
  NearestRotation(mirror, &error, &determinant);
  EXPECT_LT(determinant, 0.0);
}

TEST(Attitude, UnwrapMakesAnglesContinuousAcrossPlusMinusPi) {
  std::vector<Eigen::Vector3d> angles;
  for (int k = 0; k < 100; ++k) {
    const double truth = 0.1 * k;  // rad; passes ±π several times
    angles.emplace_back(std::remainder(truth, 2 * kPi), 0.0, std::remainder(-truth, 2 * kPi));
  }
  UnwrapAngles(angles);
  for (int k = 0; k < 100; ++k) {
    EXPECT_NEAR(angles[static_cast<std::size_t>(k)][0], 0.1 * k, 1e-12);
    EXPECT_NEAR(angles[static_cast<std::size_t>(k)][2], -0.1 * k, 1e-12);
  }
}

}  // namespace
}  // namespace rockfit::io
