// The problem of a recorded trial (bias, window, start), and system tests of whole fits on synthetic x-IMU
// trials made by the simulator and the measurement model of `rockfit synth` with parameters the fitter is not
// told: the acceptance criteria of docs/design.md §12. A whole fit runs the real simulator a few thousand times
// (0.1–0.5 s in a Release build, minutes in the Debug sanitizer build): those tests run in optimised builds
// only; EveryStageRunsOnTheSimulator covers the same code cheaply in every build.
#include "rockfit/fitting/trial_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "build_type.hpp"
#include "fit_acceptance.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/rest_noise.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

using namespace rockfit::testing;  // tolerances, kOptimisedBuild, MakeSynthTrial

constexpr double kSample_s = 1.0 / 256.0;


struct FitResult {
  TrialProblem problem;
  FitSummary summary;
};

FitResult FitSynth(const testing::SynthTrial& trial, const ParameterSet& parameters, const FitOptions& options,
                   const TrialProblemOptions& problem_options = {}) {
  TrialProblem problem = PrepareTrialProblem(trial.signal, trial.block, parameters, problem_options);
  FitSummary summary = Fit(problem.objective, problem.start, options);
  return {std::move(problem), std::move(summary)};
}

void ExpectRecovered(const testing::SynthTrial& trial, const FitResult& fit) {
  const ParameterSet& p = fit.summary.parameters;
  const ParameterSet& t = trial.truth;
  EXPECT_NEAR(p.value(ParameterId::kT0), t.value(ParameterId::kT0), kT0Tolerance_s);
  EXPECT_NEAR(p.value(ParameterId::kAlpha), t.value(ParameterId::kAlpha), kAlphaTolerance_rad);
  EXPECT_NEAR(p.value(ParameterId::kLambdaLon), t.value(ParameterId::kLambdaLon), kLambdaLonTolerance);
  const double lat = t.value(ParameterId::kLambdaLat);
  EXPECT_GT(p.value(ParameterId::kLambdaLat) * lat, 0.0) << "the sign of λ_lat";
  EXPECT_NEAR(p.value(ParameterId::kLambdaLat), lat, kLambdaLatRelative * std::abs(lat));
  EXPECT_NEAR(p.value(ParameterId::kLambda), t.value(ParameterId::kLambda), kLambdaTolerance);
  EXPECT_LE(fit.summary.epsilon_rad_s, kEpsilonRatio * fit.problem.objective.Evaluate(trial.truth).epsilon_rad_s)
      << fit.summary.FullReport();
}

// `auto` with default options on one thread (as `rockfit batch` runs each trial) meets every criterion.
void ExpectAutoRecoversOnOneThread(const testing::SynthTrial& trial) {
  FitOptions options;
  options.num_threads = 1;
  const FitResult fit = FitSynth(trial, ParameterSet::Defaults(), options);
  ASSERT_TRUE(fit.summary.feasible);
  ExpectRecovered(trial, fit);
}

// ---------------------------------------------------------------- the problem

TEST(TrialProblem, TheGyroBiasAtRestIsMeasuredAndSubtracted) {
  // Noise 0.1 deg/s over ~230 samples at rest plus the 1/16 deg/s quantisation: the mean is good to ~1e-3 rad/s.
  constexpr double kBiasTolerance_rad_s = 1.5e-3;
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 3);
  const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  ASSERT_TRUE(p.bias_subtracted);
  const Eigen::Vector3d bias = Eigen::Vector3d(0.3, -0.2, 0.1) * (M_PI / 180.0);  // injected by MakeSynthTrial
  EXPECT_LT((p.rest_bias_rad_s - bias).norm(), kBiasTolerance_rad_s) << p.rest_bias_rad_s.transpose();
  EXPECT_EQ(p.objective.signal().w_B[10], trial.signal.w_B[10] - p.rest_bias_rad_s);

  TrialProblemOptions keep;
  keep.subtract_rest_bias = false;
  const TrialProblem raw = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults(), keep);
  EXPECT_FALSE(raw.bias_subtracted);
  EXPECT_EQ(raw.objective.signal().w_B[10], trial.signal.w_B[10]);
}

// The rest segment that the default phase-1 fit's t0 places (the first estimate before the bias is known).
RestNoise RestBeforeDefaultRelease(const testing::SynthTrial& trial, const TrialProblemOptions& options) {
  const InitialGuess guess = EstimateInitialGuess(trial.signal, trial.block, ParameterSet::Defaults(), options.guess);
  return MeasureRestNoise(trial.signal, guess.parameters.value(ParameterId::kT0),
                          {options.rest_margin_s, options.rest_min_duration_s});
}

void ExpectSameRest(const RestNoise& a, const RestNoise& b) {
  EXPECT_EQ(a.available, b.available);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.mean_rad_s, b.mean_rad_s);  // bit for bit: the same samples summed in the same order
  EXPECT_EQ(fmt::format("{:.2f}", a.duration_s), fmt::format("{:.2f}", b.duration_s));  // as the note shows it
}

TEST(TrialProblem, TheClosedFormReleasePlacesTheDefaultFitsRestSegment) {
  for (const std::uint64_t seed : {3, 4, 5, 6}) {
    const auto trial = MakeSynthTrial(0.18 + 0.01 * static_cast<double>(seed), 0.8, -2.0, 0.6, seed);
    const TrialProblemOptions options;
    const std::optional<RestNoise> rest =
        RestBeforeClosedFormRelease(trial.signal, trial.block, ParameterSet::Defaults(), options);
    ASSERT_TRUE(rest.has_value()) << "seed " << seed;
    ExpectSameRest(*rest, RestBeforeDefaultRelease(trial, options));
    // The problem subtracts that segment's mean.
    const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults(), options);
    EXPECT_EQ(p.rest_bias_rad_s, rest->mean_rad_s);
  }
}

TEST(TrialProblem, ASampleAtTheEndOfTheRestSegmentFallsBackToTheDefaultFit) {
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 3);
  InitialGuessOptions closed_form;
  closed_form.closed_form_fall = true;
  const double t0_s = EstimateRelease(trial.signal, trial.block, ParameterSet::Defaults(), closed_form).t0_s;
  // The margin that ends the segment on a sample 0.3 s before the release: the closed-form t0 and the default's
  // (~1e-9 s apart) may keep it on either side.
  const auto k = static_cast<std::size_t>(
      std::lower_bound(trial.signal.t_s.begin(), trial.signal.t_s.end(), t0_s - 0.3) - trial.signal.t_s.begin());
  TrialProblemOptions options;
  options.rest_margin_s = t0_s - trial.signal.t_s[k];
  EXPECT_FALSE(RestBeforeClosedFormRelease(trial.signal, trial.block, ParameterSet::Defaults(), options).has_value());
  // The problem then places the segment from the default fit, as it always did.
  const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults(), options);
  const RestNoise rest = RestBeforeDefaultRelease(trial, options);
  ASSERT_TRUE(rest.available);
  EXPECT_EQ(p.rest_bias_rad_s, rest.mean_rad_s);
}

// How far the nearest sample lies from t [s].
double DistanceToNearestSample(const MeasuredSignal& signal, double t_s) {
  double d = std::numeric_limits<double>::infinity();
  for (double t : signal.t_s) d = std::min(d, std::abs(t - t_s));
  return d;
}

TEST(TrialProblem, ADurationNearTheMinimumOrANoteRoundingFallsBackToTheDefaultFit) {
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 3);
  InitialGuessOptions closed_form;
  closed_form.closed_form_fall = true;
  const double t0_s = EstimateRelease(trial.signal, trial.block, ParameterSet::Defaults(), closed_form).t0_s;
  const TrialProblemOptions defaults;
  const double duration_s = t0_s - defaults.rest_margin_s - trial.signal.t_s.front();
  TrialProblemOptions at_minimum;
  at_minimum.rest_min_duration_s = duration_s;  // the comparison with the minimum is in doubt
  ASSERT_GT(DistanceToNearestSample(trial.signal, t0_s - defaults.rest_margin_s), 1e-5) << "the samples are not in doubt";
  EXPECT_FALSE(RestBeforeClosedFormRelease(trial.signal, trial.block, ParameterSet::Defaults(), at_minimum));
  // A margin that puts the duration on a rounding boundary of the note's 2 decimals (…5 exactly, ± round-off).
  TrialProblemOptions on_rounding;
  on_rounding.rest_margin_s = t0_s - trial.signal.t_s.front() - (std::floor(duration_s * 100.0) + 0.5) / 100.0;
  ASSERT_GT(DistanceToNearestSample(trial.signal, t0_s - on_rounding.rest_margin_s), 1e-5) << "the samples are not in doubt";
  EXPECT_FALSE(RestBeforeClosedFormRelease(trial.signal, trial.block, ParameterSet::Defaults(), on_rounding));
  TrialProblemOptions off_rounding = on_rounding;  // a millisecond away from that boundary: no doubt
  off_rounding.rest_margin_s += 1e-3;
  ASSERT_GT(DistanceToNearestSample(trial.signal, t0_s - off_rounding.rest_margin_s), 1e-5);
  EXPECT_TRUE(RestBeforeClosedFormRelease(trial.signal, trial.block, ParameterSet::Defaults(), off_rounding));
}

TEST(TrialProblem, WithoutARestSegmentTheFullDefaultEstimateIsUsed) {
  // Released 0.1 s into the recording: the segment before it lasts 0.05 s, less than the minimum of 0.1 s.
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 3, 0.1, 1.6);
  EXPECT_FALSE(RestBeforeClosedFormRelease(trial.signal, trial.block, ParameterSet::Defaults(), {}).has_value());
  const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  EXPECT_FALSE(p.bias_subtracted);
  const InitialGuess full = EstimateInitialGuess(trial.signal, trial.block, ParameterSet::Defaults());
  EXPECT_EQ(p.guess.parameters.value(ParameterId::kT0), full.parameters.value(ParameterId::kT0));
  EXPECT_EQ(p.guess.parameters.value(ParameterId::kLambdaLat), full.parameters.value(ParameterId::kLambdaLat));
  EXPECT_EQ(p.guess.notes, full.notes);
}

TEST(TrialProblem, TheWindowEndsJustBeforeTheImpactThatEndsPhaseFour) {
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 4);
  ASSERT_TRUE(trial.phase4_end_s.has_value());
  const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  EXPECT_NEAR(p.guess.t_end_s, *trial.phase4_end_s, kSample_s);
  EXPECT_DOUBLE_EQ(p.objective.t_end_s(), p.guess.t_end_s - TrialProblemOptions{}.window_end_margin_s);
  // t0 bounds narrowed to the recording before the first impact.
  EXPECT_EQ(p.start[ParameterId::kT0].lower, trial.signal.t_s.front());
  EXPECT_EQ(p.start[ParameterId::kT0].upper, p.guess.t_first_impact_s);
}

TEST(TrialProblem, AGivenWindowEndIsUsedAsItIsAndCheckedAgainstTheRecording) {
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 4);
  TrialProblemOptions given;
  given.t_end_s = 1.8;
  EXPECT_EQ(PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults(), given).objective.t_end_s(), 1.8);
  given.t_end_s = 0.5;  // before the release
  EXPECT_THROW(PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults(), given), InvalidArgument);
}

// ---------------------------------------------------------------- whole fits

TEST(FitSystem, AutoRecoversUnknownParametersFromNoStartingPoint) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // Two trials with edge impacts in the window, lateral motion of either sign, λ_lon on both sides of 1.
  const auto a = MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 21);
  const FitResult fa = FitSynth(a, ParameterSet::Defaults(), FitOptions{});
  ASSERT_TRUE(fa.summary.feasible);
  ExpectRecovered(a, fa);
  EXPECT_FALSE(fa.summary.HasWarning(WarningKind::kNotIdentifiable)) << fa.summary.FullReport();
  EXPECT_FALSE(fa.summary.HasWarning(WarningKind::kPoorFit)) << fa.summary.FullReport();

  const auto b = MakeSynthTrial(0.2, 1.5, 3.0, 1.2, 22);
  const FitResult fb = FitSynth(b, ParameterSet::Defaults(), FitOptions{});
  ASSERT_TRUE(fb.summary.feasible);
  ExpectRecovered(b, fb);
}

TEST(FitSystem, TheoreticalBoundsRecoverParametersInsideThem) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const auto trial = MakeSynthTrial(0.2, 0.7, -0.8, 0.5, 23);
  ExpectRecovered(trial, FitSynth(trial, ParameterSet::Defaults(BoundsSet::kTheoretical), FitOptions{}));
}

TEST(FitSystem, BothBackEndsPolishTheDataEstimate) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // Planar motion (λ_lat fixed at 0) has no multimodal lateral phase: each back end alone, from the data
  // estimate, reaches the error of the truth.
  const auto trial = MakeSynthTrial(0.19, 0.9, 0.0, 0.7, 25);
  ParameterSet parameters = ParameterSet::Defaults();
  parameters[ParameterId::kLambdaLat] = {0.0, -6.0, 6.0, true};
  parameters[ParameterId::kLambda].fixed = true;  // no edge impact: λ does not act
  for (FitMethod method : {FitMethod::kNelderMead, FitMethod::kCeres}) {
    FitOptions options;
    options.method = method;
    options.global.enabled = false;
    const FitResult fit = FitSynth(trial, parameters, options);
    EXPECT_LE(fit.summary.epsilon_rad_s, kEpsilonRatio * fit.problem.objective.Evaluate(trial.truth).epsilon_rad_s)
        << ToString(method) << "\n" << fit.summary.FullReport();
    EXPECT_NEAR(fit.summary.parameters.value(ParameterId::kLambdaLon), 0.7, kLambdaLonTolerance) << ToString(method);
  }
}

TEST(FitSystem, WeakLateralMotionFindsTheJointBasinOfLambdaAndLambdaLat) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // A deep block with weak lateral motion (from a random sweep of such trials): the continued
  // starts end in a valley of (28) along which λ_lat and λ trade for each other (λ = 3.07, λ_lat = −0.342 at
  // ε 1.2 × ε(truth) with `global.refine = false`); the refinement's joint (λ, λ_lat) scan finds the truth.
  const core::Block block = core::Block::FromDensity(0.05, 0.03782592839333507, 0.175494159779338, 2692.0);
  const double t0_s = 0.9660540691724219;
  const auto trial = MakeSynthTrial(0.20584848006981443, 1.8270303924379572, -0.3011092591948558,
                                    0.6658312054002498, 1011, t0_s, t0_s + 2.5,
                                    Eigen::Vector3d(-0.1798389072629259, -0.01693756887550263, -0.2647271474006842),
                                    block);
  ExpectAutoRecoversOnOneThread(trial);
}

TEST(FitSystem, WeakLateralMotionDoesNotLeaveT0DriftedAlongTheRidge) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // Another trial of the same sweep: in the intermediate windows λ is still wrong and the continuation makes up for it
  // along the ridge t0 + T(α) = t1 (t0 2.2 ms early, α and λ_lon high, at ε 1.12 × ε(truth) with
  // `global.refine = false`); the second pass from the first window and the ridge scan bring them back.
  const core::Block block = core::Block::FromDensity(0.05, 0.05241833796580257, 0.20411491619832395, 2692.0);
  const double t0_s = 1.2276142293908103;
  const auto trial = MakeSynthTrial(0.1730527373621992, 0.481860483649444, -0.489336696299072, 1.0635960434493699,
                                    1004, t0_s, t0_s + 2.5,
                                    Eigen::Vector3d(-0.08212286591768944, 0.11406867825505512, 0.10426369298951005),
                                    block);
  ExpectAutoRecoversOnOneThread(trial);
}

TEST(FitSystem, LambdaIsNotIdentifiableWithoutLateralMotion) {
  // λ_lat fixed at 0, as the paper did for blocks 7 and 8: the motion stays planar, no edge impact happens.
  const auto trial = MakeSynthTrial(0.2, 0.8, 0.0, 0.6, 24);
  ParameterSet parameters = ParameterSet::Defaults();
  parameters[ParameterId::kLambdaLat] = {0.0, -6.0, 6.0, true};
  FitOptions options;  // planar motion: the local search from the estimate suffices
  options.global.enabled = false;
  options.method = FitMethod::kNelderMead;
  options.nelder_mead.max_evaluations = kOptimisedBuild ? 1500 : 60;
  const FitResult fit = FitSynth(trial, parameters, options);
  EXPECT_TRUE(fit.summary.HasWarning(WarningKind::kNotIdentifiable, "lambda")) << fit.summary.FullReport();
  if (kOptimisedBuild) {
    EXPECT_NEAR(fit.summary.parameters.value(ParameterId::kLambdaLon), 0.6, kLambdaLonTolerance);
  }
}

TEST(FitSystem, AMissingMountingGivesAPoorFitWarning) {
  // Position B of the paper: the sensor turned by 180° about z. Without the mounting ω_x and ω_y change sign,
  // the block seems to fall the wrong way and no release on V1V2 explains the data.
  auto trial = MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 27);
  for (Eigen::Vector3d& w : trial.signal.w_B) w = Eigen::Vector3d(-w.x(), -w.y(), w.z());
  FitOptions options;  // the warning is the point here, not the search
  options.global.enabled = false;
  options.method = FitMethod::kNelderMead;
  options.nelder_mead.max_evaluations = 30;
  options.nelder_mead.restarts = 0;
  options.compute_std_errors = false;
  const FitResult fit = FitSynth(trial, ParameterSet::Defaults(), options);
  EXPECT_TRUE(fit.summary.HasWarning(WarningKind::kPoorFit)) << fit.summary.FullReport();
}

TEST(FitSystem, EveryStageRunsOnTheSimulator) {
  // The pipeline of `--method auto` with small budgets, cheap enough for the sanitizer build: every stage
  // runs on the real simulator and the summary is consistent. (The accuracy is the other tests' business.)
  const auto trial = MakeSynthTrial(0.19, 0.9, -1.8, 0.7, 28);
  FitOptions options;
  GlobalStageOptions& g = options.global;
  g.num_samples = 4;
  g.num_polished = 2;
  g.polish_evaluations = 12;
  g.num_continued = 2;
  g.continuation_evaluations = 8;
  g.scan_points = 3;
  g.joint_scan_lat_points = 3;
  g.ridge_points = 3;
  options.nelder_mead.max_evaluations = 20;
  options.nelder_mead.restarts = 0;
  options.ceres.max_iterations = 2;
  const FitResult fit = FitSynth(trial, ParameterSet::Defaults(), options);
  const FitSummary& s = fit.summary;
  ASSERT_TRUE(s.feasible) << s.FullReport();
  ASSERT_EQ(s.stages.size(), 4u);
  EXPECT_EQ(s.stages[1].name, "global");
  EXPECT_EQ(s.stages[3].name, "ceres");
  EXPECT_LE(s.epsilon_rad_s, s.epsilon_initial_rad_s);
  for (const StageReport& stage : s.stages) EXPECT_GE(stage.epsilon_rad_s, s.epsilon_rad_s) << stage.name;
  EXPECT_GT(s.simulations, 0);
}

}  // namespace
}  // namespace rockfit::fitting
