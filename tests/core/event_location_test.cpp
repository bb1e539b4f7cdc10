// Event location on one step: sign changes, dips below zero and back within the step, guards that start
// on the surface.
#include "rockfit/core/event_location.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace rockfit::core {
namespace {

constexpr double kTimeTol = 1e-12;  // [s] the simulator's event tolerance

// A quadratic guard g(t) = (t − a)(t − b) + c with its derivative.
struct Quadratic {
  double a, b, c;
  GuardValue operator()(double t) const { return {(t - a) * (t - b) + c, 2.0 * t - a - b}; }
};

std::optional<double> Find(const Quadratic& g, double t0, double t1, RootPolisher& polisher) {
  return FindFirstDescent(g, t0, g(t0), t1, g(t1), polisher, kTimeTol);
}

TEST(RootPolisher, FindsASimpleRootToTheTolerance) {
  RootPolisher polisher;
  const auto root = polisher.Solve([](double x) { return x * x - 2.0; }, 0.0, 2.0, kTimeTol);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, std::sqrt(2.0), kTimeTol);
}

TEST(RootPolisher, RefusesABracketWithoutASignChange) {
  RootPolisher polisher;
  EXPECT_FALSE(polisher.Solve([](double x) { return x * x + 1.0; }, -1.0, 2.0, kTimeTol).has_value());
}

TEST(FindFirstDescent, LocatesASignChange) {
  RootPolisher polisher;
  // Positive at 0, negative at 0.5: the first root is 0.3.
  const auto t = Find({0.3, 0.7, 0.0}, 0.0, 0.5, polisher);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.3, kTimeTol);
}

TEST(FindFirstDescent, FindsADipThatReturnsAboveZeroWithinTheStep) {
  RootPolisher polisher;
  // g > 0 at both ends, below zero on (0.4, 0.6): the lift-off-and-land case.
  const auto t = Find({0.4, 0.6, 0.0}, 0.0, 1.0, polisher);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.4, kTimeTol);
}

TEST(FindFirstDescent, IgnoresADipThatStaysAboveZero) {
  RootPolisher polisher;
  EXPECT_FALSE(Find({0.5, 0.5, 1e-6}, 0.0, 1.0, polisher).has_value());
}

TEST(FindFirstDescent, GuardLeavingTheSurfaceCountsOnlyAfterItHasBeenPositive) {
  RootPolisher polisher;
  // g(0) = 0 rising, back to zero at 0.5 and negative after: the crossing is at 0.5, not at 0.
  const Quadratic falling{0.0, 0.5, 0.0};
  const auto neg = [&falling](double t) { return GuardValue{-falling(t).value, -falling(t).rate}; };
  const auto root = FindFirstDescent(neg, 0.0, neg(0.0), 0.8, neg(0.8), polisher, kTimeTol);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, 0.5, kTimeTol);
  // Rising and still positive at the end: nothing.
  EXPECT_FALSE(FindFirstDescent(neg, 0.0, neg(0.0), 0.4, neg(0.4), polisher, kTimeTol).has_value());
}

TEST(FindFirstDescent, GuardOnTheSurfaceMovingDownIsAnEventAtTheStart) {
  RootPolisher polisher;
  const Quadratic g{0.0, 0.5, 0.0};  // g(0) = 0, ġ(0) = −0.5
  const auto t = Find(g, 0.0, 0.2, polisher);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(*t, 0.0);
}

}  // namespace
}  // namespace rockfit::core
