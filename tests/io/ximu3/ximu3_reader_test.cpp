#include "ximu3/ximu3_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "csv_numbers.hpp"
#include "imu_test_files.hpp"
#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "rockfit/io/units.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;

// docs/design.md §12: angles from Euler and quaternion outputs agree to this.
constexpr double kEulerVsQuaternion_rad = 1e-4;

std::string LoadError(const std::filesystem::path& dir, const LoadOptions& options = {}) {
  try {
    ReadXimu3Recording(dir, options);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(ReadXimu3Recording, TimeIsDeviceTimeFromTheFirstRowAndLongStepsAreGaps) {
  const ScratchDir dir("ximu3_gaps");
  dir.Write("Inertial.csv", testing::MakeXimu3Inertial({19991, 19990, 39980, 19990, 19991, 19990, 79960, 19990}));
  const Recording r = ReadXimu3Recording(dir.path(), {});
  ASSERT_EQ(r.size(), 9u);
  EXPECT_EQ(r.format, "ximu3");
  EXPECT_EQ(r.rate_source, RateSource::kTimestamps);
  EXPECT_NEAR(r.rate_hz, 1e6 / 19990.5, 1e-9);  // eight steps: median of 19 990 and 19 991 µs
  EXPECT_DOUBLE_EQ(r.t_s[0], 0.0);
  EXPECT_NEAR(r.t_s[3], (19991 + 19990 + 39980) * 1e-6, 1e-12);
  ASSERT_EQ(r.gaps.size(), 2u);
  EXPECT_EQ(r.gaps[0].index, 2u);
  EXPECT_EQ(r.gaps[0].missing, 1u);
  EXPECT_EQ(r.gaps[1].index, 6u);
  EXPECT_EQ(r.gaps[1].missing, 3u);
  EXPECT_NEAR(r.w_B[0].z(), 0.066303 * kRadPerDeg, 1e-15);
  EXPECT_NEAR(r.accel_B[0].z(), 0.996598 * kMetresPerSecond2PerG, 1e-12);
  EXPECT_FALSE(r.has_euler());
}

TEST(ReadXimu3Recording, RefusesRepeatedOrDecreasingTimestamps) {
  const ScratchDir dir("ximu3_time");
  dir.Write("Inertial.csv", testing::MakeXimu3Inertial({20000, 0, 20000}));
  EXPECT_THAT(LoadError(dir.path()), AllOf(HasSubstr("Inertial.csv:4:1: column 1 'Timestamp (us)'"),
                                           HasSubstr("'19170794' again (as on line 3)")));
  dir.Write("Inertial.csv", testing::MakeXimu3Inertial({20000, -5, 20000}));
  EXPECT_THAT(LoadError(dir.path()), AllOf(HasSubstr("Inertial.csv:4:1"), HasSubstr("smaller than '19170794' on line 3")));
}

TEST(ReadXimu3Recording, AGivenRateMustAgreeWithTheTimestamps) {
  const ScratchDir dir("ximu3_rate");
  dir.Write("Inertial.csv", testing::MakeXimu3Inertial({20000, 20000, 20000}));
  LoadOptions options;
  options.rate_hz = 50.5;
  EXPECT_NO_THROW(ReadXimu3Recording(dir.path(), options));
  options.rate_hz = 100.0;
  EXPECT_THAT(LoadError(dir.path(), options),
              AllOf(HasSubstr("Inertial.csv:1:1"), HasSubstr("i.e. 50 Hz"), HasSubstr("--rate (100 Hz)")));
}

TEST(ReadXimu3Recording, MergesAhrsOutputsAndReadsQuaternionsWithoutConjugation) {
  const ScratchDir dir("ximu3_attitude");
  dir.Write("Inertial.csv", testing::MakeXimu3Inertial({20000, 20000, 20000, 20000, 20000}));
  // Rows 0–2 from Quaternion.csv (+10° roll, W first), rows 3–5 from EulerAngles.csv (+20° roll).
  const double half = 5.0 * kRadPerDeg;
  std::string quaternion = "Timestamp (us),W,X,Y,Z\n";
  for (long long t : {19150794LL, 19170794LL, 19190794LL}) {
    quaternion += std::to_string(t) + "," + testing::G7(std::cos(half)) + "," + testing::G7(std::sin(half)) + ",0,0\n";
  }
  dir.Write("Quaternion.csv", quaternion);
  dir.Write("EulerAngles.csv", "Timestamp (us),Roll (deg),Pitch (deg),Yaw (deg)\n19210794,20,0,0\n19230794,20,0,0\n"
                               "19250794,20,0,0\n");
  const Recording r = ReadXimu3Recording(dir.path(), {});
  ASSERT_EQ(r.size(), 6u);
  EXPECT_EQ(r.orientation_source, "EulerAngles.csv + Quaternion.csv");
  EXPECT_NEAR(r.euler_zyx[1][2], 10.0 * kRadPerDeg, 1e-6);
  EXPECT_NEAR(r.euler_zyx[4][2], 20.0 * kRadPerDeg, 1e-12);
  LoadOptions only_euler;
  only_euler.orientation = OrientationChoice::kEulerAngles;
  const Recording trimmed = ReadXimu3Recording(dir.path(), only_euler);
  EXPECT_EQ(trimmed.size(), 3u);  // gyro rows without attitude are dropped
  ASSERT_EQ(trimmed.warnings.size(), 1u);
  only_euler.orientation = OrientationChoice::kRotationMatrix;
  EXPECT_THAT(LoadError(dir.path(), only_euler), HasSubstr("no RotationMatrix.csv"));
}

TEST(ReadXimu3Recording, NeedsAnInertialFileWithAtLeastTwoRows) {
  const ScratchDir dir("ximu3_short");
  EXPECT_THAT(LoadError(dir.path()), HasSubstr("no Inertial.csv"));
  dir.Write("Inertial.csv", testing::MakeXimu3Inertial({}));
  EXPECT_THAT(LoadError(dir.path()), AllOf(HasSubstr("Inertial.csv:2"), HasSubstr("a single sample")));
}

// --- the real x-IMU3 log ------------------------------------------------------------------------

std::filesystem::path RealXimu3Dir() { return testing::RealImuDir() / "x-IMU3-CSV/Logged Data/x-IMU3 673B204B (UDP)"; }

TEST(ReadXimu3Recording, RealLogHasTheTimestampRateAndItsFourDroppedMessagesAsGaps) {
  ROCKFIT_REQUIRE_REAL_IMU();
  const auto inertial = testing::ReadCsvNumbers(RealXimu3Dir() / "Inertial.csv");
  std::vector<double> steps;
  for (std::size_t k = 1; k < inertial.size(); ++k) steps.push_back(inertial[k][0] - inertial[k - 1][0]);
  std::vector<double> sorted = steps;
  std::sort(sorted.begin(), sorted.end());
  const double median_us = sorted[sorted.size() / 2];  // 361 steps: the middle one
  std::vector<std::size_t> expected_gaps;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (steps[k] > 1.5 * median_us) expected_gaps.push_back(k);
  }
  ASSERT_EQ(expected_gaps.size(), 4u);  // the README: four ~40 ms steps

  const Recording r = ReadXimu3Recording(RealXimu3Dir(), {});
  EXPECT_EQ(r.size(), inertial.size());
  EXPECT_NEAR(r.rate_hz, 1e6 / median_us, 1e-9);
  EXPECT_NEAR(r.rate_hz, 50.0, 0.05);
  EXPECT_NEAR(r.duration_s(), (inertial.back()[0] - inertial.front()[0]) * 1e-6, 1e-9);
  ASSERT_EQ(r.gaps.size(), expected_gaps.size());
  for (std::size_t g = 0; g < r.gaps.size(); ++g) {
    EXPECT_EQ(r.gaps[g].index, expected_gaps[g]);
    EXPECT_EQ(r.gaps[g].missing, 1u);
  }
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(r.size(), r.euler_zyx.size());  // the five AHRS outputs together cover the whole log
}

TEST(ReadXimu3Recording, RealEulerAnglesAgreeWithTheQuaternionThatFollowsThem) {
  ROCKFIT_REQUIRE_REAL_IMU();
  // The device lies still and sends one AHRS output at a time: EulerAngles.csv ends one message
  // (20 ms) before LinearAcceleration.csv, whose rows carry the quaternion, begins.
  const auto euler = testing::ReadCsvNumbers(RealXimu3Dir() / "EulerAngles.csv");
  const auto linear = testing::ReadCsvNumbers(RealXimu3Dir() / "LinearAcceleration.csv");
  const auto& last = euler.back();
  const auto& next = linear.front();
  ASSERT_NEAR(next[0] - last[0], 19990.0, 20.0);
  // Standard ZYX angles of the (not conjugated) quaternion W, X, Y, Z.
  const Eigen::Quaterniond q = Eigen::Quaterniond(next[1], next[2], next[3], next[4]).normalized();
  const Eigen::Matrix3d R = q.toRotationMatrix();
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double pitch = -std::asin(R(2, 0));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  EXPECT_NEAR(last[1] * kRadPerDeg, roll, kEulerVsQuaternion_rad);
  EXPECT_NEAR(last[2] * kRadPerDeg, pitch, kEulerVsQuaternion_rad);
  EXPECT_NEAR(last[3] * kRadPerDeg, yaw, kEulerVsQuaternion_rad);
  ASSERT_GT(std::abs(roll), 10 * kEulerVsQuaternion_rad);  // a conjugated quaternion would flip the roll

  // The reader gives both samples these values.
  const Recording r = ReadXimu3Recording(RealXimu3Dir(), {});
  const auto inertial = testing::ReadCsvNumbers(RealXimu3Dir() / "Inertial.csv");
  std::size_t k = 0;
  while (inertial[k][0] != last[0]) ++k;
  EXPECT_NEAR(r.euler_zyx[k][2], last[1] * kRadPerDeg, 1e-12);
  EXPECT_NEAR(r.euler_zyx[k + 1][2], roll, 1e-12);
  EXPECT_NEAR(r.euler_zyx[k + 1][1], pitch, 1e-12);
}

}  // namespace
}  // namespace rockfit::io
