#include "rockfit/io/trial_metrics.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rocking_signals.hpp"

namespace rockfit::io {
namespace {

TEST(TrialMetrics, PlanarTrialGivesBothMetrics) {
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu());
  const MetricsSummary s = ComputeTrialMetrics(measured.recording, block, {});
  EXPECT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(s.status, MetricsStatus::kOk);
  EXPECT_TRUE(s.opmf.ok());
  EXPECT_TRUE(s.avrf.ok());
  EXPECT_NEAR(s.avrf.avrf, motion.r, 1e-2);
}

TEST(TrialMetrics, WithoutABlockOnlyTheOpmfIsComputed) {
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, {});
  const MetricsSummary s = ComputeTrialMetrics(measured.recording, std::nullopt, {});
  EXPECT_TRUE(s.opmf.ok());
  EXPECT_EQ(s.avrf.status, AvrfStatus::kNoBlock);
  EXPECT_EQ(s.status, MetricsStatus::kNoBlock);
  EXPECT_NE(s.message.find("--b1"), std::string::npos);
}

TEST(TrialMetrics, TheFirstFailingMetricNamesTheStatus) {
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  spec.release_s = 100.0;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  const MetricsSummary s = ComputeTrialMetrics(testing::MeasurePlanar(motion, spec.rate_hz, {}).recording, block, {});
  EXPECT_EQ(s.status, MetricsStatus::kNoImpact);
  EXPECT_FALSE(s.message.empty());
}

// ---- recordings of the hybrid simulator (core/simulator.hpp)

// A released block like the paper's: α = 0.2 rad, λ_lon of the facet impacts, λ of the edge impacts.
core::ModelParameters Released(double lambda_lat, double lambda_lon) {
  core::ModelParameters p;
  p.alpha_rad = 0.2;
  p.lambda = 0.8;
  p.lambda_lat = lambda_lat;
  p.lambda_lon = lambda_lon;
  return p;
}

// max|φx| / max|φy| of the simulated angles between two times of the recording.
double SimulatedOpmf(const testing::MeasuredRecording& m, double from_s, double to_s) {
  double max_x = 0.0, max_y = 0.0;
  for (std::size_t k = 0; k < m.recording.size(); ++k) {
    if (m.recording.t_s[k] < from_s || m.recording.t_s[k] > to_s) continue;
    max_x = std::max(max_x, std::abs(m.true_euler_zyx[k][2]));
    max_y = std::max(max_y, std::abs(m.true_euler_zyx[k][1]));
  }
  return max_x / max_y;
}

TEST(TrialMetricsOfSimulatedRocking, PlanarRockingGivesChatzisAvrfOfLambdaLon) {
  // λ_lat = 0: every facet impact is the planar map (6) with λ = λ_lon, b = b1, θ = Θ_yy (docs/design.md §3).
  const core::Block block = testing::PaperLikeBlock(0.05);
  for (double lambda_lon : {0.3, 0.6, 1.0}) {
    core::Trajectory run;
    const auto m = testing::MeasureSimulated(block, Released(0.0, lambda_lon), 0.5, 8.0, 256.0,
                                             testing::LinearDriftOnly(), &run);
    ASSERT_EQ(run.end_reason, core::EndReason::kTMax) << run.message;
    const MetricsSummary s = ComputeTrialMetrics(m.recording, block, {});
    ASSERT_TRUE(s.ok()) << s.message;
    EXPECT_NEAR(s.avrf.avrf, testing::ChatzisAvrfAboutY(block, lambda_lon), 2e-3) << "λ_lon = " << lambda_lon;
    EXPECT_LT(s.opmf.opmf, 1e-3);
  }
}

TEST(TrialMetricsOfSimulatedRocking, PlanarRockingWithRealisticImuErrors) {
  const core::Block block = testing::PaperLikeBlock(0.05);
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const auto m = testing::MeasureSimulated(block, Released(0.0, 0.6), 0.5, 8.0, 256.0, testing::RealisticImu(seed));
    const MetricsSummary s = ComputeTrialMetrics(m.recording, block, {});
    ASSERT_TRUE(s.ok()) << s.message;
    EXPECT_NEAR(s.avrf.avrf, testing::ChatzisAvrfAboutY(block, 0.6), 1e-2) << "seed " << seed;
    EXPECT_LT(s.opmf.opmf, 0.01) << "seed " << seed;  // zero within the noise (opmf_test: ≤ 8e-4 rad / 0.15 rad)
  }
}

TEST(TrialMetricsOfSimulatedRocking, OpmfOfThreeDimensionalRockingMatchesTheSimulatedAngles) {
  // Paper-like out-of-plane motion (Φ ≈ 0.03 … 0.08). The drift correction sees only the gyro and the drifting
  // angles; the truth is the simulator's Euler angles.
  struct Case {
    double b2_m, lambda_lat;
  };
  for (const Case c : {Case{0.05, 2.0}, Case{0.05, 3.0}, Case{0.05, -3.0}, Case{0.08, 2.0}}) {
    const core::Block block = testing::PaperLikeBlock(c.b2_m);
    for (std::uint32_t seed : {0u, 7u}) {
      const testing::MeasurementModel model = seed == 0 ? testing::LinearDriftOnly() : testing::RealisticImu(seed);
      const auto m = testing::MeasureSimulated(block, Released(c.lambda_lat, 0.6), 0.5, 8.0, 256.0, model);
      const MetricsSummary s = ComputeTrialMetrics(m.recording, block, {});
      ASSERT_TRUE(s.opmf.ok()) << s.opmf.message;
      const double truth = SimulatedOpmf(m, s.correction.first_impact_s(), s.correction.last_impact_s());
      EXPECT_GT(truth, 0.02);
      EXPECT_NEAR(s.opmf.opmf / truth, 1.0, 0.05)
          << "b2 = " << c.b2_m << ", λ_lat = " << c.lambda_lat << (seed ? ", realistic IMU errors" : ", drift only");
    }
  }
}

TEST(TrialMetricsOfSimulatedRocking, TiltedRollingPeaksOfOmegaYAreNotImpacts) {
  // λ_lat = 3 on b2 = 5 cm: right after the first facet impact the block, tilted by 0.15 rad about y, rolls from
  // V3 to V4 and back, and |ω_y| peaks there although φ_y is far from zero.
  const core::Block block = testing::PaperLikeBlock(0.05);
  const auto m = testing::MeasureSimulated(block, Released(3.0, 0.6), 0.5, 8.0, 256.0, {});
  const DriftCorrection c = CorrectDrift(m.recording, {});
  EXPECT_GT(c.rejected_y, 0u);
  for (const Anchor& a : c.impacts_y) {
    EXPECT_LT(std::abs(m.true_euler_zyx[a.index][1]), 0.012) << "impact at " << a.t_s << " s";  // ≤ |ω|Δt
  }
  for (std::size_t k = 0; k < m.recording.size(); ++k) {
    const double t = m.recording.t_s[k];
    if (t < c.first_impact_s() || t > c.last_impact_s()) continue;
    ASSERT_NEAR(c.euler_corrected_zyx[k][1], m.true_euler_zyx[k][1], 2e-3) << "t = " << t;
  }
}

}  // namespace
}  // namespace rockfit::io
