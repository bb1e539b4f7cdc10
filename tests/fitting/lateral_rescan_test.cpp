// The rescan of λ_lat over growing windows (lateral_rescan.hpp). A narrow block with weak lateral motion
// (λ_lat = 0.389, b2/b1 = 0.54) whose search ended on the plateau of nearly planar motion, with λ_lat of the wrong
// sign and λ half the truth's (a case of the coverage study, fitting/README.md "Lateral rescan"): from there the
// rescan finds the needle of the truth. Also: its options, its result in any thread count, and nothing to do
// when λ_lat is fixed.
#include "rockfit/fitting/lateral_rescan.hpp"

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

NeedleTrial MakeNeedleTrial() {
  const core::Block block = core::Block::FromDensity(0.05, 0.02702412972219614, 0.23094777956419704, 2692.0);
  const double t0_s = 1.3466395022554005;
  const testing::SynthTrial trial =
      testing::MakeSynthTrial(0.15615324225483226, 1.4627796709001304, 0.38859182743319126, 0.5451761153474652,
                              204506704, t0_s, t0_s + 2.5, Eigen::Vector3d(0.2027, -0.2292, 0.1156), block);
  NeedleTrial n{PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults()), trial.truth, trial.truth};
  const std::pair<ParameterId, double> plateau[] = {{ParameterId::kT0, 1.3469684721706037},
                                                    {ParameterId::kAlpha, 0.15603740486112044},
                                                    {ParameterId::kLambda, 0.7427532653974394},
                                                    {ParameterId::kLambdaLat, -0.11451666500588317},
                                                    {ParameterId::kLambdaLon, 0.543030821209235}};
  for (const auto& [id, value] : plateau) n.plateau[id].value = value;
  return n;
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
                   +[](LateralRescanOptions& o) { o.lambda_scan_points = -1; }}) {
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
