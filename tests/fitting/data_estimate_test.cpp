// The starting point from the data: window, release, bias and impact parameters of synthetic x-IMU trials.
#include "rockfit/fitting/data_estimate.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeSynthTrial;

constexpr double kSample_s = 1.0 / 256.0;
// A starting point only needs to be in the basin of the global stage (its box is ±15 ms, ±0.015 rad).
constexpr double kT0Tolerance_s = 0.012;
constexpr double kAlphaTolerance_rad = 4e-3;
// Bias from ~0.9 s at rest: noise 0.1 deg/s / √230 samples plus quantisation 1/16 deg/s.
constexpr double kBiasTolerance_rad_s = 1.5e-3;

TEST(DataEstimate, WindowEndsJustBeforeTheImpactThatEndsPhaseFour) {
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6);
  ASSERT_TRUE(trial.phase4_end_s.has_value());
  const DataEstimate e = EstimateFromData(trial.block, trial.signal, ParameterSet::Defaults(), EstimateOptions{});
  // The |ω_y| peak is the last sample before the impact.
  EXPECT_LE(e.t_end_impact_s, *trial.phase4_end_s);
  EXPECT_GT(e.t_end_impact_s, *trial.phase4_end_s - 2 * kSample_s);
  EXPECT_NEAR(e.t_end_s, e.t_end_impact_s - EstimateOptions{}.t_end_margin_s, 1e-12);
  EXPECT_NEAR(e.first_impact_s, 1.0 + 0.3986, 2 * kSample_s);  // the simulator's first impact, 0.3986 s after release
}

TEST(DataEstimate, ReleaseTiltAndTimeAndBiasComeFromPhaseOne) {
  for (double alpha : {0.17, 0.2, 0.22}) {
    const auto trial = MakeSynthTrial(alpha, 0.8, 1.5, 0.6, 3);
    const DataEstimate e = EstimateFromData(trial.block, trial.signal, ParameterSet::Defaults(), EstimateOptions{});
    EXPECT_NEAR(e.parameters.value(ParameterId::kAlpha), alpha, kAlphaTolerance_rad) << alpha;
    EXPECT_NEAR(e.parameters.value(ParameterId::kT0), 1.0, kT0Tolerance_s) << alpha;
    ASSERT_TRUE(e.bias_estimated);
    const Eigen::Vector3d bias = Eigen::Vector3d(0.3, -0.2, 0.1) * (M_PI / 180.0);
    EXPECT_LT((e.rest_bias_rad_s - bias).norm(), kBiasTolerance_rad_s) << e.rest_bias_rad_s.transpose();
    // t0 bounds narrowed around the estimate, inside the recording.
    EXPECT_GE(e.parameters[ParameterId::kT0].lower, 0.0);
    EXPECT_LT(e.parameters[ParameterId::kT0].upper, e.first_impact_s);
  }
}

TEST(DataEstimate, LambdaLonFromTheFirstJumpInvertsTheFacetMapWhenItIsPlanar) {
  // With λ_lat = 0 the facet map is the planar map (6) (DESIGN §3 errata), so (6) inverted gives λ_lon back.
  // With an ideal sensor the error comes from extrapolating both sides to the impact time (fixed by the energy
  // of phase 1 to a fraction of a sample); with the ringing of a real gyro (25 % of the jump at 38 Hz) the
  // extrapolated ω⁺ is off by a few 0.01 rad/s — good enough to start the global stage, which samples λ_lon
  // over its whole bounds.
  constexpr double kIdealTolerance = 0.05;
  constexpr double kRingingTolerance = 0.35;
  const core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);
  for (double lon : {0.3, 0.9, 1.6}) {
    const auto ideal = MakeSynthTrial(0.2, 1.0, 0.0, lon, 5, 1.0, 2.5, Eigen::Vector3d::Zero(), block, true);
    const DataEstimate e = EstimateFromData(ideal.block, ideal.signal, ParameterSet::Defaults(), EstimateOptions{});
    EXPECT_NEAR(e.parameters.value(ParameterId::kLambdaLon), lon, kIdealTolerance) << lon;
    const auto real = MakeSynthTrial(0.2, 1.0, 0.0, lon, 5);
    const DataEstimate r = EstimateFromData(real.block, real.signal, ParameterSet::Defaults(), EstimateOptions{});
    EXPECT_NEAR(r.parameters.value(ParameterId::kLambdaLon), lon, kRingingTolerance) << lon;
  }
}

TEST(DataEstimate, LambdaLatHasTheSignOfTheLateralMotion) {
  for (double lat : {-3.0, -1.0, 1.0, 3.0}) {
    const auto trial = MakeSynthTrial(0.2, 0.8, lat, 0.6, 7);
    const DataEstimate e = EstimateFromData(trial.block, trial.signal, ParameterSet::Defaults(), EstimateOptions{});
    EXPECT_GT(e.parameters.value(ParameterId::kLambdaLat) * lat, 0.0) << lat;
  }
}

TEST(DataEstimate, FixedParametersKeepTheirValues) {
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6);
  ParameterSet p = ParameterSet::Defaults();
  p[ParameterId::kLambdaLat] = {0.0, -6.0, 6.0, true};
  p[ParameterId::kAlpha] = {0.21, 0.01, 0.3, true};
  const DataEstimate e = EstimateFromData(trial.block, trial.signal, p, EstimateOptions{});
  EXPECT_EQ(e.parameters.value(ParameterId::kLambdaLat), 0.0);
  EXPECT_EQ(e.parameters.value(ParameterId::kAlpha), 0.21);
}

TEST(DataEstimate, ARecordingWithoutImpactIsBadInput) {
  MeasuredSignal still;
  for (int k = 0; k < 512; ++k) {
    still.t_s.push_back(k / 256.0);
    still.w_B.push_back(Eigen::Vector3d::Zero());
  }
  const core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);
  EXPECT_THROW(EstimateFromData(block, still, ParameterSet::Defaults(), EstimateOptions{}), BadInput);
}

TEST(DataEstimate, ARecordingThatEndsBeforePhaseFourAsksForTEnd) {
  const auto trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 1, 1.0, 1.6);  // ends 0.6 s after the release
  try {
    EstimateFromData(trial.block, trial.signal, ParameterSet::Defaults(), EstimateOptions{});
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("--t-end"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rockfit::fitting
