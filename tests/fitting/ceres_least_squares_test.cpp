// The Ceres back end and the covariance standard errors.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "analytic_trial.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeAnalyticTrial;

ParameterSet Free(const testing::AnalyticTrial& trial, std::vector<ParameterId> free) {
  ParameterSet p = trial.Bounded(BoundsSet::kEmpirical);
  for (ParameterId id : kAllParameters) {
    p[id].value = trial.truth.value(id);
    p[id].fixed = std::find(free.begin(), free.end(), id) == free.end();
  }
  return p;
}

TEST(Ceres, FindsTheTrueParametersOfNoiseFreeData) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective =
      trial.MakeObjective(Free(trial, {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kLambdaLat, ParameterId::kLambdaLon}));
  Eigen::VectorXd x0(4);
  x0 << 0.501, 0.198, -1.95, 0.62;
  const LocalResult r = MakeCeres(CeresOptions{})->Minimize(objective, x0);
  ASSERT_TRUE(r.feasible) << r.termination;
  EXPECT_EQ(r.termination.rfind("ceres: ", 0), 0u);
  // Tolerances: a small fraction of the difference steps (the Jacobian is a secant over ±step).
  EXPECT_NEAR(r.x[0], 0.5, 2e-4);
  EXPECT_NEAR(r.x[1], 0.2, 2e-4);
  EXPECT_NEAR(r.x[2], -2.0, 2e-3);
  EXPECT_NEAR(r.x[3], 0.6, 1e-3);
  EXPECT_EQ(r.epsilon_rad_s, objective.EvaluateFree(r.x).epsilon_rad_s);  // the reported cost is (28)
}

TEST(Ceres, KeepsParametersInsideTheirBounds) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  ParameterSet p = Free(trial, {ParameterId::kAlpha, ParameterId::kLambdaLon});
  p[ParameterId::kLambdaLon] = {0.9, 0.8, 1.0, false};  // truth 0.6 below the lower bound
  const Objective objective = trial.MakeObjective(p);
  const LocalResult r = MakeCeres(CeresOptions{})->Minimize(objective, objective.FreeValues(p));
  EXPECT_GE(r.x[1], 0.8);
  EXPECT_LE(r.x[1], 1.0);
  EXPECT_NEAR(r.x[1], 0.8, 1e-6);
}

TEST(Ceres, StandardErrorsBoundTheScatterOfEstimatesUnderWhiteNoise) {
  // The defining property of a standard error: over repeated noisy trials, the spread of the estimates. The
  // Jacobian of the covariance leaves out the jumps of residuals where a simulated impact crosses a sample
  // time (limited differences), i.e. part of the information on the impact times, so the standard errors are
  // conservative: here about twice the spread. They must not understate it, nor overstate it grossly.
  // 12 trials estimate a spread to ±25 %.
  constexpr int kTrials = 12;
  constexpr double kLowestRatio = 0.3;   // spread / standard error
  constexpr double kHighestRatio = 1.25;
  std::vector<double> alpha, se_alpha, lon, se_lon;
  for (int seed = 1; seed <= kTrials; ++seed) {
    testing::SyntheticSignalOptions noise;
    noise.noise_rad_s = 0.03;
    noise.seed = static_cast<std::uint64_t>(seed);
    const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, noise);
    const Objective objective = trial.MakeObjective(Free(trial, {ParameterId::kAlpha, ParameterId::kLambdaLon}));
    const LocalResult r = MakeCeres(CeresOptions{})->Minimize(objective, objective.FreeValues(trial.truth));
    ASSERT_TRUE(r.feasible);
    const StandardErrors se = ComputeStandardErrors(objective, r.x, CeresOptions{});
    ASSERT_TRUE(se.available) << se.message;
    alpha.push_back(r.x[0]);
    lon.push_back(r.x[1]);
    se_alpha.push_back(se.std_error[0]);
    se_lon.push_back(se.std_error[1]);
  }
  auto spread = [](const std::vector<double>& v, double truth) {
    double s = 0.0;
    for (double x : v) s += (x - truth) * (x - truth);
    return std::sqrt(s / static_cast<double>(v.size()));
  };
  auto mean = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s / static_cast<double>(v.size());
  };
  const double ratio_alpha = spread(alpha, 0.2) / mean(se_alpha);
  const double ratio_lon = spread(lon, 0.6) / mean(se_lon);
  EXPECT_GT(ratio_alpha, kLowestRatio);
  EXPECT_LT(ratio_alpha, kHighestRatio);
  EXPECT_GT(ratio_lon, kLowestRatio);
  EXPECT_LT(ratio_lon, kHighestRatio);
}

TEST(Ceres, StandardErrorsAreUnavailableForAParameterWithoutInfluence) {
  // λ_lat = 0: no lateral motion, no edge impact, λ does not act — the covariance is not defined.
  const auto trial = MakeAnalyticTrial(0.2, 0.8, 0.0, 0.6);
  const Objective objective = trial.MakeObjective(Free(trial, {ParameterId::kAlpha, ParameterId::kLambda}));
  const StandardErrors se = ComputeStandardErrors(objective, objective.FreeValues(trial.truth), CeresOptions{});
  EXPECT_FALSE(se.available);
  EXPECT_NE(se.message.find("rank-deficient"), std::string::npos) << se.message;
}

TEST(Ceres, StandardErrorsAreUnavailableWhereTheModelFailsWithinTheDifferenceSteps) {
  // α just below θ_c: the model runs at the point, but the difference step of α (0.5 mrad) tips the block over.
  // The Jacobian cannot be formed; that is a message, never a crash (it once read an empty sparse matrix).
  const testing::SynthTrial trial = testing::MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 7);
  const TrialProblem problem = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  ParameterSet at = trial.truth;
  at[ParameterId::kAlpha].value = std::atan(trial.block.b1() / trial.block.h()) - 1e-4;
  ASSERT_TRUE(problem.objective.Evaluate(at).feasible);
  const StandardErrors se = ComputeStandardErrors(problem.objective, problem.objective.FreeValues(at), CeresOptions{});
  EXPECT_FALSE(se.available);
  EXPECT_NE(se.message.find("cannot be evaluated"), std::string::npos) << se.message;
}

}  // namespace
}  // namespace rockfit::fitting
