// The gyro at rest before the release (rest_noise.hpp): a known bias and white noise are recovered, the segment
// ends the margin before the release, and a short rest is not used.
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
  // A jump of ω at 1.0 s (the release) must not enter a segment that ends 50 ms before a release at 1.0 s.
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s.t_s[k] >= 0.96) s.w_B[k] += Eigen::Vector3d(0, 1.0, 0);
  }
  const RestNoise rest = MeasureRestNoise(s, 1.0);
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
}

}  // namespace
}  // namespace rockfit::fitting
