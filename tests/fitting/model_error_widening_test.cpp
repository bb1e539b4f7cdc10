#include "rockfit/fitting/model_error_widening.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace rockfit::fitting {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(ModelErrorWidening, FactorIsOneWhereTheNoiseExplainsEpsilon) {
  EXPECT_EQ(ModelErrorWideningFactor(1.0, 0.5), 1.0);
  EXPECT_EQ(ModelErrorWideningFactor(0.8, 0.5), 1.0);  // ε below the floor: no negative model error
  EXPECT_EQ(ModelErrorWideningFactor(5.0, 0.0), 1.0);  // off
  EXPECT_EQ(ModelErrorWideningFactor(kNaN, 0.5), 1.0);
  EXPECT_EQ(ModelErrorWideningFactor(std::numeric_limits<double>::infinity(), 0.5), 1.0);
}

TEST(ModelErrorWidening, FactorAddsAModelErrorVarianceProportionalToItsShareOverTheNoise) {
  // r = 3: ε_model²/ε_noise² = 8; c = 0.5: f² = 1 + 0.25·8 = 3.
  EXPECT_NEAR(ModelErrorWideningFactor(3.0, 0.5), std::sqrt(3.0), 1e-15);
  // Far above the floor f approaches c·r: f/(c·r) = 1 + (1 − c²)/(2c²r²) + … = 1 + 1.5e-6 here.
  EXPECT_NEAR(ModelErrorWideningFactor(1000.0, 0.5) / 500.0, 1.0, 1e-5);
}

TEST(ModelErrorWidening, HalfWidthAddsTheFloorInQuadrature) {
  EXPECT_NEAR(WidenedHalfWidth(3.0, 1.0, 4.0), 5.0, 1e-15);
  EXPECT_NEAR(WidenedHalfWidth(1.5, 2.0, 0.0), 3.0, 1e-15);
}

TEST(ModelErrorWidening, IntervalWidensEachSideAboutTheValueAndStaysWithinTheBounds) {
  const Interval i = WidenInterval({0.9, 1.2}, 1.0, 2.0, 0.0, 0.0, 1.3);
  EXPECT_NEAR(i[0], 0.8, 1e-15);  // 1 − 2·0.1
  EXPECT_EQ(i[1], 1.3);           // 1 + 2·0.2 = 1.4, clipped to the upper bound
  const Interval open = WidenInterval({kNaN, 1.1}, 1.0, 1.0, 0.0, 0.0, 2.0);
  EXPECT_TRUE(std::isnan(open[0]));
  EXPECT_NEAR(open[1], 1.1, 1e-15);
}

}  // namespace
}  // namespace rockfit::fitting
