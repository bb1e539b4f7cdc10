#include "rockfit/io/ground_motion_input.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

TEST(GroundMotionInput, IncidenceAngleTurnsTheComponentsAboutTheVertical) {
  GroundMotionAssembly a;
  a.horizontal_1 = RecordComponent{"h1", 0.01, {0.0, 1.0, 0.0}};
  a.horizontal_2 = RecordComponent{"h2", 0.01, {0.0, 0.0, 2.0}};
  a.vertical = RecordComponent{"v", 0.01, {0.0, 0.5}};
  a.incidence_rad = M_PI / 6;
  const AssembledGroundMotion g = AssembleGroundMotion(a);
  EXPECT_NEAR(g.ground.Sample(1).x(), std::cos(M_PI / 6), 1e-15);  // h1 along (cos β, sin β, 0)
  EXPECT_NEAR(g.ground.Sample(1).y(), std::sin(M_PI / 6), 1e-15);
  EXPECT_NEAR(g.ground.Sample(2).x(), -2.0 * std::sin(M_PI / 6), 1e-15);  // h2 along (−sin β, cos β, 0)
  EXPECT_NEAR(g.ground.Sample(2).y(), 2.0 * std::cos(M_PI / 6), 1e-15);
  EXPECT_EQ(g.ground.Sample(1).z(), 0.5);
  EXPECT_EQ(g.ground.Sample(2).z(), 0.0);  // the shorter vertical is padded
  EXPECT_EQ(g.notes.size(), 1u);
}

TEST(GroundMotionInput, TargetPgaScalesTheHorizontalResultant) {
  GroundMotionAssembly a;
  a.horizontal_1 = RecordComponent{"h1", 0.01, {0.0, 3.0, -1.0}};
  a.horizontal_2 = RecordComponent{"h2", 0.01, {0.0, 4.0, 0.0}};
  a.vertical = RecordComponent{"v", 0.01, {0.0, 1.0, 0.0}};
  a.target_pga_m_s2 = 2.0;
  const AssembledGroundMotion g = AssembleGroundMotion(a);
  EXPECT_NEAR(g.scale, 0.4, 1e-15);
  EXPECT_NEAR(g.ground.PeakHorizontal(), 2.0, 1e-15);
  EXPECT_NEAR(g.ground.PeakVertical(), 0.4, 1e-15);
}

TEST(GroundMotionInput, ComponentsWithDifferentStepsAreABadInput) {
  GroundMotionAssembly a;
  a.horizontal_1 = RecordComponent{"h1.AT2", 0.01, {0.0, 1.0}};
  a.vertical = RecordComponent{"v.AT2", 0.02, {0.0, 1.0}};
  EXPECT_THROW(AssembleGroundMotion(a), BadInput);
  EXPECT_THROW(AssembleGroundMotion(GroundMotionAssembly{}), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
