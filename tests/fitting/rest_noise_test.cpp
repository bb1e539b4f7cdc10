// The gyro at rest before the release (rest_noise.hpp): a known bias and white noise are recovered, the segment
// ends the margin before the release — or before a motion that runs into it —, and a short rest is not used.
#include "rockfit/fitting/rest_noise.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "synthetic_signal.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kRateHz = 256.0;

// A recording at rest of `duration_s` with bias `bias_rad_s` and white noise σ per axis.
MeasuredSignal RestSignal(double duration_s, const Eigen::Vector3d& bias_rad_s, double sigma_rad_s, std::uint64_t seed) {
  MeasuredSignal s;
  std::mt19937_64 rng(seed);
  for (int k = 0; k < static_cast<int>(duration_s * kRateHz); ++k) {
    s.t_s.push_back(k / kRateHz);
    Eigen::Vector3d w = bias_rad_s;
    for (int c = 0; c < 3; ++c) w[c] += sigma_rad_s * testing::NormalDeviate(rng);
    s.w_B.push_back(w);
  }
  return s;
}

TEST(RestNoise, RecoversAKnownBiasNoiseVarianceAndTheNoiseFloorOfTheError28) {
  const Eigen::Vector3d bias(0.005, -0.003, 0.002);
  const double sigma = 0.0017;  // 0.1 deg/s, the x-IMU's gyro noise
  const MeasuredSignal s = RestSignal(20.0, bias, sigma, 5);
  const RestNoise rest = MeasureRestNoise(s, 19.0);
  ASSERT_TRUE(rest.available);
  const double n = static_cast<double>(rest.samples);
  EXPECT_NEAR(n, (19.0 - 0.05) * kRateHz, 1.0);
  // Bias within 4 standard errors of a mean, variance within 10 % (n ≈ 4850: its relative sd is 2 %).
  EXPECT_LT((rest.mean_rad_s - bias).cwiseAbs().maxCoeff(), 4.0 * sigma / std::sqrt(n));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rest.variance_rad2_s2[c], sigma * sigma, 0.1 * sigma * sigma);
  // The mean norm of an isotropic Gaussian 3-vector is σ·2√(2/π).
  EXPECT_NEAR(rest.epsilon_floor_rad_s, sigma * 2.0 * std::sqrt(2.0 / M_PI), 0.03 * sigma);
}

TEST(RestNoise, SegmentEndsTheMarginBeforeTheReleaseAndShortRestsAreNotUsed) {
  MeasuredSignal s = RestSignal(2.0, Eigen::Vector3d::Zero(), 0.001, 6);
  // A jump of ω at 0.96 s must not enter a segment that ends 50 ms before a release at 1.0 s (with the rest never
  // cut short at a motion, still_rate 0).
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s.t_s[k] >= 0.96) s.w_B[k] += Eigen::Vector3d(0, 1.0, 0);
  }
  const RestNoise rest = MeasureRestNoise(s, 1.0, {0.05, 0.1, 0.0});
  ASSERT_TRUE(rest.available);
  EXPECT_LT(s.t_s[rest.samples - 1], 0.95);
  EXPECT_GE(s.t_s[rest.samples], 0.95);
  EXPECT_LT(std::abs(rest.mean_rad_s.y()), 0.001);
  EXPECT_NEAR(rest.duration_s, 0.95, 1e-12);

  const RestNoise short_rest = MeasureRestNoise(s, 0.14);  // 0.09 s of rest < 0.1 s
  EXPECT_FALSE(short_rest.available);
  EXPECT_FALSE(MeasureRestNoise(s, 0.0).available);
  EXPECT_FALSE(MeasureRestNoise(MeasuredSignal{}, 1.0).available);
  EXPECT_THROW(MeasureRestNoise(s, 1.0, {-0.1, 0.1}), InvalidArgument);
  EXPECT_THROW(MeasureRestNoise(s, 1.0, {0.05, 0.1, -0.03}), InvalidArgument);
}

TEST(RestNoise, AMotionRunningIntoTheReleaseIsLeftOutOfTheRestWithItsMargin) {
  // A bias and the x-IMU's noise, then from 0.9 s a push at 0.2 rad/s about y that a late release at 1.0 s lies
  // in (a block pushed as it was let go, fitted as a release from rest later: motion_before_release.hpp).
  const Eigen::Vector3d bias(0.004, -0.002, 0.001);
  const double sigma = 0.0017;
  MeasuredSignal s = RestSignal(2.0, bias, sigma, 8);
  const double t_push = 0.9;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s.t_s[k] >= t_push) s.w_B[k] += Eigen::Vector3d(0, 0.2, 0);
  }
  const RestNoise whole = MeasureRestNoise(s, 1.0, {0.05, 0.1, 0.0});
  const RestNoise cut = MeasureRestNoise(s, 1.0);
  ASSERT_TRUE(cut.available);
  // The rest ends the margin before the push's first sample (231/256 s), 0.0977 s earlier than 0.95 s.
  const double t_first = std::ceil(t_push * kRateHz) / kRateHz;
  EXPECT_NEAR(cut.duration_s, t_first - 0.05, 1e-12);
  EXPECT_NEAR(cut.cut_before_release_s, 0.95 - (t_first - 0.05), 1e-12);
  EXPECT_LT(s.t_s[cut.samples - 1], t_first - 0.05);
  EXPECT_GE(s.t_s[cut.samples], t_first - 0.05);
  // Its bias and noise floor are the sensor's; the whole stretch's carry the push (0.05 s of 0.2 rad/s in 0.95 s).
  EXPECT_LT((cut.mean_rad_s - bias).cwiseAbs().maxCoeff(), 4.0 * sigma / std::sqrt(static_cast<double>(cut.samples)));
  EXPECT_NEAR(whole.mean_rad_s.y() - bias.y(), 0.2 * 0.05 / 0.95, 0.001);
  EXPECT_NEAR(cut.epsilon_floor_rad_s, sigma * 2.0 * std::sqrt(2.0 / M_PI), 0.1 * sigma);
  EXPECT_GT(whole.epsilon_floor_rad_s, 2.0 * cut.epsilon_floor_rad_s);
  // Still at the release: the rest is not cut (the same to the last bit as without the rule).
  const RestNoise still = MeasureRestNoise(s, 0.8);
  const RestNoise still_whole = MeasureRestNoise(s, 0.8, {0.05, 0.1, 0.0});
  EXPECT_EQ(still.cut_before_release_s, 0.0);
  EXPECT_EQ(still.samples, still_whole.samples);
  EXPECT_EQ(still.mean_rad_s, still_whole.mean_rad_s);
  EXPECT_EQ(still.epsilon_floor_rad_s, still_whole.epsilon_floor_rad_s);
  // A cut that would leave less than the minimum duration is not made: the stretch is kept whole.
  const RestNoise short_cut = MeasureRestNoise(s, 1.0, {0.05, 0.9, 0.03});
  EXPECT_EQ(short_cut.cut_before_release_s, 0.0);
  EXPECT_EQ(short_cut.samples, whole.samples);
}

}  // namespace
}  // namespace rockfit::fitting
