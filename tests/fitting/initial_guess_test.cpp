// The data-driven starting point (fitting/src/initial_guess.cpp) on in-process synthetic trials of the hybrid
// simulator with gyro noise, ringing and bias, against the parameters that made them.
#include "rockfit/fitting/initial_guess.hpp"

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_rocking.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "synthetic_signal.hpp"

namespace rockfit::fitting {
namespace {

// t0 within a few ms: a fraction of the 3.9 ms sample period at 256 Hz plus the noise.
constexpr double kT0ToleranceS = 3e-3;
// α within 0.01 rad: the global stage searches ±0.015 rad around the estimate.
constexpr double kAlphaToleranceRad = 0.01;
// t_end: the second base impact is a sample of the peak of |ω_y|, within one sample of the true impact.
constexpr double kWindowEndToleranceS = 1.0 / 256.0 + 1e-9;
// The phase-1 fit with the closed-form fall and Brent's method against RK4 and golden sections: the same model to
// round-off, whose minimum is defined to ~1e-9 s (≤ 3.7e-9 s and 2.6e-10 rad on the 16 sample trials).
constexpr double kSameStartT0ToleranceS = 1e-8;
constexpr double kSameStartAlphaToleranceRad = 1e-9;

core::Block PaperBlock(double b2_m) { return core::Block::FromDensity(0.05, b2_m, 0.2, 2692.0); }

struct Truth {
  double t0_s, alpha_rad, lambda, lambda_lat, lambda_lon;

  core::ModelParameters Model() const {
    core::ModelParameters p = ParameterSet::Defaults().ToModel();
    p.alpha_rad = alpha_rad;
    p.lambda = lambda;
    p.lambda_lat = lambda_lat;
    p.lambda_lon = lambda_lon;
    return p;
  }
};

testing::SyntheticSignal MakeTrial(const core::Block& block, const Truth& truth, std::uint64_t seed) {
  const SimulatorModel model(block);
  testing::SyntheticSignalOptions options;
  options.t0_s = truth.t0_s;
  options.duration_s = truth.t0_s + 1.5;
  options.noise_rad_s = 0.1 * M_PI / 180.0;  // x-IMU gyro noise 0.1 °/s
  options.ringing_fraction = 0.2;
  options.bias_rad_s = Eigen::Vector3d(0.0002, 0.0009, -0.0005);
  options.seed = seed;
  return testing::MakeSyntheticSignal(model, truth.Model(), options);
}

// The simulator's phase-4 stop: the first impact on the release side after the first facet impact (docs/design.md §4).
core::Trajectory SimulateToPhase4End(const core::Block& block, const Truth& truth) {
  core::SimulationOptions options;
  options.stop = core::StopCondition::kPhase4;
  return core::Simulate(block, truth.Model(), options);
}

class InitialGuessOnSynthetic : public ::testing::TestWithParam<Truth> {};

TEST_P(InitialGuessOnSynthetic, RecoversReleaseTimeTiltAndSignOfLambdaLat) {
  const Truth truth = GetParam();
  const core::Block block = PaperBlock(0.035);
  const testing::SyntheticSignal trial = MakeTrial(block, truth, 11);
  const InitialGuess g = EstimateInitialGuess(trial.signal, block, ParameterSet::Defaults());
  EXPECT_NEAR(g.parameters.value(ParameterId::kT0), truth.t0_s, kT0ToleranceS);
  EXPECT_NEAR(g.parameters.value(ParameterId::kAlpha), truth.alpha_rad, kAlphaToleranceRad);
  EXPECT_GT(g.parameters.value(ParameterId::kLambdaLat) * truth.lambda_lat, 0.0) << "λ_lat has the wrong sign";
  // The first impact is where the planar fall from the true release lands.
  const double t_impact = truth.t0_s + core::FallTime(core::PlanarRockerAboutEdge(block, 1, 2), truth.alpha_rad);
  EXPECT_NEAR(g.t_first_impact_s, t_impact, kWindowEndToleranceS);
}

TEST_P(InitialGuessOnSynthetic, ClosedFormFallGivesTheSameReleaseToRoundOff) {
  const Truth truth = GetParam();
  const core::Block block = PaperBlock(0.035);
  const testing::SyntheticSignal trial = MakeTrial(block, truth, 11);
  InitialGuessOptions closed_form;
  closed_form.closed_form_fall = true;
  const InitialGuess integrated = EstimateInitialGuess(trial.signal, block, ParameterSet::Defaults());
  const InitialGuess fast = EstimateInitialGuess(trial.signal, block, ParameterSet::Defaults(), closed_form);
  EXPECT_NEAR(fast.parameters.value(ParameterId::kT0), integrated.parameters.value(ParameterId::kT0),
              kSameStartT0ToleranceS);
  EXPECT_NEAR(fast.parameters.value(ParameterId::kAlpha), integrated.parameters.value(ParameterId::kAlpha),
              kSameStartAlphaToleranceRad);
}

TEST_P(InitialGuessOnSynthetic, ReleaseAloneIsTheFullEstimatesReleaseBitForBit) {
  const Truth truth = GetParam();
  const core::Block block = PaperBlock(0.035);
  const testing::SyntheticSignal trial = MakeTrial(block, truth, 11);
  for (const bool closed_form_fall : {false, true}) {
    InitialGuessOptions options;
    options.closed_form_fall = closed_form_fall;
    const InitialGuess full = EstimateInitialGuess(trial.signal, block, ParameterSet::Defaults(), options);
    const ReleaseEstimate alone = EstimateRelease(trial.signal, block, ParameterSet::Defaults(), options);
    EXPECT_EQ(alone.t0_s, full.parameters.value(ParameterId::kT0)) << "closed form " << closed_form_fall;
    EXPECT_EQ(alone.t_first_impact_s, full.t_first_impact_s) << "closed form " << closed_form_fall;
  }
}

TEST_P(InitialGuessOnSynthetic, WindowEndIsTheImpactEndingPhase4) {
  const Truth truth = GetParam();
  const core::Block block = PaperBlock(0.035);
  const testing::SyntheticSignal trial = MakeTrial(block, truth, 12);
  const core::Trajectory phase4 = SimulateToPhase4End(block, truth);
  ASSERT_EQ(phase4.end_reason, core::EndReason::kPhase4);
  const double t_phase4_end = truth.t0_s + phase4.t_end_s;
  EXPECT_NEAR(DetectWindowEnd(trial.signal, {}), t_phase4_end, kWindowEndToleranceS);
}

TEST(InitialGuess, WindowEndAfterStrongLateralRockingIsTheSideEdgeImpact) {
  // A deep, squat block (b2 = 7 cm, h = 15 cm) with a strong lateral kick: after the facet impact it rocks on V4
  // with ~19° of roll and spins (ω_z ≈ 1 rad/s), and phase 4 ends when it lands on V1, i.e. on the side edge
  // V1V4. The base is flat about y there, but ∫ω_y dt is not (it drifts from the tilt by 0.03 rad under the
  // roll and spin); the detector must follow the integrated attitude.
  const core::Block block = core::Block::FromDensity(0.05, 0.0695, 0.1506, 2692.0);
  const Truth truth{0.5, 0.1783, 0.986, 3.366, 0.491};
  const testing::SyntheticSignal trial = MakeTrial(block, truth, 13);
  const core::Trajectory phase4 = SimulateToPhase4End(block, truth);
  ASSERT_EQ(phase4.end_reason, core::EndReason::kPhase4);
  ASSERT_FALSE(phase4.impacts.empty());
  EXPECT_EQ(phase4.impacts.back().kind, core::ImpactKind::kEdge) << "a side-edge impact ends phase 4 here";
  EXPECT_NEAR(DetectWindowEnd(trial.signal, {}), truth.t0_s + phase4.t_end_s, kWindowEndToleranceS);
}

TEST(InitialGuess, WindowEndIsALandingWithASmallJump) {
  // A deep block (b2 = 6.8 cm, h = 24 cm) rocks on its far edge V3V4 and lands on the release side through an
  // edge impact V3→V2 with λ = 0.5: ω_y changes by about 3 %, less than one sample of its rise before the
  // impact. The landing shows as the tilt about y passing through zero at the |ω_y| peak.
  const core::Block block = core::Block::FromDensity(0.05, 0.0681, 0.2406, 2692.0);
  // t0 puts the impact just before a sample, so that the sample after it is not lower than the one before.
  const Truth truth{0.602, 0.0957, 0.509, -1.247, 1.042};
  const testing::SyntheticSignal trial = MakeTrial(block, truth, 14);
  const core::Trajectory phase4 = SimulateToPhase4End(block, truth);
  ASSERT_EQ(phase4.end_reason, core::EndReason::kPhase4);
  ASSERT_FALSE(phase4.impacts.empty());
  const core::ImpactRecord& last = phase4.impacts.back();
  EXPECT_EQ(last.kind, core::ImpactKind::kEdge);
  EXPECT_LT(std::abs(last.w_plus_B.y() - last.w_minus_B.y()), 0.05 * std::abs(last.w_minus_B.y())) << "a small jump";
  EXPECT_NEAR(DetectWindowEnd(trial.signal, {}), truth.t0_s + phase4.t_end_s, kWindowEndToleranceS);
}

INSTANTIATE_TEST_SUITE_P(Trials, InitialGuessOnSynthetic,
                         ::testing::Values(Truth{0.5, 0.197, 2.185, -2.032, 0.197}, Truth{0.7, 0.17, 1.3, 3.5, 1.2},
                                           Truth{0.43, 0.22, 1.9, 1.6, 1.0}));

TEST(InitialGuess, FixedParametersKeepTheirValues) {
  const core::Block block = PaperBlock(0.035);
  const testing::SyntheticSignal trial = MakeTrial(block, {0.5, 0.197, 2.185, -2.032, 0.197}, 13);
  ParameterSet base = ParameterSet::Defaults();
  base[ParameterId::kLambdaLon].value = 0.3;
  base[ParameterId::kLambdaLon].fixed = true;
  EXPECT_EQ(EstimateInitialGuess(trial.signal, block, base).parameters.value(ParameterId::kLambdaLon), 0.3);
}

TEST(InitialGuess, ReleaseAloneIsClampedAndKeepsAFixedValueAsTheFullEstimate) {
  const core::Block block = PaperBlock(0.035);
  const testing::SyntheticSignal trial = MakeTrial(block, {0.5, 0.197, 2.185, -2.032, 0.197}, 13);
  ParameterSet bounded = ParameterSet::Defaults();
  bounded[ParameterId::kT0].upper = 0.45;  // before the fitted release (≈ 0.5 s): the estimate is clamped to it
  EXPECT_EQ(EstimateRelease(trial.signal, block, bounded).t0_s, 0.45);
  EXPECT_EQ(EstimateRelease(trial.signal, block, bounded).t0_s,
            EstimateInitialGuess(trial.signal, block, bounded).parameters.value(ParameterId::kT0));
  ParameterSet fixed = ParameterSet::Defaults();
  fixed[ParameterId::kT0].value = 0.123;
  fixed[ParameterId::kT0].fixed = true;
  EXPECT_EQ(EstimateRelease(trial.signal, block, fixed).t0_s, 0.123);
}

TEST(InitialGuess, RecordingWithoutImpactIsBadInput) {
  MeasuredSignal quiet;
  for (int k = 0; k < 512; ++k) {
    quiet.t_s.push_back(k / 256.0);
    quiet.w_B.push_back(Eigen::Vector3d(0.0, 1e-4 * (k % 3), 0.0));
  }
  EXPECT_THROW(EstimateInitialGuess(quiet, PaperBlock(0.035), ParameterSet::Defaults()), BadInput);
  EXPECT_THROW(EstimateRelease(quiet, PaperBlock(0.035), ParameterSet::Defaults()), BadInput);
}

}  // namespace
}  // namespace rockfit::fitting
