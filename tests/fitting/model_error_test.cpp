// The model-error statement (model_error.hpp) on trials of the analytic test model, whose truth reproduces the
// motion exactly: white noise alone is explained by the floor measured at rest, unmodelled motion of a known size
// is recovered as the model error, every ε above twice the floor is flagged, and no rest means no statement.
#include "rockfit/fitting/model_error.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analytic_trial.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kGyroNoiseRadS = 0.1 * M_PI / 180.0;  // the x-IMU's 0.1 deg/s per axis

testing::AnalyticTrial NoisyTrial(double ringing_fraction = 0.0, std::uint64_t seed = 3) {
  testing::SyntheticSignalOptions o;
  o.noise_rad_s = kGyroNoiseRadS;
  o.ringing_fraction = ringing_fraction;
  o.ringing_hz = 38.0;
  o.ringing_decay_s = 0.03;
  o.seed = seed;
  return testing::MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6, o);
}

ModelErrorStatement AtTruth(const testing::AnalyticTrial& trial) {
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  const Evaluation e = objective.Evaluate(trial.truth);
  EXPECT_TRUE(e.feasible);
  return AssessModelError(objective, e.epsilon_rad_s);
}

TEST(ModelError, NoiseAloneAtTheTruthIsExplainedByTheFloorMeasuredAtRest) {
  const ModelErrorStatement s = AtTruth(NoisyTrial());
  ASSERT_TRUE(s.available);
  // The truth leaves only the noise: ε equals the floor up to the sampling scatter of two means (≈ 2 %).
  EXPECT_NEAR(s.ratio, 1.0, 0.1);
  EXPECT_GT(s.noise_share, 0.8);
  EXPECT_FALSE(s.dominates);
  EXPECT_NEAR(s.model_error_rad_s * s.model_error_rad_s + s.noise_floor_rad_s * s.noise_floor_rad_s,
              std::max(s.epsilon_rad_s * s.epsilon_rad_s, s.noise_floor_rad_s * s.noise_floor_rad_s), 1e-15);
}

TEST(ModelError, UnmodelledMotionOfKnownSizeIsRecoveredAsTheModelError) {
  // Motion the model does not make: independent Gaussian ω of twice the noise's σ after the release. Errors of
  // one shape add in quadrature, so ε_model / ε_noise must be 2.
  testing::AnalyticTrial trial = NoisyTrial();
  std::mt19937_64 rng(17);
  const double t0 = trial.truth.value(ParameterId::kT0);
  for (std::size_t k = 0; k < trial.data.signal.size(); ++k) {
    if (trial.data.signal.t_s[k] < t0) continue;
    for (int c = 0; c < 3; ++c) trial.data.signal.w_B[k][c] += 2.0 * kGyroNoiseRadS * testing::NormalDeviate(rng);
  }
  const ModelErrorStatement s = AtTruth(trial);
  ASSERT_TRUE(s.available);
  EXPECT_NEAR(s.model_error_rad_s / s.noise_floor_rad_s, 2.0, 0.2);
  EXPECT_NEAR(s.noise_share, 0.2, 0.05);
  EXPECT_TRUE(s.dominates);
}

TEST(ModelError, EveryEpsilonAboveTwiceTheFloorIsFlaggedAsDominatedByModelError) {
  // Ringing after the impacts, which the model lacks, from none to a full jump: the flag follows the ratio.
  int above_twice = 0, below = 0;
  for (double ringing : {0.0, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0}) {
    const ModelErrorStatement s = AtTruth(NoisyTrial(ringing));
    ASSERT_TRUE(s.available);
    if (s.ratio > 2.0) {
      ++above_twice;
      EXPECT_TRUE(s.dominates) << "ringing " << ringing << ", ratio " << s.ratio;
    }
    if (s.ratio < std::sqrt(2.0)) {
      ++below;
      EXPECT_FALSE(s.dominates) << "ringing " << ringing << ", ratio " << s.ratio;
    }
  }
  EXPECT_GE(above_twice, 1);  // the premise: some cases are far above the floor …
  EXPECT_GE(below, 1);        // … and some at it
}

TEST(ModelError, NoRestBeforeTheReleaseGivesNoStatementAndNullsInJson) {
  testing::AnalyticTrial trial = NoisyTrial();
  // Cut the recording to start 60 ms before the release: less than 0.1 s of rest before t0 − 50 ms.
  MeasuredSignal cut;
  for (std::size_t k = 0; k < trial.data.signal.size(); ++k) {
    if (trial.data.signal.t_s[k] < trial.truth.value(ParameterId::kT0) - 0.06) continue;
    cut.t_s.push_back(trial.data.signal.t_s[k]);
    cut.w_B.push_back(trial.data.signal.w_B[k]);
  }
  trial.data.signal = cut;
  const ModelErrorStatement s = AtTruth(trial);
  EXPECT_FALSE(s.available);
  EXPECT_FALSE(s.dominates);
  const nlohmann::json j = nlohmann::json::parse(ModelErrorJson(s));
  EXPECT_FALSE(j["available"].get<bool>());
  EXPECT_TRUE(j["dominates"].is_null());
  EXPECT_TRUE(j["noise_floor_rad_s"].is_null());
  EXPECT_NE(ModelErrorText(s).find("not measured"), std::string::npos);
}

TEST(ModelError, JsonCarriesTheSplitAndTheFlag) {
  const ModelErrorStatement s = AtTruth(NoisyTrial(1.0));
  const nlohmann::json j = nlohmann::json::parse(ModelErrorJson(s));
  for (const char* key : {"available", "epsilon_rad_s", "noise_floor_rad_s", "ratio", "noise_share",
                          "model_error_rad_s", "model_error_share", "dominates", "rest_duration_s", "rest_samples"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_TRUE(j["dominates"].get<bool>());
  EXPECT_NEAR(j["noise_share"].get<double>() + j["model_error_share"].get<double>(), 1.0, 1e-12);
}

TEST(ModelError, OptionsAreValidated) {
  ModelErrorOptions o;
  o.dominance_share = 1.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
  o.dominance_share = 0.5;
  o.rest.min_duration_s = -1.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
