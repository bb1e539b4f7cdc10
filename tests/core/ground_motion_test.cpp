#include "rockfit/core/ground_motion.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

GroundMotion Ramp() {
  // a_x = 0, 1, 4, 2 m/s² at t = 0, 0.1, 0.2, 0.3 s; a_z = −a_x.
  std::vector<Eigen::Vector3d> a{{0, 0, 0}, {1, 0, -1}, {4, 0, -4}, {2, 0, -2}};
  return GroundMotion::Uniform(0.1, a);
}

TEST(GroundMotion, IsLinearBetweenSamplesAndExactAtThem) {
  const GroundMotion g = Ramp();
  EXPECT_EQ(g.Acceleration_W(0.1).x(), 1.0);
  EXPECT_EQ(g.Acceleration_W(0.3).x(), 2.0);
  EXPECT_NEAR(g.Acceleration_W(0.15).x(), 2.5, 1e-15);
  EXPECT_NEAR(g.Acceleration_W(0.275).x(), 2.5, 1e-15);
  EXPECT_NEAR(g.Acceleration_W(0.275).z(), -2.5, 1e-15);
}

TEST(GroundMotion, IsZeroOutsideTheRecord) {
  const GroundMotion g = Ramp();
  EXPECT_EQ(g.Acceleration_W(-1e-9).norm(), 0.0);
  EXPECT_EQ(g.Acceleration_W(0.3 + 1e-12).norm(), 0.0);
}

TEST(GroundMotion, NextBreakIsTheNextSampleTime) {
  const GroundMotion g = Ramp();
  EXPECT_DOUBLE_EQ(g.NextBreak(0.0), 0.1);
  EXPECT_DOUBLE_EQ(g.NextBreak(0.1), 0.2);  // on a break: the one after it
  EXPECT_DOUBLE_EQ(g.NextBreak(0.15), 0.2);
  EXPECT_DOUBLE_EQ(g.NextBreak(-2.0), 0.0);
  EXPECT_TRUE(std::isinf(g.NextBreak(0.3)));
}

TEST(GroundMotion, RotationTurnsAnXRecordToTheIncidenceDirection) {
  const GroundMotion g = Ramp().Rotated(std::atan2(3.0, 4.0));
  const Eigen::Vector3d a = g.Acceleration_W(0.2);
  EXPECT_NEAR(a.x(), 4.0 * 0.8, 1e-15);
  EXPECT_NEAR(a.y(), 4.0 * 0.6, 1e-15);
  EXPECT_EQ(a.z(), -4.0);
  EXPECT_NEAR(g.PeakHorizontal(), 4.0, 1e-15);
  EXPECT_NEAR(Ramp().Scaled(0.5).PeakVertical(), 2.0, 1e-15);
}

TEST(GroundMotion, LiftOffIsTheExactCrossingOfMinusG) {
  // a_z falls linearly from −1 to −4 over [0.1, 0.2]: g + a_z = 0 at a_z = −2.5, t = 0.15.
  EXPECT_NEAR(LiftOffTime(Ramp(), 2.5, 0.0, 1.0), 0.15, 1e-15);
  EXPECT_TRUE(std::isinf(LiftOffTime(Ramp(), 9.81, 0.0, 1.0)));
  EXPECT_EQ(LiftOffTime(Ramp(), 0.5, 0.2, 1.0), 0.2);  // already below −g
}

TEST(GroundMotion, RejectsBadSamples) {
  EXPECT_THROW(GroundMotion::Uniform(0.0, {{0, 0, 0}, {0, 0, 0}}), InvalidArgument);
  EXPECT_THROW(GroundMotion::Uniform(0.01, {{0, 0, 0}}), InvalidArgument);
  EXPECT_THROW(GroundMotion::Uniform(0.01, {{0, 0, 0}, {std::nan(""), 0, 0}}), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::core
