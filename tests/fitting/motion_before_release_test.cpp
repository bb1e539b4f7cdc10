// The motion before the fitted release (motion_before_release.hpp) against closed forms: a block turning at a
// constant rate or a uniformly growing one before t0 turns by ω·Δt or ½·θ̈·Δt², a block still before t0 by nothing
// but its noise, and the stretch looked at ends at the recording's first sample.
#include "rockfit/fitting/motion_before_release.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kRateHz = 256.0;
constexpr double kDegPerRad = 180.0 / M_PI;

// 2 s at 256 Hz whose ω_y is rate(t).
template <typename Rate>
MeasuredSignal Signal(Rate rate) {
  MeasuredSignal s;
  for (int k = 0; k < 512; ++k) {
    const double t = k / kRateHz;
    s.t_s.push_back(t);
    s.w_B.emplace_back(0.0, rate(t), 0.0);
  }
  return s;
}

TEST(MotionBeforeRelease, AConstantRateBeforeT0TurnsByRateTimesTheLookback) {
  const double rate_rad_s = -0.2;  // a hand's push away from the fall
  const MeasuredSignal s = Signal([&](double) { return rate_rad_s; });
  const MotionBeforeRelease m = MeasureMotionBeforeRelease(s, 1.0);
  ASSERT_TRUE(m.available);
  EXPECT_DOUBLE_EQ(m.lookback_s, 0.1);
  EXPECT_NEAR(m.turn_deg, 0.2 * 0.1 * kDegPerRad, 1e-12);
  EXPECT_NEAR(m.rate_at_release_rad_s, 0.2, 1e-15);
  EXPECT_TRUE(m.moving);
}

TEST(MotionBeforeRelease, AUniformlyGrowingRateTurnsByHalfTheAccelerationTimesTheSquaredTime) {
  // ω = θ̈·(t − t_p) after t_p: ∫ from t_p to t0 is ½·θ̈·(t0 − t_p)², exact for the trapezoids of a linear ω,
  // also where t0 lies between samples.
  const double accel_rad_s2 = 2.5, t_p = 1.0;
  const MeasuredSignal s = Signal([&](double t) { return t > t_p ? accel_rad_s2 * (t - t_p) : 0.0; });
  for (double t0 : {1.02, 1.0371, 1.09}) {
    const MotionBeforeRelease m = MeasureMotionBeforeRelease(s, t0);
    ASSERT_TRUE(m.available);
    EXPECT_NEAR(m.turn_deg, 0.5 * accel_rad_s2 * (t0 - t_p) * (t0 - t_p) * kDegPerRad, 1e-12) << t0;
    EXPECT_NEAR(m.rate_at_release_rad_s, accel_rad_s2 * (t0 - t_p), 1e-12) << t0;
  }
  // A release from rest fitted 5 ms late with this acceleration turns by 3.1e-5 rad (0.0018°): 1/56 of the warning.
  const MotionBeforeRelease late = MeasureMotionBeforeRelease(s, t_p + 0.005);
  EXPECT_LT(late.turn_deg, 0.05 * MotionBeforeReleaseOptions{}.warn_turn_deg);
  EXPECT_FALSE(late.moving);
}

TEST(MotionBeforeRelease, TheTurnIsTheFarthestFromTheReleaseNotTheNetTurn) {
  // Out and back within the lookback: the net turn is zero, the farthest the block was is not.
  const MeasuredSignal s = Signal([](double t) { return t < 0.95 ? 0.0 : (t < 0.975 ? 0.4 : (t < 1.0 ? -0.4 : 0.0)); });
  const MotionBeforeRelease m = MeasureMotionBeforeRelease(s, 1.05);
  EXPECT_GT(m.turn_deg, 0.5 * 0.4 * 0.025 * kDegPerRad);
  EXPECT_TRUE(m.moving);
}

TEST(MotionBeforeRelease, GyroNoiseAtRestStaysFarBelowTheWarning) {
  std::mt19937 rng(17);
  std::normal_distribution<double> noise(0.0, 0.1 / kDegPerRad);  // 0.1 deg/s per axis, the x-IMU's
  MeasuredSignal s = Signal([](double) { return 0.0; });
  for (auto& w : s.w_B) w = Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const MotionBeforeRelease m = MeasureMotionBeforeRelease(s, 1.5);
  ASSERT_TRUE(m.available);
  EXPECT_LT(m.turn_deg, 0.1 * MotionBeforeReleaseOptions{}.warn_turn_deg);
  EXPECT_FALSE(m.moving);
}

TEST(MotionBeforeRelease, TheLookbackEndsAtTheFirstSampleAndNothingIsMeasuredWithoutOne) {
  const MeasuredSignal s = Signal([](double) { return 0.3; });
  const MotionBeforeRelease early = MeasureMotionBeforeRelease(s, 0.04);
  ASSERT_TRUE(early.available);
  EXPECT_DOUBLE_EQ(early.lookback_s, 0.04);
  EXPECT_NEAR(early.turn_deg, 0.3 * 0.04 * kDegPerRad, 1e-12);
  const MotionBeforeRelease at_start = MeasureMotionBeforeRelease(s, 0.0);
  EXPECT_FALSE(at_start.available);
  EXPECT_FALSE(at_start.moving);
  const nlohmann::json j = nlohmann::json::parse(MotionBeforeReleaseJson(at_start));
  EXPECT_TRUE(j["turn_deg"].is_null());
  EXPECT_TRUE(j["moving"].is_null());
  EXPECT_NE(MotionBeforeReleaseText(at_start).find("not measured"), std::string::npos);
}

TEST(MotionBeforeRelease, TheSentencesNameTheTurnInDegreesAndMradAndTheRate) {
  const MeasuredSignal s = Signal([](double) { return 0.2; });
  const MotionBeforeRelease m = MeasureMotionBeforeRelease(s, 1.0);
  const std::string warning = MotionBeforeReleaseWarning(m);
  EXPECT_NE(warning.find("1.15°"), std::string::npos) << warning;       // 0.02 rad
  EXPECT_NE(warning.find("20.0 mrad"), std::string::npos) << warning;
  EXPECT_NE(warning.find("0.2 rad/s"), std::string::npos) << warning;
  EXPECT_NE(warning.find("t0 = 1.0000 s"), std::string::npos) << warning;
  const nlohmann::json j = nlohmann::json::parse(MotionBeforeReleaseJson(m));
  EXPECT_NEAR(j["turn_deg"].get<double>(), m.turn_deg, 0.0);
  EXPECT_TRUE(j["moving"].get<bool>());
}

TEST(MotionBeforeRelease, BadOptionsAndAnUnknownT0AreRefused) {
  const MeasuredSignal s = Signal([](double) { return 0.0; });
  MotionBeforeReleaseOptions o;
  o.lookback_s = 0.0;
  EXPECT_THROW(MeasureMotionBeforeRelease(s, 1.0, o), InvalidArgument);
  o = {};
  o.warn_turn_deg = -1.0;
  EXPECT_THROW(MeasureMotionBeforeRelease(s, 1.0, o), InvalidArgument);
  EXPECT_THROW(MeasureMotionBeforeRelease(s, std::nan("")), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
