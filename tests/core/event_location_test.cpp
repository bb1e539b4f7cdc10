// Event location on one step: sign changes, dips below zero and back within the step, guards that start
// on the surface.
#include "rockfit/core/event_location.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

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

// A guard with the value and rate of f, counting its evaluations.
template <class F, class DF>
struct Counted {
  F f;
  DF df;
  mutable int evaluations = 0;
  GuardValue operator()(double t) const {
    ++evaluations;
    return {f(t), df(t)};
  }
};
template <class F, class DF>
Counted<F, DF> Count(F f, DF df) {
  return {f, df};
}

TEST(PolishCrossing, ReachesRoundOffOfARotatingHeightInFewEvaluations) {
  // A height under a steady rotation, cos t − 1/2, crosses zero at π/3; a 1 ms bracket around it, as an
  // integrator step would give.
  const auto g = Count([](double t) { return std::cos(t) - 0.5; }, [](double t) { return -std::sin(t); });
  const double a = M_PI / 3.0 - 4e-4;
  const double b = M_PI / 3.0 + 6e-4;
  const auto root = PolishCrossing(g, a, g(a), b, g(b));
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, M_PI / 3.0, 4.0 * std::numeric_limits<double>::epsilon());
  EXPECT_LE(g.evaluations - 2, 5);  // (the two ends are the caller's)
  // Brent's method on the value alone, to the simulator's former tolerance of 1e-12 s, for comparison.
  int brent_evaluations = 0;
  RootPolisher polisher;
  ASSERT_TRUE(polisher.Solve([&](double t) { ++brent_evaluations; return std::cos(t) - 0.5; }, a, b, kTimeTol));
  std::printf("evaluations inside the bracket: Newton %d (to round-off), Brent %d (to 1e-12 s)\n",
              g.evaluations - 2, brent_evaluations - 2);
}

TEST(PolishCrossing, FallsBackToBisectionWhereNewtonCycles) {
  // Newton's method on x³ − 2x + 2 cycles between 0 and 1; the real root is near −1.7693.
  const auto g = Count([](double x) { return x * x * x - 2.0 * x + 2.0; }, [](double x) { return 3.0 * x * x - 2.0; });
  const auto root = PolishCrossing(g, -3.0, g(-3.0), 1.0, g(1.0));
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(g.f(*root), 0.0, 1e-13);
  EXPECT_LT(g.evaluations, 80);
}

TEST(PolishCrossing, AWrongRateStillConvergesByBisection) {
  // A rate of zero (an undefined Newton step) everywhere: every step is a bisection.
  const auto g = Count([](double t) { return 0.3 - t; }, [](double) { return 0.0; });
  const auto root = PolishCrossing(g, 0.0, g(0.0), 1.0, g(1.0));
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, 0.3, 4.0 * std::numeric_limits<double>::epsilon());
}

TEST(PolishCrossing, RefusesABracketWithoutASignChangeAndANonFiniteGuard) {
  const auto positive = Count([](double t) { return 1.0 + t * t; }, [](double t) { return 2.0 * t; });
  EXPECT_FALSE(PolishCrossing(positive, -1.0, positive(-1.0), 1.0, positive(1.0)).has_value());
  const auto broken = Count([](double t) { return t < 0.5 ? 1.0 - t : std::nan(""); }, [](double) { return -1.0; });
  EXPECT_FALSE(PolishCrossing(broken, 0.0, GuardValue{1.0, -1.0}, 2.0, GuardValue{-1.0, -1.0}).has_value());
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

// A vertex height under a steady rotation, A cos(ω t) + C, over steps that turn the body by 0.5 rad at most.
struct RotatingHeight {
  double amplitude_m, offset_m, rate_rad_s;
  GuardValue operator()(double t) const {
    return {amplitude_m * std::cos(rate_rad_s * t) + offset_m, -amplitude_m * rate_rad_s * std::sin(rate_rad_s * t)};
  }
};

TEST(TimeBelowZeroNearMinimum, ADipThatClearsTheGroundNeedsNoEvaluationAndOneBelowIsFound) {
  int evaluations = 0;
  const RotatingHeight clears{0.05, 0.0501, 3.0};  // lowest point 0.1 mm above the ground at t = π/3 s
  const auto counted = [&](double t) { ++evaluations; return clears(t); };
  const double t0 = M_PI / 3.0 - 0.1, t1 = M_PI / 3.0 + 0.05;  // the step turns the body by 0.45 rad
  EXPECT_FALSE(TimeBelowZeroNearMinimum(counted, t0, clears(t0), t1, clears(t1), 1e-9).has_value());
  EXPECT_LE(evaluations, 3);
  for (double clearance_m : {1e-4, 1e-7, 1e-10}) {  // lowest point below the ground by this much
    const RotatingHeight dips{0.05, 0.05 - clearance_m, 3.0};
    const auto below = TimeBelowZeroNearMinimum(dips, t0, dips(t0), t1, dips(t1), 1e-9);
    ASSERT_TRUE(below.has_value()) << clearance_m;
    EXPECT_LT(dips(*below).value, 0.0) << clearance_m;
  }
}

TEST(FindFirstDescent, FindsTheFirstCrossingOfARotatingHeightThatDipsBelowTheGround) {
  RootPolisher polisher;
  const RotatingHeight dips{0.05, 0.0499, 3.0};  // below the ground for |3t − π| < acos(0.998)
  const double t0 = M_PI / 3.0 - 0.1, t1 = M_PI / 3.0 + 0.05;
  const auto root = FindFirstDescent(dips, t0, dips(t0), t1, dips(t1), polisher, kTimeTol);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, (M_PI - std::acos(0.998)) / 3.0, 1e-11);
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

TEST(FindFirstDescent, GuardOnTheSurfaceAtRestThatRisesAndFallsBackCrossesAfterItsMaximum) {
  // g = t² − 2t³: on the surface with no rate at t = 0, lifted by its acceleration, back below at t = 0.5
  // (a block that uplifts where the table's acceleration barely passes the threshold).
  RootPolisher polisher;
  const auto g = [](double t) { return GuardValue{t * t - 2.0 * t * t * t, 2.0 * t - 6.0 * t * t}; };
  const auto root = FindFirstDescent(g, 0.0, g(0.0), 0.8, g(0.8), polisher, kTimeTol);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, 0.5, kTimeTol);
  // At rest on the surface and pulled into it (g = −t²): an event at the start.
  const auto down = [](double t) { return GuardValue{-t * t, -2.0 * t}; };
  const auto at_once = FindFirstDescent(down, 0.0, down(0.0), 0.8, down(0.8), polisher, kTimeTol);
  ASSERT_TRUE(at_once.has_value());
  EXPECT_EQ(*at_once, 0.0);
}

// A cubic guard (t − r1)(t − r2)(t − r3) with its derivative.
struct Cubic {
  double r1, r2, r3;
  GuardValue operator()(double t) const {
    return {(t - r1) * (t - r2) * (t - r3), (t - r2) * (t - r3) + (t - r1) * (t - r3) + (t - r1) * (t - r2)};
  }
};

TEST(FindFirstDescent, FindsADipBetweenAMaximumAndAMinimumThatTheStepEndsDoNotShow) {
  RootPolisher polisher;
  // g = (t + 0.2)(t − 0.4)(t − 0.6) on [0, 1]: positive and rising at both ends, below zero on (0.4, 0.6).
  const Cubic g{-0.2, 0.4, 0.6};
  ASSERT_GT(g(0.0).value, 0.0);
  ASSERT_GT(g(0.0).rate, 0.0);
  ASSERT_GT(g(1.0).rate, 0.0);
  const auto t = FindFirstDescent(g, 0.0, g(0.0), 1.0, g(1.0), polisher, kTimeTol);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.4, 1e-14);
  // The same shape rising from the surface (a vertex that has just left the ground).
  const Cubic from_surface{0.0, 0.4, 0.6};
  const auto t_surface =
      FindFirstDescent(from_surface, 0.0, GuardValue{0.0, from_surface(0.0).rate}, 1.0, from_surface(1.0), polisher,
                       kTimeTol);
  ASSERT_TRUE(t_surface.has_value());
  EXPECT_NEAR(*t_surface, 0.4, 1e-14);
}

TEST(FindFirstDescent, AHopFarShorterThanTheStepFromTheSurfaceLandsAfterTheHopNotAtTheStart) {
  RootPolisher polisher;
  // g = t (t − 2e-7)(t − 0.6) on [0, 1]: leaves the surface rising, hops for 2e-7 of the step, stays below zero up
  // to 0.6 and ends above it, rising (a vertex after a chatter's facet impact). The landing is the hop's end: at
  // t = 0 the vertex still rises, and a landing there has no solution.
  const Cubic hop{0.0, 2e-7, 0.6};
  ASSERT_GT(hop(0.0).rate, 0.0);
  ASSERT_GT(hop(1.0).value, 0.0);
  const auto t = FindFirstDescent(hop, 0.0, GuardValue{0.0, hop(0.0).rate}, 1.0, hop(1.0), polisher, kTimeTol);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 2e-7, 1e-16);  // round-off of g near its root, 5e-10 relative
}

// A vertex that leaves the ground at t = 0 under a steady rotation and comes back within the step: its height is
// the hump A cos(ω (t − t_m)) − A cos(ω t_m), rising at 0, highest at t_m, landing at 2 t_m.
struct Hop {
  double amplitude_m, rate_rad_s, t_top_s;
  GuardValue operator()(double t) const {
    return {amplitude_m * (std::cos(rate_rad_s * (t - t_top_s)) - std::cos(rate_rad_s * t_top_s)),
            -amplitude_m * rate_rad_s * std::sin(rate_rad_s * (t - t_top_s))};
  }
  double landing_s() const { return 2.0 * t_top_s; }
  // Round-off of the landing time: a few units of round-off of the height over its rate at the landing.
  double landing_tol_s() const {
    const double eps = std::numeric_limits<double>::epsilon();
    return 8.0 * eps * std::max(1.0, landing_s()) + 8.0 * eps / (rate_rad_s * std::sin(rate_rad_s * t_top_s));
  }
};

TEST(HermiteLandingTime, IsTheLandingOfACubicGuardThatLeavesTheSurface) {
  // g = t (0.4 − t)(t + 0.5): zero and rising at 0, back to zero at 0.4 and below after; the Hermite cubic of a
  // cubic is the cubic itself.
  const auto g = [](double t) {
    return GuardValue{t * (0.4 - t) * (t + 0.5), (0.4 - t) * (t + 0.5) - t * (t + 0.5) + t * (0.4 - t)};
  };
  for (const double t1 : {0.5, 1.0, 3.0}) {
    const auto landing = HermiteLandingTime(0.0, g(0.0), t1, g(t1));
    ASSERT_TRUE(landing.has_value()) << t1;
    EXPECT_NEAR(*landing, 0.4, 1e-15) << t1;
  }
  // Not a guard leaving the surface: no landing.
  EXPECT_FALSE(HermiteLandingTime(0.0, GuardValue{1e-3, 1.0}, 1.0, g(1.0)).has_value());
  EXPECT_FALSE(HermiteLandingTime(0.0, GuardValue{0.0, -1.0}, 1.0, g(1.0)).has_value());
  EXPECT_FALSE(HermiteLandingTime(0.0, g(0.0), 0.3, g(0.3)).has_value());
}

TEST(FindFirstDescent, AVertexThatLiftsAndLandsWithinOneStepLandsAtTheClosedFormInFewEvaluations) {
  RootPolisher polisher;
  // Steps that turn the body by 0.45 rad (the simulator's bound is 0.5), hops from 1e-7 of the step to 0.95 of it.
  constexpr double kRate_rad_s = 3.0;
  constexpr double kStep_s = 0.15;
  for (const double fraction : {1e-7, 1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.95}) {
    const Hop hop{0.05, kRate_rad_s, 0.5 * fraction * kStep_s};
    const auto g = Count([&](double t) { return hop(t).value; }, [&](double t) { return hop(t).rate; });
    const auto root = FindFirstDescent(g, 0.0, GuardValue{0.0, hop(0.0).rate}, kStep_s, hop(kStep_s), polisher,
                                       kTimeTol);
    ASSERT_TRUE(root.has_value()) << fraction;
    EXPECT_NEAR(*root, hop.landing_s(), hop.landing_tol_s()) << fraction;
    EXPECT_LT(hop(*root).rate, 0.0) << fraction;  // a landing, not the start
    EXPECT_LE(g.evaluations, 4) << fraction;      // the search from the guard's maximum needed 7
  }
  // A hop that is not a cubic's shape (a hump with a long low tail): further from the Hermite landing, still found.
  const auto tail = Count([](double t) { return t * (0.4 - t) * std::exp(-8.0 * t); },
                          [](double t) { return ((0.4 - t) - t - 8.0 * t * (0.4 - t)) * std::exp(-8.0 * t); });
  const auto root = FindFirstDescent(tail, 0.0, tail(0.0), 1.0, tail(1.0), polisher, kTimeTol);
  ASSERT_TRUE(root.has_value());
  EXPECT_NEAR(*root, 0.4, 4.0 * std::numeric_limits<double>::epsilon());
}

// Newton's error bound ends the polish one evaluation early where the next step would be below round-off: over
// random crossings of rotating heights A cos(ω t) + C within steps that turn the body by up to 0.5 rad, the crossing
// is the closed form's to round-off, as without the bound, in fewer evaluations.
TEST(PolishCrossing, NewtonsErrorBoundSavesTheConfirmingEvaluationAndKeepsTheRootAtRoundOff) {
  std::mt19937 rng(20261127);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long with_bound = 0, without_bound = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double amplitude_m = 0.01 + 0.1 * unit(rng);
    const double rate_rad_s = 0.5 + 20.0 * unit(rng);
    const double crossing_rad = 0.05 + 2.9 * unit(rng);  // ω t at the crossing, where the height falls
    const RotatingHeight g{amplitude_m, -amplitude_m * std::cos(crossing_rad), rate_rad_s};
    const double t_cross = crossing_rad / rate_rad_s;
    const double turn_rad = 0.5 * unit(rng) + 1e-3;
    const double t0 = t_cross - unit(rng) * turn_rad / rate_rad_s;
    const double t1 = t0 + turn_rad / rate_rad_s;
    if (!(g(t0).value > 0.0 && g(t1).value < 0.0)) continue;
    int counted_plain = 0, counted_bound = 0;
    const auto plain = [&](double t) { ++counted_plain; return g(t); };
    const auto bounded = [&](double t) { ++counted_bound; return g(t); };
    const auto root_plain = PolishCrossing(plain, t0, g(t0), t1, g(t1));
    const auto root_bound = PolishCrossing(bounded, t0, g(t0), t1, g(t1), HermiteCurvatureBound(t0, g(t0), t1, g(t1)));
    ASSERT_TRUE(root_plain.has_value() && root_bound.has_value()) << trial;
    // Round-off of the crossing time: a few units of round-off of the height over its rate there.
    const double eps = std::numeric_limits<double>::epsilon();
    const double tol_s = 8.0 * eps * std::max(1.0, t_cross) + 8.0 * eps / (rate_rad_s * std::sin(crossing_rad));
    EXPECT_NEAR(*root_bound, t_cross, tol_s) << trial;
    EXPECT_NEAR(*root_bound, *root_plain, tol_s) << trial;
    EXPECT_LE(counted_bound, counted_plain) << trial;
    with_bound += counted_bound;
    without_bound += counted_plain;
  }
  std::printf("evaluations: %ld with Newton's error bound, %ld without\n", with_bound, without_bound);
  EXPECT_LT(with_bound, without_bound);
}

TEST(HermiteDipTime, IsEmptyForAGuardThatTurnsTwiceAboveZeroAndExactForACubic) {
  // (t + 0.2)(t − 0.4)(t − 0.6) + 0.02 turns twice but stays above zero: no dip.
  const auto above = [](double t) {
    const GuardValue g = Cubic{-0.2, 0.4, 0.6}(t);
    return GuardValue{g.value + 0.02, g.rate};
  };
  EXPECT_FALSE(HermiteDipTime(0.0, above(0.0), 1.0, above(1.0)).has_value());
  // For a cubic guard the Hermite cubic is the guard: its minimum, where the rate vanishes.
  const Cubic g{-0.2, 0.4, 0.6};
  const auto dip = HermiteDipTime(0.0, g(0.0), 1.0, g(1.0));
  ASSERT_TRUE(dip.has_value());
  EXPECT_NEAR(g(*dip).rate, 0.0, 1e-12);
  EXPECT_GT(*dip, 0.4);
  EXPECT_LT(*dip, 0.6);
}

// The cheap bound that skips the search never hides a dip: over random end values and rates, a cubic whose sampled
// minimum lies clearly below the negligible depth always has its dip reported, and a reported dip is below zero.
TEST(HermiteDipTime, FindsEveryDipOfRandomCubicsThatTheSampledCubicShows) {
  std::mt19937 rng(1127);
  std::uniform_real_distribution<double> value(-0.1, 1.0);
  std::uniform_real_distribution<double> rate(-8.0, 8.0);
  std::uniform_real_distribution<double> step(0.01, 2.0);
  int dips = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const GuardValue g0{value(rng), rate(rng)};
    const GuardValue g1{value(rng), rate(rng)};
    const double h = step(rng);
    // The Hermite cubic on s ∈ [0, 1], written independently of HermiteDipTime (basis functions).
    const auto cubic = [&](double s) {
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * g0.value + (s3 - 2 * s2 + s) * h * g0.rate + (-2 * s3 + 3 * s2) * g1.value +
             (s3 - s2) * h * g1.rate;
    };
    double sampled_min = std::numeric_limits<double>::infinity();
    for (int i = 1; i < 1000; ++i) sampled_min = std::min(sampled_min, cubic(i / 1000.0));
    const double change = std::max({std::abs(g0.value), std::abs(g1.value), h * std::abs(g0.rate), h * std::abs(g1.rate)});
    const std::optional<double> dip = HermiteDipTime(0.0, g0, h, g1);
    if (sampled_min < -1e-3 * change && sampled_min < std::min(g0.value, g1.value)) {
      ASSERT_TRUE(dip.has_value()) << trial;
      ++dips;
    }
    if (dip) {
      EXPECT_LT(cubic(*dip / h), 0.0) << trial;
    }
  }
  EXPECT_GT(dips, 1000);
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
