// The prefix screen of the scans: its bound never exceeds (28) on the whole window, it rules out only points
// that cannot win, and a screened scan finds what the unscreened scan finds.
#include "rockfit/fitting/prefix_screen.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "rockfit/fitting/global_stage.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

// A recorded-like trial of the real simulator, its window ending 0.8 s after the release.
struct ScreenTrial {
  testing::SynthTrial trial = testing::MakeSynthTrial(0.19, 1.6, -1.8, 0.5);
  Objective objective{trial.signal, 1.8, std::make_shared<SimulatorModel>(trial.block), trial.truth};
};

// Random parameter values around the truth: t0 within ±10 ms, α within ±10 mrad, the impact parameters over
// their empirical bounds.
ParameterSet RandomPoint(const ParameterSet& truth, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ParameterSet p = truth;
  p[ParameterId::kT0].value += 0.02 * (unit(*rng) - 0.5);
  p[ParameterId::kAlpha].value += 0.02 * (unit(*rng) - 0.5);
  p[ParameterId::kLambda].value = -0.5 + 4.5 * unit(*rng);
  p[ParameterId::kLambdaLat].value = -6.0 + 12.0 * unit(*rng);
  p[ParameterId::kLambdaLon].value = -0.5 + 3.0 * unit(*rng);
  return p;
}

TEST(PrefixScreen, BoundNeverExceedsTheErrorOnTheWholeWindow) {
  const ScreenTrial t;
  std::mt19937_64 rng(7);
  for (double fraction : {0.3, 0.7}) {
    const PrefixScreen screen(t.objective, fraction);
    int feasible = 0;
    for (int k = 0; k < 40; ++k) {
      const ParameterSet p = RandomPoint(t.trial.truth, &rng);
      const PrefixBound bound = screen.Bound(p);
      const Evaluation full = t.objective.Evaluate(p);
      if (!bound.feasible) {
        EXPECT_FALSE(full.feasible) << "a failure within the prefix is a failure over the window";
        continue;
      }
      if (!full.feasible) continue;
      ++feasible;
      EXPECT_LE(bound.epsilon_lower_rad_s, full.epsilon_rad_s * (1.0 + 1e-9)) << "fraction " << fraction;
      EXPECT_GT(bound.epsilon_lower_rad_s, 0.0);
    }
    EXPECT_GT(feasible, 20);
  }
}

TEST(PrefixScreen, BoundIsThePrefixErrorScaledByTheCoveredTimesWithOrWithoutExcludedSamples) {
  // The bound ε(prefix)·W(prefix)/W(window), W the time the weights cover (ErrorNodes::weighted_duration_s), computed
  // here from the objective of the prefix window and nodes built for both windows: exactly, also with excluded
  // samples (whose weight both W leave out).
  ScreenTrial t;
  MeasuredSignal clipped = t.trial.signal;
  clipped.excluded.assign(clipped.size(), false);
  for (std::size_t k = 0; k < clipped.size(); k += 23) clipped.excluded[k] = true;
  const Objective with_excluded(clipped, 1.8, std::make_shared<SimulatorModel>(t.trial.block), t.trial.truth);
  constexpr double kFraction = 0.5;
  std::mt19937_64 rng(11);
  int compared = 0;
  for (const Objective* objective : {static_cast<const Objective*>(&t.objective), &with_excluded}) {
    const PrefixScreen screen(*objective, kFraction);
    const MeasuredSignal& signal = objective->signal();
    for (int k = 0; k < 6; ++k) {
      const ParameterSet p = k == 0 ? t.trial.truth : RandomPoint(t.trial.truth, &rng);
      const double t0 = p.value(ParameterId::kT0);
      const double prefix_end =
          *std::lower_bound(signal.t_s.begin(), signal.t_s.end(), t0 + kFraction * (objective->t_end_s() - t0));
      ErrorNodes window;
      ErrorNodes prefix;
      ASSERT_TRUE(BuildErrorNodes(signal, t0, objective->t_end_s(), &window));
      ASSERT_TRUE(BuildErrorNodes(signal, t0, prefix_end, &prefix));
      const Evaluation e = objective->WithWindowEnd(prefix_end).Evaluate(p);
      const PrefixBound bound = screen.Bound(p);
      EXPECT_EQ(bound.feasible, e.feasible);
      if (!e.feasible) continue;
      ++compared;
      EXPECT_EQ(bound.epsilon_lower_rad_s, e.epsilon_rad_s * prefix.weighted_duration_s() / window.weighted_duration_s());
    }
  }
  EXPECT_GT(compared, 4);
}

TEST(PrefixScreen, NeverRulesOutThePointThatSetTheBest) {
  const ScreenTrial t;
  const PrefixScreen screen(t.objective, 0.7);
  const Evaluation truth = t.objective.Evaluate(t.trial.truth);
  ASSERT_TRUE(truth.feasible);
  EXPECT_FALSE(screen.CannotBeat(t.trial.truth, truth.epsilon_rad_s));
}

TEST(PrefixScreen, OffOrWithoutAShorterPrefixGivesTheTrivialBoundWithoutARun) {
  const ScreenTrial t;
  const PrefixScreen off(t.objective, 0.0);
  const std::int64_t runs = t.objective.counters().runs();
  const PrefixBound bound = off.Bound(t.trial.truth);
  EXPECT_TRUE(bound.feasible);
  EXPECT_EQ(bound.epsilon_lower_rad_s, 0.0);
  EXPECT_FALSE(off.CannotBeat(t.trial.truth, 0.0));
  EXPECT_EQ(t.objective.counters().runs(), runs);
  EXPECT_THROW(PrefixScreen(t.objective, 1.0), std::exception);
  EXPECT_THROW(PrefixScreen(t.objective, -0.1), std::exception);
}

TEST(PrefixScreen, ScreenedScanFindsWhatTheFullScanFinds) {
  const ScreenTrial t;
  ParameterSet start = t.trial.truth;
  start[ParameterId::kLambda].value = 0.4;
  start[ParameterId::kLambdaLon].value = 1.1;
  for (ParameterId id : {ParameterId::kLambda, ParameterId::kLambdaLat, ParameterId::kLambdaLon}) {
    const ParameterSet full = ScanParameter(t.objective, start, id, 48);
    const ParameterSet screened = ScanParameter(t.objective, start, id, 48, 0.7);
    EXPECT_EQ(full.value(id), screened.value(id)) << Name(id);
  }
}

// Values with equal (28) (λ before the first edge impact does not act) leave the start where it was, as a scan that
// runs every value over the whole window does: only a lower (28) moves it.
TEST(PrefixScreen, ScreenedScanOfAParameterThatDoesNotActKeepsTheStart) {
  const ScreenTrial t;
  const std::optional<double> t1 = FirstImpactTime(t.objective, t.trial.truth);
  ASSERT_TRUE(t1.has_value());
  const Objective before_impact = t.objective.WithWindowEnd(*t1 - 0.01);
  ParameterSet start = t.trial.truth;
  start[ParameterId::kLambda].value = 0.4;
  for (double fraction : {0.0, 0.7}) {
    const ParameterSet scanned = ScanParameter(before_impact, start, ParameterId::kLambda, 48, fraction);
    EXPECT_EQ(scanned.value(ParameterId::kLambda), 0.4) << "prefix fraction " << fraction;
  }
}

TEST(PrefixScreen, ScreenedArgminIsTheArgminOfTheWholeWindowInAnyThreadCount) {
  const ScreenTrial t;
  std::mt19937_64 rng(3);
  std::vector<ParameterSet> points;
  for (int k = 0; k < 60; ++k) points.push_back(RandomPoint(t.trial.truth, &rng));
  points.push_back(t.trial.truth);
  std::optional<std::size_t> argmin;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Evaluation e = t.objective.Evaluate(points[i]);
    if (e.feasible && (!argmin || e.epsilon_rad_s < t.objective.Evaluate(points[*argmin]).epsilon_rad_s)) argmin = i;
  }
  ASSERT_TRUE(argmin.has_value());
  for (int threads : {1, 3}) {
    double epsilon = 0.0;
    const std::optional<std::size_t> screened = ScreenedArgmin(t.objective, points, 0.7, threads, &epsilon);
    ASSERT_TRUE(screened.has_value());
    EXPECT_EQ(*screened, *argmin) << threads << " threads";
    EXPECT_EQ(epsilon, t.objective.Evaluate(points[*argmin]).epsilon_rad_s);
  }
}

}  // namespace
}  // namespace rockfit::fitting
