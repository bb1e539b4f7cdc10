#include "rockfit/io/drift_correction.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rocking_signals.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

using testing::PaperLikeBlock;
using testing::PlanarRockingSpec;
using testing::SimulatePlanarRocking;

// Index of the true impact nearest to t.
std::size_t NearestImpact(const testing::PlanarRocking& motion, double t) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < motion.impact_times_s.size(); ++i) {
    if (std::abs(motion.impact_times_s[i] - t) < std::abs(motion.impact_times_s[best] - t)) best = i;
  }
  return best;
}

PlanarRockingSpec LongSpec() {
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  return spec;
}

TEST(DriftCorrection, LinearDriftIsRemovedToTheAccuracyOfTheAnchors) {
  const PlanarRockingSpec spec = LongSpec();
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::LinearDriftOnly());
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  ASSERT_GE(c.impacts_y.size(), 30u);
  // Everywhere between the first and last impact, not only at the anchors: the drift is linear, the
  // interpolant through exact anchors is exact. 3e-5 rad: the anchor accuracy (impact_anchor_test).
  constexpr double kTolerance = 3e-5;
  for (std::size_t k = 0; k < measured.recording.size(); ++k) {
    const double t = measured.recording.t_s[k];
    if (t < c.first_impact_s() || t > c.last_impact_s()) continue;
    ASSERT_NEAR(c.euler_corrected_zyx[k][1], measured.true_euler_zyx[k][1], kTolerance) << "t = " << t;
    ASSERT_NEAR(c.euler_corrected_zyx[k][2], 0.0, kTolerance) << "t = " << t;
    // φz is left as measured.
    ASSERT_EQ(c.euler_corrected_zyx[k][0], measured.recording.euler_zyx[k][0]);
  }
  // Raw angles are kept untouched.
  EXPECT_EQ(c.euler_raw_zyx, measured.recording.euler_zyx);
}

TEST(DriftCorrection, CorrectedAnglesAreWithinTheNoiseOfTheTruthAtTheAnchorsWithRealisticImuErrors) {
  const PlanarRockingSpec spec = LongSpec();
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const testing::MeasurementModel model = testing::RealisticImu();
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, model);
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  ASSERT_GE(c.impacts_y.size(), 30u);
  // The noise of an anchor: the impact lies anywhere inside a sample interval, and where ringing and gyro
  // noise hide the rate jump it is placed at the middle — a timing error uniform over Δt, σ = |ω⁻|Δt/√12 —
  // plus the angle random walk over the ±20 ms fit window.
  const double dt = 1.0 / spec.rate_hz;
  double sum_sq_error = 0.0, sum_sq_noise = 0.0;
  for (const Anchor& a : c.impacts_y) {
    const double w_minus = std::abs(motion.omega_minus_rad_s[NearestImpact(motion, a.t_s)]);
    const double noise = std::hypot(w_minus * dt / std::sqrt(12.0), model.random_walk_rad_per_sqrt_s * std::sqrt(0.04));
    const double error = c.euler_corrected_zyx[a.index][1] - measured.true_euler_zyx[a.index][1];
    EXPECT_LT(std::abs(error), 4.0 * noise) << "anchor at t = " << a.t_s;
    sum_sq_error += error * error;
    sum_sq_noise += noise * noise;
  }
  EXPECT_LT(std::sqrt(sum_sq_error), std::sqrt(sum_sq_noise));
}

TEST(DriftCorrection, SubsampleAnchorsBeatThePapersSampleAnchors) {
  const PlanarRockingSpec spec = LongSpec();
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu());
  const auto rms_error = [&](AnchorMethod method) {
    DriftCorrectionOptions options;
    options.anchor_method = method;
    const DriftCorrection c = CorrectDrift(measured.recording, options);
    double sum = 0.0;
    for (const Anchor& a : c.impacts_y) {
      sum += std::pow(c.euler_corrected_zyx[a.index][1] - measured.true_euler_zyx[a.index][1], 2);
    }
    return std::sqrt(sum / static_cast<double>(c.impacts_y.size()));
  };
  EXPECT_LT(rms_error(AnchorMethod::kSubsample), 0.75 * rms_error(AnchorMethod::kSample));
}

TEST(DriftCorrection, SampleAnchorsZeroTheAngleAtThePeakSamples) {
  // The paper's literal rule: the corrected φ_y is 0 at each sample where |ω_y| peaks.
  const PlanarRockingSpec spec = LongSpec();
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu());
  DriftCorrectionOptions options;
  options.anchor_method = AnchorMethod::kSample;
  const DriftCorrection c = CorrectDrift(measured.recording, options);
  ASSERT_FALSE(c.impacts_y.empty());
  for (const Anchor& a : c.impacts_y) {
    EXPECT_DOUBLE_EQ(a.t_s, measured.recording.t_s[a.index]);
    EXPECT_NEAR(c.euler_corrected_zyx[a.index][1], 0.0, 1e-15);
  }
}

TEST(DriftCorrection, PlanarMotionAnchorsPhiXAtTheOmegaYImpacts) {
  const PlanarRockingSpec spec = LongSpec();
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu());
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  EXPECT_EQ(c.omega_x_peaks, 0u);
  ASSERT_EQ(c.anchors_x.size(), c.impacts_y.size());
  for (std::size_t i = 0; i < c.anchors_x.size(); ++i) {
    EXPECT_EQ(c.anchors_x[i].source, AnchorSource::kOmegaY);
    EXPECT_DOUBLE_EQ(c.anchors_x[i].t_s, c.impacts_y[i].t_s);
  }
}

TEST(DriftCorrection, ThreeDimensionalMotionAnchorsPhiXAtOmegaXPeaks) {
  const PlanarRockingSpec spec = LongSpec();
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::Measure3d(motion, spec.rate_hz, 0.1, testing::LinearDriftOnly());
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  EXPECT_GT(c.omega_x_peaks, 10u);
  for (std::size_t k = 0; k < measured.recording.size(); ++k) {
    const double t = measured.recording.t_s[k];
    if (t < c.first_impact_s() || t > c.last_impact_s()) continue;
    ASSERT_NEAR(c.euler_corrected_zyx[k][2], measured.true_euler_zyx[k][2], 3e-5) << "t = " << t;
  }
}

TEST(DriftCorrection, InterpolantIsPiecewiseLinearAndConstantOutside) {
  std::vector<Anchor> anchors(2);
  anchors[0].t_s = 1.0;
  anchors[0].value_rad = 0.1;
  anchors[1].t_s = 3.0;
  anchors[1].value_rad = 0.5;
  EXPECT_DOUBLE_EQ(DriftAt(anchors, 0.0), 0.1);
  EXPECT_DOUBLE_EQ(DriftAt(anchors, 2.0), 0.3);
  EXPECT_DOUBLE_EQ(DriftAt(anchors, 9.0), 0.5);
  EXPECT_DOUBLE_EQ(DriftAt({}, 2.0), 0.0);
}

TEST(DriftCorrection, WithoutImpactsTheAnglesStayAsMeasuredWithAWarning) {
  PlanarRockingSpec spec;
  spec.release_s = 100.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu());
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  EXPECT_TRUE(c.impacts_y.empty());
  EXPECT_EQ(c.euler_corrected_zyx, measured.recording.euler_zyx);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("no impact"), std::string::npos);
}

TEST(DriftCorrection, RecordingWithoutEulerAnglesGetsThemFromItsGyro) {
  Recording rec;
  rec.source = "gyro-only.csv";
  rec.rate_hz = 256.0;
  rec.t_s = {0.0, 1.0 / 256.0};
  rec.w_B = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  const DriftCorrection c = CorrectDrift(rec, {});
  ASSERT_EQ(c.euler_raw_zyx.size(), 2u);
  EXPECT_NE(c.attitude.find("integrated from the gyro"), std::string::npos);
  ASSERT_FALSE(c.warnings.empty());
  EXPECT_NE(c.warnings.front().find("no attitude"), std::string::npos);
}

TEST(DriftCorrection, AnEmptyRecordingIsBadInput) {
  Recording rec;
  rec.source = "empty.csv";
  rec.rate_hz = 256.0;
  try {
    CorrectDrift(rec, {});
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("empty.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace rockfit::io
