// System tests: synthetic x-IMU trials made by the simulator and the measurement model of `rockfit synth`,
// fitted without a starting point. The acceptance criteria of issue 6. Each fit runs the real simulator a
// few thousand times (about a second in a Release build).
#include "rockfit/fitting/trial_fit.hpp"

#include <cmath>

#include <gtest/gtest.h>

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
  const auto trial = MakeSynthTrial(0.2, 0.7, -0.8, 0.5, 23);
  TrialFitOptions options;
  const TrialFit fit = FitTrial(trial.block, trial.signal, ParameterSet::Defaults(BoundsSet::kTheoretical), options);
  ExpectRecovered(trial, fit);
}

TEST(TrialFitSystem, LambdaIsNotIdentifiableWithoutLateralMotion) {
  // λ_lat fixed at 0, as the paper did for blocks 7 and 8: the motion stays planar, no edge impact happens.
  const auto trial = MakeSynthTrial(0.2, 0.8, 0.0, 0.6, 24);
  ParameterSet parameters = ParameterSet::Defaults();
  parameters[ParameterId::kLambdaLat].fixed = true;
  parameters[ParameterId::kLambdaLat].value = 0.0;
  const TrialFit fit = FitTrial(trial.block, trial.signal, parameters, TrialFitOptions{});
  EXPECT_TRUE(fit.summary.HasWarning("not_identifiable", "lambda")) << fit.summary.FullReport();
  EXPECT_NEAR(fit.summary.parameters.value(ParameterId::kLambdaLon), 0.6, kLambdaLonTolerance);
}

TEST(TrialFitSystem, BothBackEndsPolishANearbyStart) {
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
  const TrialFit fit = FitTrial(trial.block, trial.signal, ParameterSet::Defaults(), options);
  EXPECT_TRUE(fit.summary.HasWarning("data")) << fit.summary.FullReport();
  EXPECT_TRUE(fit.summary.HasWarning("poor_fit")) << fit.summary.FullReport();
}

}  // namespace
}  // namespace rockfit::fitting
