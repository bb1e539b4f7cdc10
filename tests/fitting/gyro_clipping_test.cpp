// Samples at the gyro's full scale (gyro_clipping.hpp): found from the data alone — exactly the clipped ones on a
// recording clipped at a rail, none on one that did not clip — and left out of (28) so that the truth of a
// clipped recording is again explained by the noise, with the count in the model-error statement.
#include "rockfit/fitting/gyro_clipping.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analytic_trial.hpp"
#include "build_type.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/initial_guess.hpp"
#include "synth_trial.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/model_error.hpp"
#include "rockfit/fitting/trial_problem.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kGyroNoiseRadS = 0.1 * M_PI / 180.0;  // the x-IMU's 0.1 deg/s per axis

testing::AnalyticTrial NoisyTrial(std::uint64_t seed) {
  testing::SyntheticSignalOptions o;
  o.noise_rad_s = kGyroNoiseRadS;
  o.seed = seed;
  return testing::MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, o);
}

double LargestComponent(const MeasuredSignal& s) {
  double m = 0.0;
  for (const Eigen::Vector3d& w : s.w_B) m = std::max(m, w.cwiseAbs().maxCoeff());
  return m;
}

// Clips every axis at ±fraction × the largest |ω| component, as a gyro with too small a range; returns which
// samples had a component at the rail (beyond it, or within the detector's tolerance below it).
std::vector<bool> ClipAt(double fraction, MeasuredSignal* s) {
  const double rail = fraction * LargestComponent(*s);
  const double at_rail = (1.0 - GyroClippingOptions{}.level_tolerance) * rail;
  std::vector<bool> beyond(s->size(), false);
  for (std::size_t k = 0; k < s->size(); ++k) {
    beyond[k] = s->w_B[k].cwiseAbs().maxCoeff() >= at_rail;
    s->w_B[k] = s->w_B[k].cwiseMax(-rail).cwiseMin(rail);
  }
  return beyond;
}

TEST(GyroClipping, FindsExactlyTheSamplesClippedAtTheRail) {
  for (double fraction : {0.6, 0.75, 0.9}) {
    testing::AnalyticTrial trial = NoisyTrial(5);
    const std::vector<bool> beyond = ClipAt(fraction, &trial.data.signal);
    const GyroClipping c = DetectGyroClipping(trial.data.signal);
    ASSERT_TRUE(c.detected) << fraction;
    EXPECT_EQ(c.clipped, beyond) << fraction;
    EXPECT_EQ(c.samples, static_cast<std::size_t>(std::count(beyond.begin(), beyond.end(), true)));
    EXPECT_EQ(c.level_rad_s, LargestComponent(trial.data.signal));
  }
}

TEST(GyroClipping, RecordingsThatDidNotClipHaveNoRail) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const GyroClipping c = DetectGyroClipping(NoisyTrial(seed).data.signal);
    EXPECT_FALSE(c.detected) << "seed " << seed;
    EXPECT_TRUE(c.clipped.empty());
    EXPECT_EQ(c.samples, 0u);
  }
}

TEST(GyroClipping, ClippedSamplesLeftOutLeaveTheTruthAtTheNoiseFloor) {
  // Clipped at 0.7 of the peak, the truth's ε is far above the noise; with the clipped samples left out of (28)
  // it is again explained by the noise (as for an unclipped recording, ratio 1 ± 0.1: model_error_test.cpp).
  testing::AnalyticTrial trial = NoisyTrial(7);
  ClipAt(0.7, &trial.data.signal);
  const auto statement = [&](const MeasuredSignal& signal) {
    const Objective objective(signal, trial.t_end_s, trial.model, trial.Bounded(BoundsSet::kEmpirical));
    const Evaluation e = objective.Evaluate(trial.truth);
    EXPECT_TRUE(e.feasible);
    return AssessModelError(objective, e.epsilon_rad_s);
  };
  const ModelErrorStatement kept = statement(trial.data.signal);
  MeasuredSignal marked = trial.data.signal;
  const GyroClipping c = DetectGyroClipping(marked);
  ASSERT_TRUE(c.detected);
  marked.excluded = c.clipped;
  const ModelErrorStatement left_out = statement(marked);
  ASSERT_TRUE(kept.available && left_out.available);
  EXPECT_GT(kept.ratio, 2.0);  // the premise: clipping is model error when the samples stay in
  EXPECT_NEAR(left_out.ratio, 1.0, 0.1);
  EXPECT_EQ(kept.clipped_samples, 0u);
  EXPECT_EQ(left_out.clipped_samples, c.samples);
  EXPECT_EQ(nlohmann::json::parse(ModelErrorJson(left_out))["clipped_samples"].get<std::size_t>(), c.samples);
}

TEST(GyroClipping, TheTrialProblemMarksTheClippedSamplesAndSaysHowMany) {
  testing::AnalyticTrial trial = NoisyTrial(9);
  const std::vector<bool> beyond = ClipAt(0.8, &trial.data.signal);
  const TrialProblem problem = PrepareTrialProblem(trial.data.signal, trial.block, ParameterSet::Defaults());
  ASSERT_TRUE(problem.clipping.detected);
  EXPECT_EQ(problem.objective.signal().excluded, beyond);
  EXPECT_TRUE(std::any_of(problem.notes.begin(), problem.notes.end(),
                          [](const std::string& n) { return n.find("full scale") != std::string::npos; }));
  TrialProblemOptions off;
  off.clipping.enabled = false;
  EXPECT_TRUE(PrepareTrialProblem(trial.data.signal, trial.block, ParameterSet::Defaults(), off)
                  .objective.signal()
                  .excluded.empty());
}

TEST(GyroClipping, ARecordingClippedAtThreeQuartersOfItsPeakIsFittedToItsTruth) {
  // synth's measurement model (noise, bias, quantisation, ringing) and a gyro whose range ends at 0.75 of the
  // largest |ω|: with the clipped samples left out the fit finds the truth's basin (ε within 2 % of the truth's)
  // and its 95 % intervals of t0 and α hold the truth. A whole fit: optimised builds only.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  testing::SynthTrial trial = testing::MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 3);
  ClipAt(0.75, &trial.signal);
  const TrialProblem problem = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  ASSERT_TRUE(problem.clipping.detected);
  FitOptions options;
  options.num_threads = 1;
  const FitSummary fit = Fit(problem.objective, problem.start, options);
  ASSERT_TRUE(fit.feasible);
  const Evaluation truth = problem.objective.Evaluate(trial.truth);
  EXPECT_LE(fit.epsilon_rad_s, 1.02 * truth.epsilon_rad_s) << fit.FullReport();
  EXPECT_EQ(fit.model_error.clipped_samples, problem.clipping.samples);
  for (ParameterId id : {ParameterId::kT0, ParameterId::kAlpha}) {
    const Interval& i = fit.uncertainty.interval_95[static_cast<std::size_t>(id)];
    EXPECT_TRUE(!(i[0] > trial.truth.value(id)) && !(i[1] < trial.truth.value(id))) << fit.FullReport();
  }
}

TEST(GyroClipping, TheWindowOfAClippedRecordingEndsAtTheSameBaseImpact) {
  // The window ends at the second base impact, found as a peak of |ω_y| followed by a drop. Clipped, the peak is a
  // flat top at the rail and the impact lies at its end or inside it (after the impact |ω_y| can stay above the
  // rail): the detector must still take it for the impact, not pass on to a later one (a whole rocking
  // half-cycle, 0.3 s or more, later). Compared with the same recording unclipped.
  constexpr double kSameImpactToleranceS = 8.0 / 256.0;  // the impact placed inside a top of up to 16 samples
  for (std::uint64_t seed : {2u, 3u, 4u}) {
    for (double fraction : {0.6, 0.75, 0.9}) {
      testing::SynthTrial trial = testing::MakeSynthTrial(0.2, 0.8, -2.0, 0.6, seed);
      const double unclipped = DetectWindowEnd(trial.signal, {});
      ClipAt(fraction, &trial.signal);
      const GyroClipping c = DetectGyroClipping(trial.signal);
      ASSERT_TRUE(c.detected);
      trial.signal.excluded = c.clipped;
      EXPECT_NEAR(DetectWindowEnd(trial.signal, {}), unclipped, kSameImpactToleranceS)
          << "seed " << seed << ", rail at " << fraction << " of the peak";
    }
  }
}

TEST(GyroClipping, OptionsAreValidated) {
  GyroClippingOptions o;
  o.level_tolerance = 1.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
  o.level_tolerance = 1e-4;
  o.min_samples = 1;
  EXPECT_THROW(o.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
