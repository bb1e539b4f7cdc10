// The final stage (final_stage.hpp): its options' validation, that it never returns a higher (28) than it was
// given (from points near and far from the minimum of a disturbed analytic trial, fixed seed), that a fit with it
// ends no higher than the same fit without it, and that it runs nothing when it is off, from an infeasible point
// or with λ fixed.
#include "rockfit/fitting/final_stage.hpp"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "analytic_trial.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fitter.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeAnalyticTrial;
using testing::RealisticDisturbances;

// The message of the InvalidArgument that `options` throw, or "" when they are valid.
std::string ValidationMessage(const FinalStageOptions& options) {
  try {
    options.Validate();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(FinalStageOptions, TheDefaultsAreValidAndTheStageIsOffByDefault) {
  const FinalStageOptions options;
  EXPECT_EQ(ValidationMessage(options), "");
  EXPECT_FALSE(options.enabled);
  EXPECT_NO_THROW(FitOptions{}.Validate());
}

TEST(FinalStageOptions, EachBadOptionIsNamedInTheMessage) {
  const auto bad = [](auto change) {
    FinalStageOptions o;
    change(o);
    return ValidationMessage(o);
  };
  EXPECT_NE(bad([](FinalStageOptions& o) { o.lambda_half_width = 0.0; }).find("final_stage.lambda_half_width"), std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.lambda_half_width = std::nan(""); }).find("final_stage.lambda_half_width"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.lambda_lat_half_width = -1e-3; }).find("final_stage.lambda_lat_half_width"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.lambda_points = 0; }).find("final_stage.lambda_points"), std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.lambda_lat_points = 0; }).find("final_stage.lambda_lat_points"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.polished = -1; }).find("final_stage.polished"), std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.evaluations_per_polish = 0; }).find("final_stage.evaluations_per_polish"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.step_fraction = 0.0; }).find("final_stage.step_fraction"), std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.ridge_points = -1; }).find("final_stage.ridge_points"), std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.ridge_t0_half_width_s = 0.0; }).find("final_stage.ridge_t0_half_width_s"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.ridge_alpha_difference_rad = -1e-4; })
                .find("final_stage.ridge_alpha_difference_rad"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.lambda_lon_points = 0; }).find("final_stage.lambda_lon_points"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.lambda_lon_half_width = INFINITY; }).find("final_stage.lambda_lon_half_width"),
            std::string::npos);
  EXPECT_NE(bad([](FinalStageOptions& o) { o.rounds = 0; }).find("final_stage.rounds"), std::string::npos);
  // ridge_points 0 (no ridge grid) and one point per grid (no scan along that coordinate) are valid.
  EXPECT_EQ(bad([](FinalStageOptions& o) {
              o.ridge_points = 0;
              o.lambda_lat_points = 1;
            }),
            "");
  // The fitter's options check it too.
  FitOptions fit;
  fit.final_stage.lambda_points = 0;
  EXPECT_THROW(fit.Validate(), InvalidArgument);
}

TEST(FinalStage, NeverReturnsAHigherEpsilonThanItWasGiven) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(7));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  const Eigen::VectorXd truth = objective.FreeValues(trial.truth);
  FinalStageOptions options;
  options.enabled = true;
  options.rounds = 2;
  // Points around the truth at growing distances (fixed seed), the truth itself among them.
  std::mt19937_64 rng(20261127);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::VectorXd scale = (Eigen::VectorXd(5) << 2e-3, 2e-3, 0.05, 0.1, 0.02).finished();
  int improved = 0;
  for (int k = 0; k < 12; ++k) {
    Eigen::VectorXd x = truth;
    if (k > 0) {
      for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += (k / 4 + 1) * scale[i] * normal(rng);
    }
    x = x.cwiseMax(objective.FreeLower()).cwiseMin(objective.FreeUpper());
    const Evaluation given = objective.EvaluateFree(x);
    ASSERT_TRUE(given.feasible);
    const FinalStageResult r = RunFinalStage(objective, x, given.epsilon_rad_s, true, options, NelderMeadOptions{});
    EXPECT_LE(r.epsilon_rad_s, given.epsilon_rad_s) << "point " << k;
    // What it reports is (28) at the point it returns, and the given point itself when nothing was lower.
    EXPECT_EQ(r.epsilon_rad_s, objective.EvaluateFree(r.x).epsilon_rad_s) << "point " << k;
    if (r.improved) {
      ++improved;
      EXPECT_LT(r.epsilon_rad_s, given.epsilon_rad_s) << "point " << k;
    } else {
      EXPECT_EQ(r.x, x) << "point " << k;
    }
    EXPECT_GT(r.evaluations, 0) << "point " << k;
  }
  // The premise: the stage did find lower points from some of them.
  EXPECT_GT(improved, 0);
}

TEST(FinalStage, KeepsTheGivenPointWhenNothingIsLowerThanTheEpsilonItWasGiven) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(7));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  Eigen::VectorXd x = objective.FreeValues(trial.truth);
  x[2] += 0.1;  // λ off the truth: the stage finds lower (28) than at x, but not below 0
  FinalStageOptions options;
  options.enabled = true;
  const FinalStageResult r = RunFinalStage(objective, x, 0.0, true, options, NelderMeadOptions{});
  EXPECT_FALSE(r.improved);
  EXPECT_EQ(r.x, x);
  EXPECT_EQ(r.epsilon_rad_s, 0.0);
}

TEST(FinalStage, AFitWithItEndsNoHigherThanTheSameFitWithout) {
  const auto trial = MakeAnalyticTrial(0.19, 1.2, 1.5, 0.9, RealisticDisturbances(3));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  ParameterSet start = trial.truth;
  start[ParameterId::kT0].value += 0.001;
  start[ParameterId::kAlpha].value -= 0.001;
  start[ParameterId::kLambda].value += 0.05;
  start[ParameterId::kLambdaLon].value += 0.02;
  FitOptions options;
  options.global.enabled = false;
  options.intervals.method = IntervalMethod::kNone;
  const FitSummary without = Fit(objective, start, options);
  options.final_stage.enabled = true;
  const FitSummary with = Fit(objective, start, options);
  ASSERT_TRUE(without.feasible && with.feasible);
  EXPECT_LE(with.epsilon_rad_s, without.epsilon_rad_s);
  // The stages before it are the same; the stage is listed after them.
  ASSERT_EQ(with.stages.size(), without.stages.size() + 1);
  EXPECT_EQ(with.stages.back().name, "final");
  EXPECT_EQ(objective.Evaluate(with.parameters).epsilon_rad_s, with.epsilon_rad_s);
}

TEST(FinalStage, RunsNothingWhenOffFromAnInfeasiblePointOrWithLambdaFixed) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(7));
  ParameterSet parameters = trial.Bounded(BoundsSet::kEmpirical);
  const Objective objective = trial.MakeObjective(parameters);
  const Eigen::VectorXd x = objective.FreeValues(trial.truth);
  const double epsilon = objective.EvaluateFree(x).epsilon_rad_s;
  FinalStageOptions options;  // off
  FinalStageResult r = RunFinalStage(objective, x, epsilon, true, options, NelderMeadOptions{});
  EXPECT_EQ(r.evaluations, 0);
  EXPECT_EQ(r.x, x);
  options.enabled = true;
  r = RunFinalStage(objective, x, epsilon, false, options, NelderMeadOptions{});
  EXPECT_EQ(r.evaluations, 0);
  EXPECT_FALSE(r.feasible);
  parameters[ParameterId::kLambda].fixed = true;
  parameters[ParameterId::kLambda].value = trial.truth.value(ParameterId::kLambda);
  const Objective lambda_fixed = trial.MakeObjective(parameters);
  const Eigen::VectorXd y = lambda_fixed.FreeValues(trial.truth);
  r = RunFinalStage(lambda_fixed, y, lambda_fixed.EvaluateFree(y).epsilon_rad_s, true, options, NelderMeadOptions{});
  EXPECT_EQ(r.evaluations, 0);
  EXPECT_EQ(r.x, y);
}

}  // namespace
}  // namespace rockfit::fitting
