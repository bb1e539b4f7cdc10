// Euler angles ZYX (R_WB = Rz(φz)·Ry(φy)·Rx(φx), the x-IMU convention) and quaternion conventions.
#include "rockfit/core/attitude.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace rockfit::core {
namespace {

constexpr double kAngleTol = 1e-12;  // [rad] round-off of atan2/asin on unit-norm input

Eigen::Matrix3d Rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
Eigen::Matrix3d Ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d Rx(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }

TEST(Attitude, EulerZyxRecoversTheAnglesOfRzRyRx) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> yaw(-3.1, 3.1), pitch(-1.5, 1.5), roll(-3.1, 3.1);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d angles(yaw(rng), pitch(rng), roll(rng));
    const Eigen::Matrix3d R = Rz(angles[0]) * Ry(angles[1]) * Rx(angles[2]);
    EXPECT_NEAR((EulerZyxFromRotation(R) - angles).norm(), 0.0, kAngleTol);
    EXPECT_NEAR((QuaternionFromEulerZyx(angles).toRotationMatrix() - R).norm(), 0.0, kAngleTol);
    EXPECT_GE(QuaternionFromEulerZyx(angles).w(), 0.0);  // rockfit's quaternion convention
    EXPECT_NEAR((RotationFromEulerZyx(angles) - R).norm(), 0.0, kAngleTol);
  }
}

TEST(Attitude, ReleaseTiltIsNegativePitch) {
  // docs/design.md §2: the block tilted about edge V1V2 with the +x side lifted has φy = −α.
  const double alpha = 0.2;
  const Eigen::Vector3d euler = EulerZyxFromRotation(Ry(-alpha));
  EXPECT_NEAR(euler[1], -alpha, kAngleTol);
  // Ry(−α) lifts the +x end of the base: the body point (b1, 0, 0) goes up.
  EXPECT_GT((Ry(-alpha) * Eigen::Vector3d(1.0, 0.0, 0.0)).z(), 0.0);
}

TEST(Attitude, GimbalLockGivesFiniteAnglesOfTheSameRotation) {
  for (double pitch : {M_PI / 2, -M_PI / 2}) {
    const Eigen::Matrix3d R = Rz(0.3) * Ry(pitch) * Rx(0.1);
    const Eigen::Vector3d euler = EulerZyxFromRotation(R);
    ASSERT_TRUE(euler.allFinite());
    const Eigen::Matrix3d back = Rz(euler[0]) * Ry(euler[1]) * Rx(euler[2]);
    EXPECT_NEAR((back - R).norm(), 0.0, 1e-9);
  }
}

// The unit-quaternion conversion reads the same entries of R as the full matrix, formed the same way: the same
// angles bit for bit, also at the gimbal lock.
TEST(Attitude, EulerZyxOfAUnitQuaternionIsThatOfItsRotationMatrix) {
  std::mt19937 rng(20261127);
  std::normal_distribution<double> component(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(component(rng), component(rng), component(rng), component(rng)).normalized();
    const Eigen::Vector3d from_matrix = EulerZyxFromRotation(q.toRotationMatrix());
    EXPECT_EQ(EulerZyxFromUnitQuaternion(q), from_matrix) << i;
    const Eigen::Quaterniond scaled(3.0 * q.coeffs());
    EXPECT_NEAR((EulerZyxFromQuaternion(scaled) - from_matrix).norm(), 0.0, kAngleTol) << i;
  }
  for (double pitch : {M_PI / 2, -M_PI / 2}) {
    const Eigen::Quaterniond q = QuaternionFromEulerZyx(Eigen::Vector3d(0.3, pitch, 0.1));
    EXPECT_EQ(EulerZyxFromUnitQuaternion(q), EulerZyxFromRotation(q.toRotationMatrix()));
  }
}

TEST(Attitude, CanonicalUnitQuaternionFlipsTheSignOnly) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(-0.5, 0.5, -0.5, 0.5);
  EXPECT_EQ(CanonicalUnitQuaternion(q).coeffs(), (-q.coeffs()).eval());
  const Eigen::Quaterniond p(0.5, 0.5, -0.5, 0.5);
  EXPECT_EQ(CanonicalUnitQuaternion(p).coeffs(), p.coeffs());
}

TEST(Attitude, CanonicalQuaternionHasNonNegativeScalarAndTheSameRotation) {
  const Eigen::Quaterniond q(-0.5, 0.5, -0.5, 0.5);
  const Eigen::Quaterniond c = CanonicalQuaternion(q);
  EXPECT_GE(c.w(), 0.0);
  EXPECT_NEAR((c.toRotationMatrix() - q.toRotationMatrix()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(c.norm(), 1.0, 1e-15);
}

TEST(Attitude, YawQuaternionRotatesAboutTheVertical) {
  const Eigen::Vector3d x_W = YawQuaternion(M_PI / 2) * Eigen::Vector3d::UnitX();
  EXPECT_NEAR((x_W - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace rockfit::core
