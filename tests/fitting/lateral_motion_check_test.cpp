// The check whether the model at a fit reproduces the recorded out-of-plane motion (lateral_motion_check.hpp):
// its definition recomputed on the nodes of (28), the truth of a trial with lateral motion passes, a planar
// model (λ_lat = 0) of the same recording leaves all of it unexplained, and a planar recording has nothing to
// explain. Cheap (a few simulations): runs in every build.
#include "rockfit/fitting/lateral_motion_check.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

// λ_lat = −2 on the default block: the out-of-plane motion is many times the gyro noise.
TrialProblem LateralTrial(ParameterSet* truth) {
  const testing::SynthTrial trial = testing::MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 31);
  *truth = trial.truth;
  return PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
}

TEST(LateralMotionCheck, FractionIsTheUnexplainedOutOfPlaneVarianceAboveTheNoiseAtRest) {
  ParameterSet truth;
  const TrialProblem p = LateralTrial(&truth);
  const LateralMotionCheck c = CheckLateralMotion(p.objective, truth);
  ASSERT_TRUE(c.available);
  // The definition, recomputed: rest samples before t0 − 50 ms, window nodes with their trapezoid weights.
  const MeasuredSignal& s = p.objective.signal();
  double sx = 0, sz = 0, sxx = 0, szz = 0;
  std::size_t n = 0;
  for (; s.t_s[n] < truth.value(ParameterId::kT0) - 0.05; ++n) {
    sx += s.w_B[n].x();
    sz += s.w_B[n].z();
    sxx += s.w_B[n].x() * s.w_B[n].x();
    szz += s.w_B[n].z() * s.w_B[n].z();
  }
  const double N = static_cast<double>(n);
  const double noise_var = 0.5 * ((sxx / N - sx * sx / (N * N)) + (szz / N - sz * sz / (N * N)));
  ErrorNodes nodes;
  ModelOutput out;
  ASSERT_TRUE(p.objective.EvaluateDetailed(truth, &nodes, &out).feasible);
  double w = 0, m2 = 0, r2 = 0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Eigen::Vector3d r = nodes.w_m_B[k] - out.w_B[k];
    w += nodes.weight_s[k];
    m2 += nodes.weight_s[k] * 0.5 * (nodes.w_m_B[k].x() * nodes.w_m_B[k].x() + nodes.w_m_B[k].z() * nodes.w_m_B[k].z());
    r2 += nodes.weight_s[k] * 0.5 * (r.x() * r.x() + r.z() * r.z());
  }
  constexpr double kRelTol = 1e-9;  // the same sums in another order
  EXPECT_NEAR(c.rest_noise_rad_s, std::sqrt(noise_var), kRelTol * c.rest_noise_rad_s);
  EXPECT_NEAR(c.measured_rms_rad_s, std::sqrt(m2 / w), kRelTol * c.measured_rms_rad_s);
  EXPECT_NEAR(c.residual_rms_rad_s, std::sqrt(r2 / w), kRelTol * c.residual_rms_rad_s);
  EXPECT_NEAR(c.unexplained_fraction, std::max(0.0, (r2 / w - noise_var) / (m2 / w - noise_var)), 1e-9);
}

TEST(LateralMotionCheck, TheTruthExplainsTheLateralMotionAndAPlanarModelExplainsNone) {
  ParameterSet truth;
  const TrialProblem p = LateralTrial(&truth);
  const LateralMotionCheck at_truth = CheckLateralMotion(p.objective, truth);
  ASSERT_TRUE(at_truth.available);
  EXPECT_GT(at_truth.measured_rms_rad_s, 5.0 * at_truth.rest_noise_rad_s);  // there is lateral motion
  EXPECT_LT(at_truth.unexplained_fraction, 0.05);                          // the truth leaves noise (and ringing)
  EXPECT_TRUE(at_truth.judged);
  EXPECT_FALSE(at_truth.unexplained);

  // λ_lat = 0: the model stays in its plane (ω_x = ω_z = 0), so the residual is the measurement itself and the
  // fraction is 1 up to the model's in-plane ω leaking into x, z (none: the model rotates about y only).
  ParameterSet planar = truth;
  planar[ParameterId::kLambdaLat].value = 0.0;
  const LateralMotionCheck c = CheckLateralMotion(p.objective, planar);
  ASSERT_TRUE(c.available);
  EXPECT_NEAR(c.residual_rms_rad_s, c.measured_rms_rad_s, 1e-12);
  EXPECT_NEAR(c.unexplained_fraction, 1.0, 1e-9);
  EXPECT_TRUE(c.unexplained);
}

TEST(LateralMotionCheck, APlanarRecordingHasNothingToExplain) {
  const testing::SynthTrial trial = testing::MakeSynthTrial(0.2, 0.8, 0.0, 0.6, 32);
  const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  ParameterSet wrong = trial.truth;
  wrong[ParameterId::kLambdaLat].value = 1.0;  // a model that rocks sideways does not make the recording lateral
  const LateralMotionCheck c = CheckLateralMotion(p.objective, trial.truth);
  ASSERT_TRUE(c.available);
  EXPECT_LT(c.measured_rms_rad_s * c.measured_rms_rad_s, 2.0 * c.rest_noise_rad_s * c.rest_noise_rad_s);
  EXPECT_EQ(c.unexplained_fraction, 0.0);
  EXPECT_FALSE(c.judged);  // nothing to judge: the signal is below twice the noise variance
  EXPECT_FALSE(c.unexplained);
  EXPECT_FALSE(CheckLateralMotion(p.objective, wrong).unexplained);
}

TEST(LateralMotionCheck, WithoutARestBeforeTheReleaseTheCheckIsNotAvailable) {
  ParameterSet truth;
  const TrialProblem p = LateralTrial(&truth);
  ParameterSet early = truth;
  early[ParameterId::kT0].value = p.objective.signal().t_s.front() + 0.1;  // 0.05 s of rest: too short
  EXPECT_FALSE(CheckLateralMotion(p.objective, early).available);
  EXPECT_FALSE(CheckLateralMotion(p.objective, early).judged);
  LateralMotionCheckOptions off;
  off.enabled = false;
  EXPECT_FALSE(CheckLateralMotion(p.objective, truth, off).available);
}

}  // namespace
}  // namespace rockfit::fitting

namespace rockfit::fitting {
namespace {

// A fit that cannot reproduce the lateral motion (λ_lat held at 0.2 on a recording with λ_lat = −2: the model
// barely leaves its plane, but λ acts through its edge impacts) warns and reports λ not determined, whatever
// its interval says.
TEST(LateralMotionCheck, AFitThatLeavesTheLateralMotionUnexplainedWarnsAndDeterminesNoLambda) {
  ParameterSet truth;
  const TrialProblem p = LateralTrial(&truth);
  ParameterSet held = p.objective.parameters();
  held[ParameterId::kLambdaLat].value = 0.2;
  held[ParameterId::kLambdaLat].fixed = true;
  FitOptions options;
  options.global.enabled = false;
  options.method = FitMethod::kNelderMead;
  options.nelder_mead.max_evaluations = 200;  // the warning does not need a converged fit
  // Without the widening for model error, which would widen λ's interval of this poor fit to "no" by itself.
  options.intervals.model_error_widening = 0.0;
  options.intervals.t0_floor_samples = 0.0;
  ParameterSet start = truth;
  start[ParameterId::kLambdaLat] = held[ParameterId::kLambdaLat];
  const FitSummary s = Fit(p.objective.WithParameters(held), start, options);
  ASSERT_TRUE(s.feasible);
  ASSERT_TRUE(s.lateral_motion.available);
  EXPECT_TRUE(s.lateral_motion.unexplained) << s.lateral_motion.unexplained_fraction;
  bool warned = false;
  for (const FitWarning& w : s.warnings) warned |= w.kind == WarningKind::kLateralMotionUnexplained;
  EXPECT_TRUE(warned);
  EXPECT_EQ(s.uncertainty.determined[static_cast<std::size_t>(ParameterId::kLambda)], Determination::kNo);
  const auto json = nlohmann::json::parse(s.ToJson());
  EXPECT_EQ(json["lateral_motion"]["unexplained"], true);
  EXPECT_EQ(json["lateral_motion"]["judged"], true);
  EXPECT_EQ(json["parameters"]["lambda"]["determined"], "no");
  // Without the check, the same fit calls λ determined: the "no" above is the check's.
  options.lateral_motion.enabled = false;
  const FitSummary unchecked = Fit(p.objective.WithParameters(held), start, options);
  ASSERT_TRUE(unchecked.identifiable[static_cast<std::size_t>(ParameterId::kLambda)]);
  EXPECT_EQ(unchecked.uncertainty.determined[static_cast<std::size_t>(ParameterId::kLambda)], Determination::kYes);
  options.lateral_motion.enabled = true;

  // The truth's fit explains it.
  options.nelder_mead.max_evaluations = 50;
  const FitSummary good = Fit(p.objective, truth, options);
  EXPECT_FALSE(good.lateral_motion.unexplained) << good.lateral_motion.unexplained_fraction;
}

}  // namespace
}  // namespace rockfit::fitting
