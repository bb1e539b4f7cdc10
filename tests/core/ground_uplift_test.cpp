#include "rockfit/core/ground_uplift.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace rockfit::core {
namespace {

constexpr double kG = 9.81;

TEST(GroundUplift, PlanarMarginIsAccelerationTimesHeightMinusGTimesHalfWidth) {
  const Block block = Block::FromDensity(0.05, 0.03, 0.2, 2500);
  const auto m = UpliftMargins(block, Eigen::Quaterniond::Identity(), kG, {2.0, 0.0, 0.0});
  // Edge V1V2 (x = −b1, inward +x) is loaded by a_x > 0; V3V4 the opposite way.
  EXPECT_NEAR(m[0], 0.2 * 2.0 - 0.05 * kG, 1e-15);
  EXPECT_NEAR(m[2], -0.2 * 2.0 - 0.05 * kG, 1e-15);
  EXPECT_NEAR(m[1], -0.03 * kG, 1e-15);
}

TEST(GroundUplift, RampUpliftsAtTheExactThresholdTime) {
  const Block block = Block::FromDensity(0.05, 0.03, 0.2, 2500);
  // a_x rises linearly from 0 to 10 m/s² over 1 s: uplift at a_x = g b1/h.
  const GroundMotion ramp = GroundMotion::Uniform(1.0, {{0, 0, 0}, {10, 0, 0}});
  const auto up = NextUplift(block, ramp, Eigen::Quaterniond::Identity(), kG, 0.0, 5.0);
  ASSERT_TRUE(up.has_value());
  EXPECT_NEAR(up->t_s, kG * 0.05 / 0.2 / 10.0, 1e-15);
  EXPECT_EQ(up->contact, Contact::Edge(1, 2));
}

TEST(GroundUplift, DiagonalAccelerationStartsVertexRockingDirectly) {
  const Block block = Block::FromDensity(0.05, 0.03, 0.2, 2500);
  // Along (b1, b2): both side margins vanish together at |a_x| = g b1/h; the block pivots on V1 = (−b1, −b2).
  const double s = 2.0 * kG / 0.2;
  const GroundMotion ramp = GroundMotion::Uniform(1.0, {{0, 0, 0}, {s * 0.05, s * 0.03, 0}});
  const auto up = NextUplift(block, ramp, Eigen::Quaterniond::Identity(), kG, 0.0, 5.0);
  ASSERT_TRUE(up.has_value());
  EXPECT_EQ(up->contact, Contact::Vertex(1));
  EXPECT_NEAR(up->t_s, 0.5, 1e-12);
}

TEST(GroundUplift, YawTurnsTheEdgesWithTheBlock) {
  const Block block = Block::FromDensity(0.05, 0.03, 0.2, 2500);
  // The block turned by 90°: a world +y acceleration now loads its edge V1V2.
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const GroundMotion ramp = GroundMotion::Uniform(1.0, {{0, 0, 0}, {0, 10, 0}});
  const auto up = NextUplift(block, ramp, yaw, kG, 0.0, 5.0);
  ASSERT_TRUE(up.has_value());
  EXPECT_EQ(up->contact, Contact::Edge(1, 2));
}

TEST(GroundUplift, StaysAtRestBelowTheThresholdAndAfterTheRecord) {
  const Block block = Block::FromDensity(0.05, 0.03, 0.2, 2500);
  const double a = (1.0 - 1e-9) * kG * 0.05 / 0.2;
  const GroundMotion steady = GroundMotion::Uniform(1.0, {{a, 0, 0}, {a, 0, 0}});
  EXPECT_FALSE(NextUplift(block, steady, Eigen::Quaterniond::Identity(), kG, 0.0, 100.0).has_value());
}

}  // namespace
}  // namespace rockfit::core
