#include "recording/recording_assembly.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "recording/time_base.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

SensorSamples Samples(std::size_t n, double rate_hz) {
  SensorSamples samples;
  samples.t_s = UniformTimes(n, rate_hz);
  for (std::size_t k = 0; k < n; ++k) {
    samples.w_S.emplace_back(0.1 * static_cast<double>(k), 1.0, -2.0);
    samples.accel_S.emplace_back(0.0, 0.0, 9.81);
  }
  return samples;
}

TEST(AssembleRecording, AppliesTheMountingToGyroAccelerometerAndAttitude) {
  SensorSamples samples = Samples(4, 100.0);
  const Eigen::Vector3d euler_WS(0.3, -0.2, 0.1);
  samples.orientation.t_s = samples.t_s;
  samples.orientation.q_WS.assign(4, QuaternionFromEulerZyx(euler_WS));
  const Mounting mounting = Mounting::Parse("x,-y,-z");
  Recording recording;
  AssembleRecording(samples, mounting, recording);
  ASSERT_EQ(recording.size(), 4u);
  EXPECT_TRUE(recording.w_B[2].isApprox(Eigen::Vector3d(0.2, -1.0, 2.0)));
  EXPECT_TRUE(recording.accel_B[0].isApprox(Eigen::Vector3d(0.0, 0.0, -9.81)));
  const Eigen::Matrix3d R_WB = RotationFromEulerZyx(euler_WS) * mounting.R_BS().transpose();
  EXPECT_TRUE(RotationFromEulerZyx(recording.euler_zyx[3]).isApprox(R_WB, 1e-12));
  EXPECT_EQ(recording.mounting, "x,-y,-z");
}

TEST(AssembleRecording, DropsGyroSamplesOutsideTheAttitudeSpanWithAWarning) {
  SensorSamples samples = Samples(10, 10.0);
  samples.gaps = {{1, 0.1, 0.2, 1}, {5, 0.5, 0.2, 1}};
  for (int k = 2; k <= 7; ++k) {
    samples.orientation.t_s.push_back(k * 0.1);
    samples.orientation.q_WS.push_back(Eigen::Quaterniond::Identity());
  }
  Recording recording;
  recording.orientation_source = "E.csv";
  AssembleRecording(samples, Mounting(), recording);
  ASSERT_EQ(recording.size(), 6u);
  EXPECT_DOUBLE_EQ(recording.t_s.front(), 0.0);
  EXPECT_NEAR(recording.t_s.back(), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(recording.w_B.front().x(), 0.2);
  ASSERT_EQ(recording.gaps.size(), 1u);  // the gap after sample 1 lies outside
  EXPECT_EQ(recording.gaps[0].index, 3u);
  EXPECT_NEAR(recording.gaps[0].t_s, 0.3, 1e-12);
  ASSERT_EQ(recording.warnings.size(), 1u);
  EXPECT_THAT(recording.warnings[0], HasSubstr("the 2 samples before and 2 after it were dropped"));
}

TEST(AssembleRecording, RefusesAttitudeThatDoesNotOverlapTheGyroData) {
  SensorSamples samples = Samples(10, 10.0);
  samples.orientation.t_s = {5.0, 6.0};
  samples.orientation.q_WS.assign(2, Eigen::Quaterniond::Identity());
  Recording recording;
  recording.orientation_source = "E.csv";
  try {
    AssembleRecording(samples, Mounting(), recording);
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("E.csv"), HasSubstr("--orientation none")));
  }
}

TEST(AssembleRecording, UnwrapsYawThatPassesPlusMinusPi) {
  SensorSamples samples = Samples(50, 10.0);
  for (std::size_t k = 0; k < 50; ++k) {
    samples.orientation.t_s.push_back(samples.t_s[k]);
    samples.orientation.q_WS.push_back(QuaternionFromEulerZyx({3.0 + 0.02 * static_cast<double>(k), 0.0, 0.0}));
  }
  Recording recording;
  AssembleRecording(samples, Mounting(), recording);
  EXPECT_NEAR(recording.euler_zyx.back()[0], 3.98, 1e-12);
}

}  // namespace
}  // namespace rockfit::io
