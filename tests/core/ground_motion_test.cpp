#include "rockfit/core/ground_motion.hpp"

#include <cmath>
#include <limits>
#include <vector>

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

TEST(GroundMotion, RotatedAndScaledViewIsRotatedThenScaledBitForBitAtEveryTime) {
  std::vector<Eigen::Vector3d> a{{0.3, -1.7, 0.2}, {1.1, 0.4, -0.9}, {-2.3, 0.7, 0.1}, {0.9, -0.2, 0.6}};
  const GroundMotion g = GroundMotion::Uniform(0.01, a);
  for (const double beta : {0.0, 0.4, 2.9, -1.3}) {
    const GroundMotion view = g.RotatedAndScaled(beta, 1.7);
    const GroundMotion copy = g.Rotated(beta).Scaled(1.7);
    EXPECT_EQ(view.PeakHorizontal(), copy.PeakHorizontal());
    EXPECT_EQ(view.PeakVertical(), copy.PeakVertical());
    for (double t = -0.005; t < 0.04; t += 0.0013) {
      EXPECT_EQ(view.Acceleration_W(t), copy.Acceleration_W(t)) << "beta " << beta << ", t " << t;
    }
    EXPECT_EQ(view.samples_W(), copy.samples_W());
    // A view of a view is materialised in the same order.
    EXPECT_EQ(view.RotatedAndScaled(0.2, 0.5).samples_W(), view.Rotated(0.2).Scaled(0.5).samples_W());
  }
  EXPECT_EQ(g.samples_W(), a);  // the record itself is unchanged
  EXPECT_THROW(g.RotatedAndScaled(std::nan(""), 1.0), InvalidArgument);
  EXPECT_THROW(g.RotatedAndScaled(0.0, std::numeric_limits<double>::infinity()), InvalidArgument);
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
