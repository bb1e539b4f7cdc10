// The rescan of λ_lat over growing windows (lateral_rescan.hpp). A narrow block with weak lateral motion
// (λ_lat = 0.389, b2/b1 = 0.54) whose search ended on the plateau of nearly planar motion, with λ_lat of the wrong
// sign and λ half the truth's (a case of the coverage study, fitting/README.md "Lateral rescan"): from there the
// rescan finds the needle of the truth. A second trial has a tilted needle (its λ_lat drifts with λ) that a scan
// of λ_lat at the plateau's λ misses and the joint first-window scan finds, and a third has lateral motion too weak
// for the lateral-motion check to judge, so that only the rescan of weak lateral motion finds it. Also: its options, its
// result in any thread count, and nothing to do when λ_lat is fixed.
#include "rockfit/fitting/lateral_rescan.hpp"

#include <array>

#include <gtest/gtest.h>

#include "build_type.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/lateral_motion_check.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

struct NeedleTrial {
  TrialProblem problem;
  ParameterSet truth;
  ParameterSet plateau;  // where the search had ended
};

// The problem of `trial` with its truth and the plateau where the search had ended (t0, α, λ, λ_lat, λ_lon).
NeedleTrial WithPlateau(const testing::SynthTrial& trial, const std::array<double, 5>& plateau) {
  NeedleTrial n{PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults()), trial.truth, trial.truth};
  const ParameterId ids[] = {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kLambda, ParameterId::kLambdaLat,
                             ParameterId::kLambdaLon};
  for (std::size_t i = 0; i < plateau.size(); ++i) n.plateau[ids[i]].value = plateau[i];
  return n;
}

NeedleTrial MakeNeedleTrial() {
  const core::Block block = core::Block::FromDensity(0.05, 0.02702412972219614, 0.23094777956419704, 2692.0);
  const double t0_s = 1.3466395022554005;
  return WithPlateau(
      testing::MakeSynthTrial(0.15615324225483226, 1.4627796709001304, 0.38859182743319126, 0.5451761153474652,
                              204506704, t0_s, t0_s + 2.5, Eigen::Vector3d(0.2027, -0.2292, 0.1156), block),
      {1.3469684721706037, 0.15603740486112044, 0.7427532653974394, -0.11451666500588317, 0.543030821209235});
}

// A trial of the coverage study (seed 7, trial 14): λ_lat = 0.283 with λ = 0.361; the search ended on the
// plateau at λ = 0.080, λ_lat = −0.065 with 1.54 × the truth's ε. On the first window the needle lies at
// λ_lat 0.26 for λ = 0.1 and 0.28 for λ = 0.36, 0.01 wide.
NeedleTrial MakeTiltedNeedleTrial() {
  const core::Block block = core::Block::FromDensity(0.05, 0.061824982449641804, 0.2239873020375714, 2692.0);
  const double t0_s = 1.0844500346839667;
  return WithPlateau(
      testing::MakeSynthTrial(0.1128045452495944, 0.36146156592854184, 0.2829374259095775, 0.7139120812485118,
                              1736381712, t0_s, t0_s + 2.5,
                              Eigen::Vector3d(-0.1838130323923144, 0.06308341900936548, -0.09343144544708279), block),
      {1.0847294031106722, 0.1125455704045139, 0.0802601886911894, -0.06507127023348565, 0.6981353499742831});
}

TEST(LateralRescan, FindsTheNeedleOfTheTruthFromThePlateauOfPlanarMotion) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const NeedleTrial n = MakeNeedleTrial();
  const Objective& objective = n.problem.objective;
  const Evaluation truth = objective.Evaluate(n.truth);
  const Evaluation plateau = objective.Evaluate(n.plateau);
  ASSERT_TRUE(truth.feasible && plateau.feasible);
  // The premise: the plateau is far worse than the truth, and the lateral-motion check says so.
  ASSERT_GT(plateau.epsilon_rad_s, 1.3 * truth.epsilon_rad_s);
  ASSERT_TRUE(CheckLateralMotion(objective, n.plateau).unexplained);

  const LateralRescanResult r = RunLateralRescan(objective, n.plateau, LateralRescanOptions{}, NelderMeadOptions{}, 0);
  ASSERT_TRUE(r.ran);
  ASSERT_TRUE(r.feasible);
  EXPECT_GE(r.windows, 5);
  EXPECT_LE(r.epsilon_rad_s, 1.02 * truth.epsilon_rad_s);
  EXPECT_NEAR(r.at.value(ParameterId::kLambdaLat), n.truth.value(ParameterId::kLambdaLat), 0.01);
  EXPECT_NEAR(r.at.value(ParameterId::kLambda), n.truth.value(ParameterId::kLambda), 0.15);
  EXPECT_FALSE(CheckLateralMotion(objective, r.at).unexplained);
  EXPECT_GT(r.evaluations, 0);
}

TEST(LateralRescan, TheWholeFitOfTheNeedleTrialReachesTheTruthsEpsilon) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const NeedleTrial n = MakeNeedleTrial();
  const Objective& objective = n.problem.objective;
  FitOptions options;
  options.num_threads = 2;
  const FitSummary fit = Fit(objective, n.problem.start, options);
  const double truth_epsilon = objective.Evaluate(n.truth).epsilon_rad_s;
  ASSERT_TRUE(fit.feasible);
  EXPECT_LE(fit.epsilon_rad_s, 1.02 * truth_epsilon);
  EXPECT_NEAR(fit.parameters.value(ParameterId::kLambdaLat), n.truth.value(ParameterId::kLambdaLat), 0.01);
  EXPECT_FALSE(fit.lateral_motion.unexplained);
  bool rescanned = false;
  for (const FitWarning& w : fit.warnings) rescanned |= w.kind == WarningKind::kMovedByLateralRescan;
  std::printf("needle trial: ε %.6g rad/s (truth %.6g), kept stage %s, moved by the rescan: %s\n", fit.epsilon_rad_s,
              truth_epsilon, fit.kept_stage.c_str(), rescanned ? "yes" : "no");
}

TEST(LateralRescan, TheJointFirstWindowScanFindsATiltedNeedleThatAScanAtTheHeldLambdaMisses) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const NeedleTrial n = MakeTiltedNeedleTrial();
  const Objective& objective = n.problem.objective;
  const Evaluation truth = objective.Evaluate(n.truth);
  ASSERT_TRUE(truth.feasible);
  ASSERT_GT(objective.Evaluate(n.plateau).epsilon_rad_s, 1.3 * truth.epsilon_rad_s);

  // The premise: λ_lat scanned at the plateau's λ only (the joint scan and the other starts off) stays away.
  LateralRescanOptions held;
  held.first_window_lambda_points = 0;
  held.tracked_starts = 1;
  const LateralRescanResult old = RunLateralRescan(objective, n.plateau, held, NelderMeadOptions{}, 0);
  ASSERT_TRUE(old.ran);
  EXPECT_GT(old.epsilon_rad_s, 1.1 * truth.epsilon_rad_s);

  const LateralRescanResult r = RunLateralRescan(objective, n.plateau, LateralRescanOptions{}, NelderMeadOptions{}, 0);
  std::printf("tilted needle: ε %.6g rad/s (truth %.6g) in %lld runs, %.2f s; at the held λ %.6g in %lld runs, %.2f s\n",
              r.epsilon_rad_s, truth.epsilon_rad_s, static_cast<long long>(r.evaluations), r.wall_time_s,
              old.epsilon_rad_s, static_cast<long long>(old.evaluations), old.wall_time_s);
  ASSERT_TRUE(r.ran && r.feasible);
  EXPECT_LE(r.epsilon_rad_s, 1.02 * truth.epsilon_rad_s);
  EXPECT_NEAR(r.at.value(ParameterId::kLambdaLat), n.truth.value(ParameterId::kLambdaLat), 0.01);
  EXPECT_NEAR(r.at.value(ParameterId::kLambda), n.truth.value(ParameterId::kLambda), 0.05);
}

// A trial of the coverage study (seed 7, trial 37): λ_lat = −0.359, λ = 2.40 on a squat block, lateral motion so
// weak that the lateral-motion check cannot judge the search's result (λ 3.78 with 1.03 × the truth's ε).
TEST(LateralRescan, TheFitRescansWeakLateralMotionThatTheCheckCannotJudge) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const core::Block block = core::Block::FromDensity(0.05, 0.05058157747665191, 0.2312905392085594, 2692.0);
  const double t0_s = 1.4383737498094424;
  const testing::SynthTrial trial = testing::MakeSynthTrial(
      0.17761520860037988, 2.4033709565201216, -0.35891228402277586, 0.21061921373388673, 808781558, t0_s, t0_s + 2.5,
      Eigen::Vector3d(-0.27488273918736045, 0.08227192622739432, 0.27570964293889616), block);
  const TrialProblem problem = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  const double truth_epsilon = problem.objective.Evaluate(trial.truth).epsilon_rad_s;
  FitOptions options;
  options.num_threads = 2;
  options.intervals.method = IntervalMethod::kNone;
  const FitSummary fit = Fit(problem.objective, problem.start, options);
  ASSERT_TRUE(fit.feasible);
  EXPECT_LE(fit.epsilon_rad_s, 1.02 * truth_epsilon);
  EXPECT_NEAR(fit.parameters.value(ParameterId::kLambdaLat), trial.truth.value(ParameterId::kLambdaLat), 0.02);
  EXPECT_NEAR(fit.parameters.value(ParameterId::kLambda), trial.truth.value(ParameterId::kLambda), 0.3);
  EXPECT_FALSE(CheckLateralMotion(problem.objective, fit.parameters).unexplained);

  // The premise: without the rescan of weak lateral motion the fit ends in the other basin, where the check
  // cannot judge the out-of-plane signal.
  options.lateral_rescan.below_abs_lambda_lat = 0.0;
  const FitSummary unflagged = Fit(problem.objective, problem.start, options);
  EXPECT_FALSE(CheckLateralMotion(problem.objective, unflagged.parameters).judged);
  std::printf("weak lateral trial: ε %.6g rad/s with the rescan, %.6g without (truth %.6g)\n", fit.epsilon_rad_s,
              unflagged.epsilon_rad_s, truth_epsilon);
  EXPECT_GT(unflagged.epsilon_rad_s, 1.01 * fit.epsilon_rad_s);  // 1.03 × measured: the rescan is what lowers ε
}

TEST(LateralRescan, ResultDoesNotDependOnTheNumberOfThreads) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const NeedleTrial n = MakeNeedleTrial();
  LateralRescanOptions options;
  options.first_window_s = 0.1;
  options.window_step_s = 0.2;  // fewer windows: this test is about the threads, not the search
  const LateralRescanResult one = RunLateralRescan(n.problem.objective, n.plateau, options, NelderMeadOptions{}, 1);
  const LateralRescanResult two = RunLateralRescan(n.problem.objective, n.plateau, options, NelderMeadOptions{}, 2);
  ASSERT_TRUE(one.ran && two.ran);
  EXPECT_EQ(one.epsilon_rad_s, two.epsilon_rad_s);
  for (ParameterId id : kAllParameters) EXPECT_EQ(one.at.value(id), two.at.value(id)) << Name(id);
}

TEST(LateralRescan, DoesNothingWhenLambdaLatIsFixed) {
  const NeedleTrial n = MakeNeedleTrial();
  ParameterSet fixed = n.problem.objective.parameters();
  fixed[ParameterId::kLambdaLat].fixed = true;
  const Objective objective = n.problem.objective.WithParameters(fixed);
  const LateralRescanResult r = RunLateralRescan(objective, n.plateau, LateralRescanOptions{}, NelderMeadOptions{}, 1);
  EXPECT_FALSE(r.ran);
  EXPECT_EQ(r.evaluations, 0);
  EXPECT_EQ(r.at.value(ParameterId::kLambdaLat), n.plateau.value(ParameterId::kLambdaLat));
}

TEST(LateralRescan, OptionsRejectNonPositiveStepsAndTooFineGrids) {
  LateralRescanOptions ok;
  EXPECT_NO_THROW(ok.Validate());
  for (auto set : {+[](LateralRescanOptions& o) { o.window_step_s = 0.0; },
                   +[](LateralRescanOptions& o) { o.first_window_s = -1.0; },
                   +[](LateralRescanOptions& o) { o.lambda_lat_step = std::nan(""); },
                   +[](LateralRescanOptions& o) { o.lambda_lat_step = 1e-9; },
                   +[](LateralRescanOptions& o) { o.evaluations_per_window = 0; },
                   +[](LateralRescanOptions& o) { o.lambda_scan_points = -1; },
                   +[](LateralRescanOptions& o) { o.first_window_lambda_points = -1; },
                   +[](LateralRescanOptions& o) { o.tracked_starts = 0; },
                   +[](LateralRescanOptions& o) { o.min_separation = std::nan(""); },
                   +[](LateralRescanOptions& o) { o.below_abs_lambda_lat = -0.1; }}) {
    LateralRescanOptions o;
    set(o);
    EXPECT_THROW(o.Validate(), InvalidArgument);
  }
  FitOptions fit;
  fit.lateral_rescan.window_step_s = 0.0;
  EXPECT_THROW(fit.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
