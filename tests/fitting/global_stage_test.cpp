// The global stage: finds the right basin from a start in the wrong one, deterministically.
#include "rockfit/fitting/global_stage.hpp"

#include <gtest/gtest.h>

#include "analytic_trial.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeAnalyticTrial;

// Noise-free data: the global stage must land in the basin of the truth; a local search finishes the job.
constexpr double kLambdaLatBasin = 0.3;

// A disturbed trial (noise, ringing, drift), its objective over the empirical bounds and a rough start: the
// stage runs compared with each other below.
struct DisturbedStage {
  testing::AnalyticTrial trial = MakeAnalyticTrial(0.18, 1.2, 1.5, 0.9, testing::RealisticDisturbances());
  Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  Eigen::VectorXd start = objective.FreeValues(trial.RoughStart());
};

TEST(GlobalStage, FindsTheSignOfLambdaLatFromAStartWithTheWrongSign) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  ParameterSet start = trial.RoughStart();
  start[ParameterId::kLambdaLat].value = 2.0;
  FitOptions options;
  const GlobalStageResult g = RunGlobalStage(objective, objective.FreeValues(start), options);
  ASSERT_TRUE(g.feasible);
  const ParameterSet found = objective.WithFree(g.best_x);
  EXPECT_NEAR(found.value(ParameterId::kLambdaLat), -2.0, kLambdaLatBasin);
  EXPECT_LT(g.best_epsilon_rad_s, objective.Evaluate(start).epsilon_rad_s);
  EXPECT_GT(g.first_window_end_s, trial.truth.value(ParameterId::kT0));
  EXPECT_LT(g.first_window_end_s, trial.t_end_s);
  EXPECT_GE(g.num_continued, 1);
}

TEST(GlobalStage, GivesTheSameResultWithOneThreadAndWithMany) {
  const DisturbedStage stage;
  FitOptions one, many;
  one.num_threads = 1;
  many.num_threads = 4;
  const GlobalStageResult a = RunGlobalStage(stage.objective, stage.start, one);
  const GlobalStageResult b = RunGlobalStage(stage.objective, stage.start, many);
  EXPECT_EQ(a.best_x, b.best_x);
  EXPECT_EQ(a.best_epsilon_rad_s, b.best_epsilon_rad_s);
}

// The scan screen only skips runs that cannot change a scan: the stage with and without it ends at the same point
// (the stop rule off in both).
TEST(GlobalStage, ScanScreenLeavesTheResultUnchanged) {
  const DisturbedStage stage;
  FitOptions screened, unscreened;
  screened.num_threads = unscreened.num_threads = 1;
  screened.global.continuation_prune_ratio = unscreened.global.continuation_prune_ratio = 0.0;
  unscreened.global.scan_prefix_fraction = 0.0;
  const GlobalStageResult a = RunGlobalStage(stage.objective, stage.start, screened);
  const GlobalStageResult b = RunGlobalStage(stage.objective, stage.start, unscreened);
  EXPECT_EQ(a.best_x, b.best_x);
  EXPECT_EQ(a.best_epsilon_rad_s, b.best_epsilon_rad_s);
}

// The stop rule drops carried starts that fall far behind; the one that wins on the full window is not among
// them on this trial, and fewer starts reach the full window or the same number do.
TEST(GlobalStage, StopRuleKeepsTheBestStart) {
  const DisturbedStage stage;
  FitOptions pruned, kept;
  kept.global.continuation_prune_ratio = 0.0;
  pruned.global.refine = kept.global.refine = false;
  const GlobalStageResult a = RunGlobalStage(stage.objective, stage.start, pruned);
  const GlobalStageResult b = RunGlobalStage(stage.objective, stage.start, kept);
  EXPECT_LE(a.num_continued, b.num_continued);
  EXPECT_EQ(a.best_epsilon_rad_s, b.best_epsilon_rad_s);
}

TEST(GlobalStage, SamplingBoxNarrowsT0AndAlphaAroundTheEstimateWithinTheBounds) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  Eigen::VectorXd estimate = objective.FreeValues(trial.truth);
  estimate[1] = 0.295;  // α near its upper bound 0.3
  Eigen::VectorXd lower, upper;
  GlobalStageOptions options;
  GlobalSamplingBox(objective, estimate, options, &lower, &upper);
  EXPECT_DOUBLE_EQ(lower[0], 0.5 - options.t0_halfwidth_s);
  EXPECT_DOUBLE_EQ(upper[0], 0.5 + options.t0_halfwidth_s);
  EXPECT_DOUBLE_EQ(lower[1], 0.295 - options.alpha_halfwidth_rad);
  EXPECT_DOUBLE_EQ(upper[1], 0.3);
  EXPECT_EQ(lower[3], -6.0);  // λ_lat over its whole bounds
  EXPECT_EQ(upper[3], 6.0);
}

}  // namespace
}  // namespace rockfit::fitting
