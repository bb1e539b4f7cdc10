// System tests: synthetic x-IMU trials made by the simulator and the measurement model of `rockfit synth`,
// fitted without a starting point. The acceptance criteria of issue 6. A whole fit runs the real simulator a
// few thousand times (0.1–0.5 s in a Release build, minutes in the Debug sanitizer build): those tests run in
// optimised builds only; EveryStageRunsOnTheSimulator covers the same code cheaply in every build.
#include "rockfit/fitting/trial_fit.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "build_type.hpp"
#include "rockfit/fitting/objective.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeSynthTrial;

// Issue 6, "Done when".
constexpr double kT0Tolerance_s = 2e-3;
constexpr double kAlphaTolerance_rad = 2e-3;
constexpr double kLambdaLonTolerance = 0.03;
constexpr double kLambdaLatRelative = 0.10;
constexpr double kLambdaTolerance = 0.1;
constexpr double kEpsilonRatio = 1.05;

double EpsilonAtTruth(const testing::SynthTrial& trial, const TrialFit& fit) {
  const Objective objective(fit.signal, fit.summary.t_end_s, std::make_shared<SimulatorModel>(trial.block),
                            fit.estimate.parameters);
  return objective.Evaluate(trial.truth).epsilon_rad_s;
}

void ExpectRecovered(const testing::SynthTrial& trial, const TrialFit& fit) {
  const ParameterSet& p = fit.summary.parameters;
  const ParameterSet& t = trial.truth;
  EXPECT_NEAR(p.value(ParameterId::kT0), t.value(ParameterId::kT0), kT0Tolerance_s);
  EXPECT_NEAR(p.value(ParameterId::kAlpha), t.value(ParameterId::kAlpha), kAlphaTolerance_rad);
  EXPECT_NEAR(p.value(ParameterId::kLambdaLon), t.value(ParameterId::kLambdaLon), kLambdaLonTolerance);
  const double lat = t.value(ParameterId::kLambdaLat);
  EXPECT_GT(p.value(ParameterId::kLambdaLat) * lat, 0.0) << "the sign of λ_lat";
  EXPECT_NEAR(p.value(ParameterId::kLambdaLat), lat, kLambdaLatRelative * std::abs(lat));
  EXPECT_NEAR(p.value(ParameterId::kLambda), t.value(ParameterId::kLambda), kLambdaTolerance);
  EXPECT_LE(fit.summary.epsilon_rad_s, kEpsilonRatio * EpsilonAtTruth(trial, fit)) << fit.summary.FullReport();
}

TEST(TrialFitSystem, AutoRecoversUnknownParametersFromNoStartingPoint) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // Two trials with edge impacts in the window, lateral motion of either sign, λ_lon on both sides of 1.
  const auto a = MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 21);
  const TrialFit fa = FitTrial(a.block, a.signal, ParameterSet::Defaults(), TrialFitOptions{});
  ASSERT_TRUE(fa.summary.feasible);
  ExpectRecovered(a, fa);
  EXPECT_FALSE(fa.summary.HasWarning("not_identifiable")) << fa.summary.FullReport();

  const auto b = MakeSynthTrial(0.2, 1.5, 3.0, 1.2, 22);
  const TrialFit fb = FitTrial(b.block, b.signal, ParameterSet::Defaults(), TrialFitOptions{});
  ASSERT_TRUE(fb.summary.feasible);
  ExpectRecovered(b, fb);
}

TEST(TrialFitSystem, TheoreticalBoundsRecoverParametersInsideThem) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const auto trial = MakeSynthTrial(0.2, 0.7, -0.8, 0.5, 23);
  TrialFitOptions options;
  const TrialFit fit = FitTrial(trial.block, trial.signal, ParameterSet::Defaults(BoundsSet::kTheoretical), options);
  ExpectRecovered(trial, fit);
}

TEST(TrialFitSystem, LambdaIsNotIdentifiableWithoutLateralMotion) {
  // λ_lat fixed at 0, as the paper did for blocks 7 and 8: the motion stays planar, no edge impact happens.
  // Planar motion has no multimodal lateral phase: the local search from the estimate suffices.
  const auto trial = MakeSynthTrial(0.2, 0.8, 0.0, 0.6, 24);
  ParameterSet parameters = ParameterSet::Defaults();
  parameters[ParameterId::kLambdaLat].fixed = true;
  parameters[ParameterId::kLambdaLat].value = 0.0;
  TrialFitOptions options;
  options.fit.global.enabled = false;
  options.fit.method = FitMethod::kNelderMead;
  const TrialFit fit = FitTrial(trial.block, trial.signal, parameters, options);
  EXPECT_TRUE(fit.summary.HasWarning("not_identifiable", "lambda")) << fit.summary.FullReport();
  EXPECT_NEAR(fit.summary.parameters.value(ParameterId::kLambdaLon), 0.6, kLambdaLonTolerance);
}

TEST(TrialFitSystem, BothBackEndsPolishANearbyStart) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const auto trial = MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 25);
  for (FitMethod method : {FitMethod::kNelderMead, FitMethod::kCeres}) {
    TrialFitOptions options;
    options.fit.method = method;
    options.fit.global.enabled = false;
    options.start_values = {{ParameterId::kLambda, 0.95}, {ParameterId::kLambdaLat, -1.7}};
    const TrialFit fit = FitTrial(trial.block, trial.signal, ParameterSet::Defaults(), options);
    EXPECT_LE(fit.summary.epsilon_rad_s, kEpsilonRatio * EpsilonAtTruth(trial, fit))
        << ToString(method) << "\n" << fit.summary.FullReport();
  }
}

TEST(TrialFitSystem, EvaluateGivesTheErrorOfGivenParametersOnTheSameWindow) {
  const auto trial = MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 26);
  ParameterSet given = trial.truth;
  for (ParameterId id : kAllParameters) given[id].fixed = true;
  const TrialEvaluation e = EvaluateTrial(trial.block, trial.signal, given, TrialFitOptions{});
  ASSERT_TRUE(e.feasible);
  // The error of the truth is the measurement error: noise 0.1 deg/s, quantisation, ringing, bias residue.
  EXPECT_LT(e.epsilon_rad_s, 0.02);
  EXPECT_GT(e.epsilon_rad_s, 0.0);
  EXPECT_FALSE(e.trace.w_B.empty());
}

}  // namespace
}  // namespace rockfit::fitting

namespace rockfit::fitting {
namespace {

TEST(TrialFitSystem, AMissingMountingIsReportedAsADataProblemAndAPoorFit) {
  // Position B of the paper: the sensor turned by 180° about z. Without the mounting ω_x and ω_y change sign,
  // the block seems to fall the wrong way and no release on V1V2 explains the data.
  auto trial = testing::MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 27);
  for (Eigen::Vector3d& w : trial.signal.w_B) w = Eigen::Vector3d(-w.x(), -w.y(), w.z());
  TrialFitOptions options;
  options.fit.global.enabled = false;  // the warning is the point here, not the search
  options.fit.method = FitMethod::kNelderMead;
  options.fit.nelder_mead.max_evaluations = 30;
  options.fit.nelder_mead.restarts = 0;
  options.fit.compute_std_errors = false;
  const TrialFit fit = FitTrial(trial.block, trial.signal, ParameterSet::Defaults(), options);
  EXPECT_TRUE(fit.summary.HasWarning("data")) << fit.summary.FullReport();
  EXPECT_TRUE(fit.summary.HasWarning("poor_fit")) << fit.summary.FullReport();
}

}  // namespace
}  // namespace rockfit::fitting

namespace rockfit::fitting {
namespace {

TEST(TrialFitSystem, EveryStageRunsOnTheSimulator) {
  // The pipeline of `--method auto` with small budgets, cheap enough for the sanitizer build: every stage
  // runs on the real simulator and the summary is consistent. (The accuracy is the other tests' business.)
  const auto trial = testing::MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 28);
  TrialFitOptions options;
  GlobalStageOptions& g = options.fit.global;
  g.num_samples = 4;
  g.num_polished = 2;
  g.polish_evaluations = 12;
  g.num_continued = 2;
  g.continuation_evaluations = 8;
  g.scan_points = 3;
  options.fit.nelder_mead.max_evaluations = 20;
  options.fit.nelder_mead.restarts = 0;
  options.fit.ceres.max_iterations = 2;
  const TrialFit fit = FitTrial(trial.block, trial.signal, ParameterSet::Defaults(), options);
  const FitSummary& s = fit.summary;
  ASSERT_TRUE(s.feasible) << s.FullReport();
  ASSERT_EQ(s.stages.size(), 4u);
  EXPECT_EQ(s.stages[1].name, "global");
  EXPECT_EQ(s.stages[3].name, "ceres");
  EXPECT_LE(s.epsilon_rad_s, s.epsilon_initial_rad_s);
  for (const StageReport& stage : s.stages) EXPECT_GE(stage.epsilon_rad_s, s.epsilon_rad_s) << stage.name;
  EXPECT_GT(s.simulations, 0);
  EXPECT_EQ(fit.trace.t_s.size(), fit.trace.w_B.size());
  EXPECT_FALSE(fit.trace.events.empty());
}

}  // namespace
}  // namespace rockfit::fitting
