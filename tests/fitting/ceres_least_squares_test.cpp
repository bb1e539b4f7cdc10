// The Ceres back end and the covariance standard errors.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "analytic_trial.hpp"
#include "differenced_sensitivity_model.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "rockfit/fitting/uncertainty.hpp"
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

// Residual √w·(ω_m − ω_s) of every node at `at`, computed here from the nodes and the model run (not by the
// standard errors under test), with whether the node has weight.
struct NodeSeries {
  std::vector<Eigen::Vector3d> r;
  std::vector<bool> weighted;
};
NodeSeries SeriesAt(const Objective& objective, const ParameterSet& at) {
  ErrorNodes nodes;
  ModelOutput out;
  EXPECT_TRUE(objective.EvaluateDetailed(at, &nodes, &out).feasible);
  NodeSeries s;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    s.weighted.push_back(nodes.weight_s[i] > 0.0);
    s.r.push_back(std::sqrt(nodes.weight_s[i]) * (nodes.w_m_B[i] - out.w_B[i]));
  }
  return s;
}

TEST(Ceres, LeftOutSamplesCountNeitherInTheDegreesOfFreedomNorInTheLagOnePairs) {
  // Clipped samples (weight 0) are no residuals: the standard errors' degrees of freedom are 3 per node with
  // weight less the free parameters, and the lag-1 correlation pairs only nodes that are both weighted and
  // adjacent (no pair across a gap). Both computed here from the nodes; t0 held so that the residual slots of
  // the back end are exactly the nodes. The values recorded at the left-out samples then cannot matter.
  testing::SyntheticSignalOptions noise;
  noise.noise_rad_s = 0.03;
  noise.seed = 4;
  testing::AnalyticTrial trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, noise);
  MeasuredSignal& signal = trial.data.signal;
  signal.excluded.assign(signal.size(), false);
  std::size_t left_out = 0;
  for (std::size_t k : {150u, 151u, 152u, 153u, 220u, 300u, 301u}) {
    ASSERT_LT(signal.t_s[k], trial.t_end_s);
    ASSERT_GT(signal.t_s[k], 0.5);
    signal.excluded[k] = true;
    ++left_out;
  }
  const ParameterSet p = Free(trial, {ParameterId::kAlpha, ParameterId::kLambdaLat, ParameterId::kLambdaLon});
  const Objective objective = trial.MakeObjective(p);
  const Eigen::VectorXd x = objective.FreeValues(trial.truth);
  const StandardErrors se = ComputeStandardErrors(objective, x, CeresOptions{});
  ASSERT_TRUE(se.available) << se.message;

  const NodeSeries series = SeriesAt(objective, objective.WithFree(x));
  const auto weighted = static_cast<std::size_t>(std::count(series.weighted.begin(), series.weighted.end(), true));
  EXPECT_EQ(weighted, series.r.size() - left_out);
  EXPECT_EQ(se.weighted_nodes, weighted);
  EXPECT_EQ(se.dof, 3.0 * static_cast<double>(weighted) - 3.0);
  double lag0 = 0.0, lag1 = 0.0;
  for (std::size_t i = 0; i < series.r.size(); ++i) {
    if (!series.weighted[i]) continue;
    lag0 += series.r[i].squaredNorm();
    if (i > 0 && series.weighted[i - 1]) lag1 += series.r[i].dot(series.r[i - 1]);
  }
  const double rho = std::clamp(lag1 / lag0, 0.0, 0.99);
  constexpr double kRoundOff = 1e-12;  // relative: the same sums in another order
  EXPECT_NEAR(se.lag1_factor, (1.0 + rho) / (1.0 - rho), kRoundOff * se.lag1_factor);

  // Anything recorded at the left-out samples: the same standard errors, to the last digit.
  testing::AnalyticTrial other = trial;
  for (std::size_t k = 0; k < signal.size(); ++k) {
    if (signal.excluded[k]) other.data.signal.w_B[k] = Eigen::Vector3d(7.0, -3.0, 11.0);
  }
  const StandardErrors se_other = ComputeStandardErrors(other.MakeObjective(p), x, CeresOptions{});
  ASSERT_TRUE(se_other.available) << se_other.message;
  EXPECT_EQ(se_other.std_error, se.std_error);
  EXPECT_EQ(se_other.dof, se.dof);
}

TEST(Ceres, CensoredComponentsTheModelSatisfiesAreNoDegreesOfFreedom) {
  // A clipped axis records the rail; where the model is at or beyond it the censored misfit is 0 whatever the
  // model does nearby — no residual, so no degree of freedom. Where the model falls short it is a residual like
  // any other. Recorded values written here on y: half the model's ω_y (same sense: the model is beyond, the
  // observation satisfied) at four samples, twice it (the model falls short) at three; t0 held so that the slots
  // are the nodes. The degrees of freedom are then 3 per node less the four satisfied components less the free
  // parameters.
  testing::SyntheticSignalOptions noise;
  noise.noise_rad_s = 0.03;
  noise.seed = 4;
  testing::AnalyticTrial trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, noise);
  const ParameterSet p = Free(trial, {ParameterId::kAlpha, ParameterId::kLambdaLat, ParameterId::kLambdaLon});
  const Eigen::VectorXd x = trial.MakeObjective(p).FreeValues(trial.truth);
  ErrorNodes nodes;
  ModelOutput model;
  ASSERT_TRUE(trial.MakeObjective(p).EvaluateDetailed(trial.truth, &nodes, &model).feasible);
  MeasuredSignal& signal = trial.data.signal;
  signal.censored_axes.assign(signal.size(), 0);
  signal.excluded.assign(signal.size(), false);
  auto model_at = [&](std::size_t k) { return model.w_B[k - nodes.first_sample + 1]; };
  constexpr double kClearSense_rad_s = 0.05;  // |ω_y| of the chosen samples: far from 0, so the sense is clear
  std::vector<std::size_t> clear;  // interior samples where the model's ω_y is clearly of one sense
  for (std::size_t i = 1; i <= nodes.num_interior; ++i) {
    if (std::abs(model.w_B[i].y()) > kClearSense_rad_s) clear.push_back(nodes.first_sample + i - 1);
  }
  ASSERT_GT(clear.size(), 50u);
  constexpr std::uint8_t kY = 0b010;
  const std::size_t satisfied[] = {clear[10], clear[11], clear[12], clear[30]};
  const std::size_t short_of_it[] = {clear[45], clear[46], clear[47]};
  for (std::size_t k : satisfied) {
    signal.w_B[k].y() = 0.5 * model_at(k).y();
    signal.censored_axes[k] = kY;
    signal.excluded[k] = true;  // as the trial problem marks a clipped sample
  }
  for (std::size_t k : short_of_it) {
    signal.w_B[k].y() = 2.0 * model_at(k).y();
    signal.censored_axes[k] = kY;
    signal.excluded[k] = true;
  }
  const Objective objective = trial.MakeObjective(p);
  const StandardErrors se = ComputeStandardErrors(objective, x, CeresOptions{});
  ASSERT_TRUE(se.available) << se.message;
  EXPECT_EQ(se.weighted_nodes, nodes.size());  // a censored sample keeps its node and its weight
  EXPECT_EQ(se.dof, 3.0 * static_cast<double>(nodes.size()) - 4.0 - 3.0);

  // The intervals count the same way (WeightedResiduals).
  std::vector<Eigen::Vector3d> r;
  std::size_t unobserved = 0;
  ASSERT_TRUE(WeightedResiduals(objective, trial.truth, &r, nullptr, nullptr, &unobserved));
  EXPECT_EQ(r.size(), nodes.size());
  EXPECT_EQ(unobserved, 4u);
  EXPECT_EQ(ResidualDegreesOfFreedom(r.size(), unobserved, 3), se.dof);
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
  CeresOptions differences;
  differences.exact_jacobian = false;  // the exact Jacobian needs no steps (and is rank-deficient there)
  const StandardErrors se = ComputeStandardErrors(problem.objective, problem.objective.FreeValues(at), differences);
  EXPECT_FALSE(se.available);
  EXPECT_NE(se.message.find("cannot be evaluated"), std::string::npos) << se.message;
}


// The exact least-squares re-fit of a profile point (MinimizeSumOfSquaresExact, one parameter held, started from
// the truth moved off): it never ends above its warm start, and it lowers S where the start is off the ridge.
TEST(CeresExact, NeverEndsAboveItsWarmStart) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, testing::RealisticDisturbances(31));
  ParameterSet parameters = trial.Bounded(BoundsSet::kEmpirical);
  for (ParameterId id : kAllParameters) parameters[id].value = trial.truth.value(id);
  parameters[ParameterId::kTauEdge].fixed = true;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  // Offsets of a few standard errors: 1 ms, 1 mrad, 0.05, 0.02, 0.02.
  const PerParameter scale = {1e-3, 1e-3, 0.05, 0.02, 0.02, 0.0, 0.0};
  int lowered = 0;
  for (int i = 0; i < 12; ++i) {
    ParameterSet start = parameters;
    for (ParameterId id : {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kLambda, ParameterId::kLambdaLat,
                           ParameterId::kLambdaLon}) {
      start[id].value += scale[static_cast<std::size_t>(id)] * normal(rng);
    }
    const ParameterId held = kAllParameters[static_cast<std::size_t>(i) % 5];
    start[held].fixed = true;
    const Objective objective(trial.data.signal, trial.t_end_s,
                              std::make_shared<testing::DifferencedSensitivityModel>(trial.model), start);
    const ExactLeastSquaresResult r = MinimizeSumOfSquaresExact(objective, objective.FreeValues(start), 20);
    ASSERT_TRUE(r.exact_at_start && r.feasible) << i;
    EXPECT_LE(r.sum_sq, r.sum_sq_start) << i;
    EXPECT_GT(r.runs, 0) << i;
    if (r.sum_sq < 0.5 * r.sum_sq_start) ++lowered;
  }
  EXPECT_GE(lowered, 6);  // most starts lie well off the ridge of their held value
}

// Without the model's derivatives the exact re-fit does not search: it reports that, at the start, for the caller's
// fallback.
TEST(CeresExact, DoesNotSearchWithoutExactDerivatives) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, testing::RealisticDisturbances(32));
  ParameterSet parameters = trial.Bounded(BoundsSet::kEmpirical);
  for (ParameterId id : kAllParameters) parameters[id].value = trial.truth.value(id);
  parameters[ParameterId::kTauEdge].fixed = true;
  const Objective objective = trial.MakeObjective(parameters);
  Eigen::VectorXd x0 = objective.FreeValues(parameters);
  x0[1] += 1e-3;
  const ExactLeastSquaresResult r = MinimizeSumOfSquaresExact(objective, x0, 20);
  EXPECT_FALSE(r.exact_at_start);
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.x, x0);
  EXPECT_EQ(r.sum_sq, r.sum_sq_start);
  EXPECT_EQ(r.runs, 1);
}

}  // namespace
}  // namespace rockfit::fitting
