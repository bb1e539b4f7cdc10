// The fit pipeline on the analytic test model: every method reaches the error of the truth, bounds and
// identifiability are reported, failures are counted, the summary carries the documented fields.
#include "rockfit/fitting/fitter.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analytic_trial.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeAnalyticTrial;
using testing::RealisticDisturbances;

// The acceptance criterion of docs/design.md §12: ε no larger than 1.05 × ε at the true parameters.
constexpr double kEpsilonRatio = 1.05;

struct Tolerances {
  double t0_s = 2e-3;
  double alpha_rad = 2e-3;
  double lambda_lon = 0.03;
  double lambda_lat_relative = 0.10;
  double lambda = 0.1;
};

void ExpectRecovered(const FitSummary& s, const ParameterSet& truth, const Tolerances& tol = {}) {
  EXPECT_NEAR(s.parameters.value(ParameterId::kT0), truth.value(ParameterId::kT0), tol.t0_s);
  EXPECT_NEAR(s.parameters.value(ParameterId::kAlpha), truth.value(ParameterId::kAlpha), tol.alpha_rad);
  EXPECT_NEAR(s.parameters.value(ParameterId::kLambdaLon), truth.value(ParameterId::kLambdaLon), tol.lambda_lon);
  const double lat = truth.value(ParameterId::kLambdaLat);
  EXPECT_NEAR(s.parameters.value(ParameterId::kLambdaLat), lat, tol.lambda_lat_relative * std::abs(lat));
  EXPECT_NEAR(s.parameters.value(ParameterId::kLambda), truth.value(ParameterId::kLambda), tol.lambda);
}

class FitMethods : public ::testing::TestWithParam<FitMethod> {};

TEST_P(FitMethods, ReachTheErrorOfTheTrueParametersFromARoughStart) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances());
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options;
  options.method = GetParam();
  const FitSummary s = Fit(objective, trial.RoughStart(), options);
  ASSERT_TRUE(s.feasible) << s.FullReport();
  EXPECT_LE(s.epsilon_rad_s, kEpsilonRatio * objective.Evaluate(trial.truth).epsilon_rad_s) << s.FullReport();
  EXPECT_LT(s.epsilon_rad_s, s.epsilon_initial_rad_s);
  ExpectRecovered(s, trial.truth);
  EXPECT_EQ(s.method, GetParam());
  EXPECT_GT(s.simulations, 0);
  EXPECT_GT(s.simulations_per_second, 0.0);
  // The reported ε is (28) at the reported parameters, whichever back end produced them.
  EXPECT_EQ(s.epsilon_rad_s, objective.Evaluate(s.parameters).epsilon_rad_s);
  for (ParameterId id : objective.free_ids()) {
    EXPECT_TRUE(std::isfinite(s.std_error[static_cast<std::size_t>(id)])) << Name(id);
  }
}

// A start a few resolutions off the truth of an analytic trial, fitted without the global stage; beside it ε at
// the truth.
struct NearbyStartFit {
  FitSummary summary;
  double truth_epsilon_rad_s = 0.0;
};

NearbyStartFit FitFromNearbyStart(FitOptions options) {
  const auto trial = MakeAnalyticTrial(0.19, 1.2, 1.5, 0.9, RealisticDisturbances(3));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  ParameterSet start = trial.truth;
  start[ParameterId::kT0].value += 0.001;
  start[ParameterId::kAlpha].value -= 0.001;
  start[ParameterId::kLambdaLon].value += 0.02;
  options.global.enabled = false;
  return {Fit(objective, start, options), objective.Evaluate(trial.truth).epsilon_rad_s};
}

TEST_P(FitMethods, WithoutTheGlobalStageStillImproveFromANearbyStart) {
  FitOptions options;
  options.method = GetParam();
  const NearbyStartFit f = FitFromNearbyStart(options);
  EXPECT_LE(f.summary.epsilon_rad_s, kEpsilonRatio * f.truth_epsilon_rad_s) << f.summary.FullReport();
  ASSERT_EQ(f.summary.stages.size(), GetParam() == FitMethod::kAuto ? 3u : 2u);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, FitMethods,
                         ::testing::Values(FitMethod::kNelderMead, FitMethod::kCeres, FitMethod::kAuto),
                         [](const auto& info) { return std::string(info.param == FitMethod::kNelderMead ? "NelderMead"
                                                                   : info.param == FitMethod::kCeres  ? "Ceres"
                                                                                                      : "Auto"); });

std::vector<std::string> StageNames(const FitSummary& s) {
  std::vector<std::string> names;
  for (const StageReport& stage : s.stages) names.push_back(stage.name);
  return names;
}

TEST(Fit, AutoFallsBackToNelderMeadWhereTheModelGivesNoExactDerivatives) {
  // The analytic test model gives no derivatives: the Ceres stage differences them, so Nelder–Mead follows it.
  FitOptions options;
  options.intervals.method = IntervalMethod::kNone;
  options.ceres.exact_jacobian = true;
  options.auto_exact_ceres_first = true;
  const FitSummary s = FitFromNearbyStart(options).summary;
  EXPECT_EQ(StageNames(s), (std::vector<std::string>{"start", "ceres", "nelder-mead"})) << s.FullReport();
}

TEST(Fit, AutoUnderAGyroScaleEstimateRunsNelderMeadThenTheDifferencedCeres) {
  // The model's derivatives leave out the projected scale: no exact Jacobian, and `auto` as without one.
  FitOptions options;
  options.intervals.method = IntervalMethod::kNone;
  options.gyro_scale = GyroScaleMode::kCommon;
  options.ceres.exact_jacobian = true;
  options.auto_exact_ceres_first = true;
  EXPECT_NO_THROW(options.Validate());
  const FitSummary s = FitFromNearbyStart(options).summary;
  EXPECT_EQ(StageNames(s), (std::vector<std::string>{"start", "nelder-mead", "ceres"})) << s.FullReport();
}

TEST(Fit, SoftL1FractionOfTheExactCeresStageMustBePositive) {
  FitOptions options;
  options.auto_soft_l1_fraction = 0.0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
}

TEST(Fit, TheoreticalBoundsRecoverParametersInsideThem) {
  const auto trial = MakeAnalyticTrial(0.2, 0.7, -0.8, 0.5, RealisticDisturbances(5));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kTheoretical));
  ParameterSet start = trial.Bounded(BoundsSet::kTheoretical);
  start[ParameterId::kT0].value += 0.004;
  start[ParameterId::kAlpha].value = 0.195;
  const FitSummary s = Fit(objective, start, FitOptions{});
  EXPECT_LE(s.epsilon_rad_s, kEpsilonRatio * objective.Evaluate(trial.truth).epsilon_rad_s) << s.FullReport();
  ExpectRecovered(s, trial.truth);
  EXPECT_FALSE(s.HasWarning(WarningKind::kAtBound)) << s.FullReport();
}

TEST(Fit, AParameterBeyondTheTheoreticalBoundEndsAtTheBoundWithAWarning) {
  // λ_lon = 1.3 violates (27), as the paper's fitted values often do (Sect. 5.3).
  const auto trial = MakeAnalyticTrial(0.2, 0.7, -0.8, 1.3, RealisticDisturbances(6));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kTheoretical));
  const FitSummary s = Fit(objective, trial.Bounded(BoundsSet::kTheoretical), FitOptions{});
  EXPECT_NEAR(s.parameters.value(ParameterId::kLambdaLon), 1.0, 1e-5);
  EXPECT_TRUE(s.at_bound[static_cast<std::size_t>(ParameterId::kLambdaLon)]);
  EXPECT_TRUE(s.HasWarning(WarningKind::kAtBound, "lambda_lon")) << s.FullReport();
  EXPECT_TRUE(std::isnan(s.std_error[static_cast<std::size_t>(ParameterId::kLambdaLon)]));
}

TEST(Fit, SaysLambdaIsNotIdentifiableWithoutEdgeImpacts) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, 0.0, 0.6, RealisticDisturbances(7));
  ParameterSet parameters = trial.Bounded(BoundsSet::kEmpirical);
  parameters[ParameterId::kLambdaLat] = {0.0, -6.0, 6.0, true};  // as the paper did for blocks 7 and 8
  const Objective objective = trial.MakeObjective(parameters);
  ParameterSet start = parameters;
  start[ParameterId::kAlpha].value = 0.195;
  const FitSummary s = Fit(objective, start, FitOptions{});
  EXPECT_TRUE(s.HasWarning(WarningKind::kNotIdentifiable, "lambda")) << s.FullReport();
  EXPECT_FALSE(s.identifiable[static_cast<std::size_t>(ParameterId::kLambda)]);
  EXPECT_TRUE(std::isnan(s.std_error[static_cast<std::size_t>(ParameterId::kLambda)]));
  EXPECT_TRUE(std::isfinite(s.std_error[static_cast<std::size_t>(ParameterId::kAlpha)]));
  bool mentions_edge_impacts = false;
  for (const FitWarning& w : s.warnings) mentions_edge_impacts |= w.message.find("no edge impact") != std::string::npos;
  EXPECT_TRUE(mentions_edge_impacts) << s.FullReport();
  EXPECT_FALSE(s.HasWarning(WarningKind::kNotIdentifiable, "alpha"));
}

TEST(Fit, ModelFailuresAreCountedByReasonAndTheFitStillEndsFeasible) {
  // A start beyond the critical angle: the block overturns there; the global stage finds feasible points.
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances(8));
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  ParameterSet start = trial.RoughStart();
  start[ParameterId::kAlpha].value = 0.27;
  const FitSummary s = Fit(objective, start, FitOptions{});
  EXPECT_TRUE(s.feasible);
  ASSERT_TRUE(s.failures_by_reason.count("overturned"));
  EXPECT_GT(s.failures_by_reason.at("overturned"), 0);
  EXPECT_TRUE(s.HasWarning(WarningKind::kSimulationFailures));
  EXPECT_EQ(s.epsilon_initial_rad_s, objective.options().failure_penalty_rad_s);
}

TEST(Fit, RefusesAProblemWithoutFreeParameters) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  ParameterSet all_fixed = trial.truth;
  for (ParameterId id : kAllParameters) all_fixed[id].fixed = true;
  const Objective objective = trial.MakeObjective(all_fixed);
  EXPECT_THROW(Fit(objective, all_fixed, FitOptions{}), InvalidArgument);
}

TEST(Fit, GlobalStageToleranceOutsideItsRangeIsRefused) {
  FitOptions options;
  for (double bad : {-1e-9, 1e-16, 0.5, std::nan("")}) {
    options.global.simulation_rel_tol = bad;
    EXPECT_THROW(options.Validate(), InvalidArgument) << bad;
  }
  options.global.simulation_rel_tol = 0.0;  // the model's own
  EXPECT_NO_THROW(options.Validate());
}

TEST(Fit, ScanScreenAndStopRuleOutsideTheirRangesAreRefused) {
  for (double bad : {-0.1, 1.0, std::nan("")}) {
    FitOptions options;
    options.global.scan_prefix_fraction = bad;
    EXPECT_THROW(options.Validate(), InvalidArgument) << bad;
  }
  for (double bad : {-1.0, 0.5, 1.0, std::nan("")}) {
    FitOptions options;
    options.global.continuation_prune_ratio = bad;
    EXPECT_THROW(options.Validate(), InvalidArgument) << bad;
  }
  FitOptions off;
  off.global.scan_prefix_fraction = 0.0;      // no screen
  off.global.continuation_prune_ratio = 0.0;  // no stop rule
  EXPECT_NO_THROW(off.Validate());
}

TEST(FitSummary, JsonCarriesTheDocumentedKeys) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, RealisticDisturbances());
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options;
  options.global.enabled = false;
  const FitSummary s = Fit(objective, trial.truth, options);
  const auto j = nlohmann::json::parse(s.ToJson("T01"));
  EXPECT_EQ(j["trial"], "T01");
  for (const char* key : {"parameters", "epsilon", "epsilon_initial", "t_end", "simulations", "wall_s", "termination",
                          "warnings"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_FALSE(j["parameters"].contains("release_roll"));  // fixed at 0: not reported
  for (ParameterId id : s.parameters.ReportedIds()) {
    const auto& p = j["parameters"][Name(id)];
    for (const char* key : {"value", "lower", "upper", "fixed", "std_error"}) EXPECT_TRUE(p.contains(key)) << key;
  }
  EXPECT_TRUE(j["parameters"]["tau_edge"]["std_error"].is_null());  // fixed: no standard error
  EXPECT_TRUE(j["parameters"]["tau_edge"]["fixed"].get<bool>());
  EXPECT_DOUBLE_EQ(j["epsilon"].get<double>(), s.epsilon_rad_s);
}

}  // namespace
}  // namespace rockfit::fitting

namespace rockfit::fitting {
namespace {

TEST(Fit, ModelErrorWideningScalesThe95PercentHalfWidthsByTheModelErrorOverTheNoiseFloor) {
  // Strong ringing, which the analytic model lacks, puts ε well above the noise floor at rest.
  testing::SyntheticSignalOptions disturbances = testing::RealisticDisturbances(5);
  disturbances.ringing_fraction = 1.0;
  const auto trial = testing::MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, disturbances);
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  FitOptions options;
  options.global.enabled = false;  // the same local search twice: only the widening differs
  options.intervals.model_error_widening = 0.0;
  options.intervals.t0_floor_samples = 0.0;
  const FitSummary plain = Fit(objective, trial.truth, options);
  options.intervals.model_error_widening = 0.5;
  options.intervals.t0_floor_samples = 0.5;
  const FitSummary widened = Fit(objective, trial.truth, options);
  ASSERT_TRUE(plain.model_error.available);
  const double r = plain.model_error.ratio;
  ASSERT_GT(r, 2.0) << "the premise: ε > 2 × the noise floor";
  const double factor = std::sqrt(1.0 + 0.25 * (r * r - 1.0));
  const std::vector<double>& t_s = objective.signal().t_s;
  const double t0_floor_s = 0.5 * (t_s.back() - t_s.front()) / static_cast<double>(t_s.size() - 1);
  for (ParameterId id : {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kLambdaLon}) {
    const std::size_t k = static_cast<std::size_t>(id);
    const double v = plain.parameters.value(id);
    ASSERT_EQ(widened.parameters.value(id), v);
    const Interval& a = plain.uncertainty.interval_95[k];
    const Interval& b = widened.uncertainty.interval_95[k];
    const Parameter& p = plain.parameters[id];
    const double floor = id == ParameterId::kT0 ? t0_floor_s : 0.0;
    EXPECT_NEAR(b[0], std::max(p.lower, v - std::hypot(factor * (v - a[0]), floor)), 1e-12) << Name(id);
    EXPECT_NEAR(b[1], std::min(p.upper, v + std::hypot(factor * (a[1] - v), floor)), 1e-12) << Name(id);
    EXPECT_EQ(widened.uncertainty.interval_68[k], plain.uncertainty.interval_68[k]) << Name(id);
  }
  EXPECT_NE(widened.uncertainty.description.find("widened"), std::string::npos);
  options.intervals.model_error_widening = -1.0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options.intervals.model_error_widening = 0.5;
  options.intervals.t0_floor_samples = -1.0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
