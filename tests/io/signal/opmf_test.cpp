#include "rockfit/io/opmf.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rocking_signals.hpp"
#include "rockfit/io/drift_correction.hpp"

namespace rockfit::io {
namespace {

using testing::PaperLikeBlock;
using testing::PlanarRockingSpec;
using testing::SimulatePlanarRocking;

OpmfResult OpmfOf(const testing::MeasuredRecording& measured) {
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  return ComputeOpmf(measured.recording.t_s, c.euler_corrected_zyx, !c.impacts_y.empty(), c.first_impact_s(),
                     c.last_impact_s());
}

// max|φx| / max|φy| of the true angles between the first and last impact.
double TrueOpmf(const testing::PlanarRocking& motion, const testing::MeasuredRecording& measured, double t_last) {
  double max_x = 0.0, max_y = 0.0;
  for (std::size_t k = 0; k < motion.t_s.size(); ++k) {
    if (motion.t_s[k] < motion.impact_times_s.front() || motion.t_s[k] > t_last) continue;
    max_x = std::max(max_x, std::abs(measured.true_euler_zyx[k][2]));
    max_y = std::max(max_y, std::abs(measured.true_euler_zyx[k][1]));
  }
  return max_x / max_y;
}

TEST(Opmf, IsTheRatioOfTheLargestAnglesAfterTheFirstImpact) {
  // Defining formula on a hand-made signal: before the impact at t = 1 the larger φx does not count, nor after
  // the last impact at t = 4.
  const std::vector<double> t{0, 1, 2, 3, 4, 5};
  const std::vector<Eigen::Vector3d> e{{0, 0.5, 0.9}, {0, 0, 0}, {0, -0.2, 0.01}, {0, 0.1, -0.03}, {0, 0, 0}, {0, 0.3, 0.3}};
  const OpmfResult r = ComputeOpmf(t, e, true, 1.0, 4.0);
  ASSERT_TRUE(r.ok());
  EXPECT_DOUBLE_EQ(r.opmf, 0.03 / 0.2);
  EXPECT_DOUBLE_EQ(r.t_phi_x_max_s, 3.0);
  EXPECT_DOUBLE_EQ(r.t_phi_y_max_s, 2.0);
}

TEST(Opmf, PlanarMotionHasZeroOpmfWithoutNoise) {
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const OpmfResult r = OpmfOf(testing::MeasurePlanar(motion, spec.rate_hz, testing::LinearDriftOnly()));
  ASSERT_TRUE(r.ok());
  // Linear drift of φx is removed to the anchor accuracy (3e-5 rad) out of max|φy| ≈ 0.155 rad.
  EXPECT_LT(r.opmf, 3e-5 / 0.155);
}

TEST(Opmf, PlanarMotionHasZeroOpmfWithinTheNoise) {
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const testing::MeasurementModel model = testing::RealisticImu();
  const OpmfResult r = OpmfOf(testing::MeasurePlanar(motion, spec.rate_hz, model));
  ASSERT_TRUE(r.ok());
  // What is left of φx is the angle random walk between anchors (≤ 0.6 s apart: a Brownian bridge with
  // σ ≤ 5e-4·√0.15 ≈ 2e-4 rad, 4σ = 8e-4 rad) plus the anchor error of the same size.
  const double noise_rad = 4.0 * model.random_walk_rad_per_sqrt_s * std::sqrt(0.6 / 4.0) * std::sqrt(2.0);
  EXPECT_LT(r.max_abs_phi_x_rad, noise_rad);
  EXPECT_LT(r.opmf, noise_rad / r.max_abs_phi_y_rad);
}

TEST(Opmf, ThreeDimensionalMotionMatchesTheTrueRatioWithoutNoise) {
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::Measure3d(motion, spec.rate_hz, 0.05, testing::LinearDriftOnly());
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  const OpmfResult r = OpmfOf(measured);
  ASSERT_TRUE(r.ok());
  const double truth = TrueOpmf(motion, measured, c.last_impact_s());
  EXPECT_GT(truth, 0.05);
  EXPECT_NEAR(r.opmf / truth, 1.0, 1e-3);
}

TEST(Opmf, ThreeDimensionalMotionMatchesTheTrueRatioToFivePercentWithRealisticNoise) {
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const auto measured = testing::Measure3d(motion, spec.rate_hz, 0.1, testing::RealisticImu(seed));
    const DriftCorrection c = CorrectDrift(measured.recording, {});
    const OpmfResult r = OpmfOf(measured);
    ASSERT_TRUE(r.ok());
    const double truth = TrueOpmf(motion, measured, c.last_impact_s());
    EXPECT_NEAR(r.opmf / truth, 1.0, 0.05) << "seed " << seed;
  }
}

TEST(Opmf, NoImpactAndNoInPlaneMotionAreStatusesNotNumbers) {
  const std::vector<double> t{0, 1, 2};
  const std::vector<Eigen::Vector3d> e(3, Eigen::Vector3d::Zero());
  const OpmfResult none = ComputeOpmf(t, e, false, 0.0, 0.0);
  EXPECT_EQ(none.status, OpmfStatus::kNoImpact);
  EXPECT_FALSE(none.message.empty());
  const OpmfResult flat = ComputeOpmf(t, e, true, 0.0, 2.0);
  EXPECT_EQ(flat.status, OpmfStatus::kNoInPlaneMotion);
  EXPECT_STREQ(ToString(flat.status), "no_in_plane_motion");
}

}  // namespace
}  // namespace rockfit::io
