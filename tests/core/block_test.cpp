#include "rockfit/core/block.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

TEST(Block, MassIsEightTimesDensityTimesHalfSizes) {
  const Block block = Block::FromDensity(0.05, 0.03, 0.2, 2692.0);
  EXPECT_DOUBLE_EQ(block.mass(), 8.0 * 2692.0 * 0.05 * 0.03 * 0.2);
  EXPECT_DOUBLE_EQ(block.density(), 2692.0);
}

TEST(Block, InertiaAboutComIsThatOfAHomogeneousCuboid) {
  // Θ of a cuboid with full edges (2b1, 2b2, 2h): m/12·((2b2)²+(2h)², …) = m/3·(b2²+h², …).
  const double b1 = 0.05, b2 = 0.03, h = 0.2, m = 1.0;
  const Block block = Block::FromMass(b1, b2, h, m);
  const Eigen::Matrix3d& theta = block.inertia_C_B();
  EXPECT_NEAR(theta(0, 0), m / 12.0 * (4 * b2 * b2 + 4 * h * h), 1e-15);
  EXPECT_NEAR(theta(1, 1), m / 12.0 * (4 * b1 * b1 + 4 * h * h), 1e-15);
  EXPECT_NEAR(theta(2, 2), m / 12.0 * (4 * b1 * b1 + 4 * b2 * b2), 1e-15);
  EXPECT_EQ(theta(0, 1), 0.0);
}

TEST(Block, VerticesFollowTheCyclicNumberingOfDesign) {
  const Block block = Block::FromMass(0.05, 0.03, 0.2, 1.0);
  EXPECT_TRUE(block.p_BV_B(1).isApprox(Eigen::Vector3d(-0.05, -0.03, 0)));
  EXPECT_TRUE(block.p_BV_B(2).isApprox(Eigen::Vector3d(-0.05, +0.03, 0)));
  EXPECT_TRUE(block.p_BV_B(3).isApprox(Eigen::Vector3d(+0.05, +0.03, 0)));
  EXPECT_TRUE(block.p_BV_B(4).isApprox(Eigen::Vector3d(+0.05, -0.03, 0)));
  EXPECT_TRUE(block.p_BV_B(0).isApprox(block.p_BV_B(4)));
  EXPECT_TRUE(block.p_BV_B(5).isApprox(block.p_BV_B(1)));
  EXPECT_TRUE(Block::AreNeighbours(1, 2));
  EXPECT_TRUE(Block::AreNeighbours(4, 1));
  EXPECT_FALSE(Block::AreNeighbours(1, 3));
  EXPECT_FALSE(Block::AreNeighbours(2, 2));
}

TEST(Block, RejectsNonPositiveOrNonFiniteGeometryWithAMessage) {
  EXPECT_THROW(Block::FromMass(0.0, 0.03, 0.2, 1.0), InvalidArgument);
  EXPECT_THROW(Block::FromMass(0.05, -0.03, 0.2, 1.0), InvalidArgument);
  EXPECT_THROW(Block::FromMass(0.05, 0.03, std::numeric_limits<double>::quiet_NaN(), 1.0), InvalidArgument);
  EXPECT_THROW(Block::FromDensity(0.05, 0.03, 0.2, std::numeric_limits<double>::infinity()), InvalidArgument);
  try {
    Block::FromMass(0.05, 0.03, -1.0, 1.0);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("h must be a positive finite"), std::string::npos);
  }
}

}  // namespace
}  // namespace rockfit::core
