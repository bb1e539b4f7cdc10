#include "rockfit/io/impact_anchor.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rocking_signals.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/impact_detection.hpp"

namespace rockfit::io {
namespace {

using testing::PaperLikeBlock;
using testing::PlanarRockingSpec;
using testing::SimulatePlanarRocking;

struct Channels {
  std::vector<double> t, angle, rate;
};

Channels PhiY(const Recording& rec) {
  Channels c;
  c.t = rec.t_s;
  for (std::size_t i = 0; i < rec.size(); ++i) {
    c.angle.push_back(rec.euler_zyx[i][1]);
    c.rate.push_back(rec.w_B[i].y());
  }
  return c;
}

// Without noise the impact time and the drift there come out to the accuracy of the rate parabolas:
// 2e-5 s is 0.5 % of a sample period, 2e-5 rad is 1e-3 of the angle swept in one sample at 1.4 rad/s.
constexpr double kCleanTimeTolerance = 2e-5;   // s
constexpr double kCleanValueTolerance = 2e-5;  // rad

TEST(ImpactAnchor, LocatesImpactsInsideTheSampleIntervalUnderLinearDrift) {
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::LinearDriftOnly());
  const Channels c = PhiY(measured.recording);
  const std::vector<Peak> peaks = DetectRatePeaks(measured.recording, 1, {});
  ASSERT_GE(peaks.size(), 30u);
  const double dt = 1.0 / spec.rate_hz;
  std::size_t located = 0;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const AnchorEstimate a = EstimateAnchor(c.t, c.angle, c.rate, peaks[i].index, {});
    ASSERT_TRUE(a.subsample);
    std::size_t j = 0;
    for (std::size_t k = 1; k < motion.impact_times_s.size(); ++k) {
      if (std::abs(motion.impact_times_s[k] - a.t_s) < std::abs(motion.impact_times_s[j] - a.t_s)) j = k;
    }
    const double t_true = motion.impact_times_s[j];
    const double drift_true = 0.03 + 0.0175 * t_true;  // linear drift: offset + rate·t
    const double jump = (1.0 - motion.r) * std::abs(motion.omega_minus_rad_s[j]);
    if (jump > 1.5 * AnchorFitOptions{}.min_rate_jump_rad_s) {
      EXPECT_TRUE(a.located) << "impact " << j;
      located += 1;
      EXPECT_NEAR(a.t_s, t_true, kCleanTimeTolerance) << "impact " << j;
      EXPECT_NEAR(a.value_rad, drift_true, kCleanValueTolerance) << "impact " << j;
    } else {
      // A jump near the threshold may fall back to the middle of the interval: half a sample at most.
      EXPECT_NEAR(a.t_s, t_true, 0.5 * dt) << "impact " << j;
      EXPECT_NEAR(a.value_rad, drift_true, 0.5 * dt * std::abs(motion.omega_minus_rad_s[j]) + kCleanValueTolerance);
    }
  }
  EXPECT_GE(located, 30u);
}

TEST(ImpactAnchor, WithAKnownImpactTimeOnlyTheValueIsEstimated) {
  PlanarRockingSpec spec;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::LinearDriftOnly());
  const Channels c = PhiY(measured.recording);
  const std::vector<Peak> peaks = DetectRatePeaks(measured.recording, 1, {});
  ASSERT_FALSE(peaks.empty());
  const double t_true = motion.impact_times_s[0];
  const AnchorEstimate a = EstimateAnchor(c.t, c.angle, c.rate, peaks[0].index, {}, t_true);
  EXPECT_DOUBLE_EQ(a.t_s, t_true);
  EXPECT_NEAR(a.value_rad, 0.03 + 0.0175 * t_true, kCleanValueTolerance);
}

TEST(ImpactAnchor, WithoutARateJumpTheMiddleOfTheIntervalIsUsed) {
  // A straight line with constant rate: nothing marks an impact inside the interval.
  std::vector<double> t, angle, rate;
  for (int k = 0; k < 40; ++k) {
    t.push_back(k * 0.01);
    angle.push_back(0.5 * k * 0.01);
    rate.push_back(0.5);
  }
  const AnchorEstimate a = EstimateAnchor(t, angle, rate, 20, {});
  EXPECT_FALSE(a.located);
  EXPECT_NEAR(a.t_s, 0.205, 1e-12);
  // No drift: the fitted angle there is the line's value.
  EXPECT_NEAR(a.value_rad, 0.5 * 0.205, 1e-12);
}

TEST(ImpactAnchor, NearTheEndsOfTheRecordingTheSampleValueIsUsed) {
  std::vector<double> t{0.0, 0.01, 0.02, 0.03}, angle{0.1, 0.2, 0.3, 0.4}, rate{1, 1, 1, 1};
  const AnchorEstimate a = EstimateAnchor(t, angle, rate, 1, {});
  EXPECT_FALSE(a.subsample);
  EXPECT_DOUBLE_EQ(a.t_s, 0.01);
  EXPECT_DOUBLE_EQ(a.value_rad, 0.2);
}

TEST(ImpactAnchor, MismatchedInputsAndBadOptionsAreRejected) {
  std::vector<double> t{0.0, 0.01, 0.02}, angle{0.1, 0.2}, rate{1, 1, 1};
  EXPECT_THROW(EstimateAnchor(t, angle, rate, 1, {}), InvalidArgument);
  AnchorFitOptions bad;
  bad.half_window_samples = 2;
  EXPECT_THROW(bad.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
