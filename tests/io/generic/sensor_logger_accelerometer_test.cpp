// Sensor Logger's TotalAcceleration.csv beside its Gyroscope.csv: resampled onto the gyro's times, refused with both
// files' lines when the two do not cover the same times.
#include "generic/sensor_logger_accelerometer.hpp"

#include <cstdint>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "generic/generic_csv_reader.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/load_options.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;

constexpr std::int64_t kEpoch_ns = 1'700'000'000'000'000'000;
// Interpolating a linear function reproduces it to the round-off of values near 10 m/s².
constexpr double kInterpolationTolerance_m_s2 = 1e-12;

// A specific force that changes linearly in time [m/s²], t in seconds from the gyro's first sample.
Eigen::Vector3d Force(double t_s) { return {0.5 + 2.0 * t_s, -1.0 + 0.25 * t_s, 9.81 - 3.0 * t_s}; }

// Sensor Logger's layout (time, seconds_elapsed, z, y, x): `count` rows every `step_ns` from `start_ns`.
std::string SensorFile(std::int64_t start_ns, std::int64_t step_ns, int count, bool force) {
  std::string text = "time,seconds_elapsed,z,y,x\n";
  for (int k = 0; k < count; ++k) {
    const std::int64_t t_ns = start_ns + k * step_ns;
    const double t_s = static_cast<double>(t_ns - kEpoch_ns) * 1e-9;
    const Eigen::Vector3d v = force ? Force(t_s) : Eigen::Vector3d(0.01, 0.02, 0.03);
    text += fmt::format("{},{},{:.17g},{:.17g},{:.17g}\n", t_ns, t_s, v.z(), v.y(), v.x());
  }
  return text;
}

CsvTable Table(const std::string& text, const std::string& name) {
  std::vector<std::string> warnings;
  return CsvTable::FromText(text, name, warnings);
}

std::vector<double> GyroTimes(int count, double step_s) {
  std::vector<double> t;
  for (int k = 0; k < count; ++k) t.push_back(k * step_s);
  return t;
}

std::string ResampleError(const std::string& accel_text, const std::string& gyro_text, const std::vector<double>& t) {
  try {
    ResampleSensorLoggerAccelerometer(Table(accel_text, "dir/TotalAcceleration.csv"), Table(gyro_text, "dir/Gyroscope.csv"),
                                      0, TimeUnit::kNanoseconds, t);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(SensorLoggerAccelerometer, ALinearForceIsInterpolatedExactlyOntoTheGyroTimes) {
  // Gyro at 100 Hz; accelerometer at 50 Hz starting 3 ms later (not synchronised), covering the gyro's span.
  const std::string gyro = SensorFile(kEpoch_ns, 10'000'000, 100, false);
  const std::string accel = SensorFile(kEpoch_ns + 3'000'000, 20'000'000, 50, true);
  const std::vector<double> t = GyroTimes(100, 0.01);
  const SensorLoggerAccelerometer a = ResampleSensorLoggerAccelerometer(
      Table(accel, "dir/TotalAcceleration.csv"), Table(gyro, "dir/Gyroscope.csv"), 0, TimeUnit::kNanoseconds, t);
  ASSERT_EQ(a.accel_S.size(), t.size());
  const double first_s = 0.003;
  const double last_s = 0.003 + 49 * 0.02;
  for (std::size_t k = 0; k < t.size(); ++k) {
    SCOPED_TRACE(k);
    const double held = std::min(std::max(t[k], first_s), last_s);  // beyond the ends the end value holds
    EXPECT_LT((a.accel_S[k] - Force(held)).cwiseAbs().maxCoeff(), kInterpolationTolerance_m_s2);
  }
  EXPECT_THAT(a.columns.front(), HasSubstr("TotalAcceleration.csv: x"));
  EXPECT_THAT(a.notes.front(), HasSubstr("interpolated linearly"));
}

TEST(SensorLoggerAccelerometer, AnAccelerometerStartingLateIsRefusedWithBothFilesLines) {
  const std::string gyro = SensorFile(kEpoch_ns, 10'000'000, 100, false);
  const std::string accel = SensorFile(kEpoch_ns + 500'000'000, 10'000'000, 100, true);  // 0.5 s late
  const std::string error = ResampleError(accel, gyro, GyroTimes(100, 0.01));
  EXPECT_THAT(error, HasSubstr("dir/TotalAcceleration.csv:2:1"));
  EXPECT_THAT(error, HasSubstr("dir/Gyroscope.csv:2:1"));
  EXPECT_THAT(error, HasSubstr("0.5 s after"));
}

TEST(SensorLoggerAccelerometer, AnAccelerometerStoppingEarlyIsRefusedAtItsLastLine) {
  const std::string gyro = SensorFile(kEpoch_ns, 10'000'000, 100, false);
  const std::string accel = SensorFile(kEpoch_ns, 10'000'000, 60, true);  // 0.4 s short
  const std::string error = ResampleError(accel, gyro, GyroTimes(100, 0.01));
  EXPECT_THAT(error, HasSubstr("dir/TotalAcceleration.csv:61:1"));
  EXPECT_THAT(error, HasSubstr("dir/Gyroscope.csv:101:1"));
}

TEST(SensorLoggerAccelerometer, TimesInAnotherBaseAreRefused) {
  // The accelerometer's time in nanoseconds since boot, the gyro's since 1970.
  const std::string gyro = SensorFile(kEpoch_ns, 10'000'000, 100, false);
  const std::string accel = SensorFile(123'000'000'000, 10'000'000, 100, true);
  EXPECT_THAT(ResampleError(accel, gyro, GyroTimes(100, 0.01)), HasSubstr("same base"));
}

TEST(SensorLoggerAccelerometer, TheReaderTakesTotalAccelerationButNotAccelerometerWithoutGravity) {
  const ScratchDir dir("sensor_logger_accel");
  const auto gyro = dir.Write("Gyroscope.csv", SensorFile(kEpoch_ns, 10'000'000, 100, false));
  dir.Write("Accelerometer.csv", SensorFile(kEpoch_ns, 10'000'000, 100, true));
  const Recording without = ReadGenericCsvRecording(gyro, LoadOptions{});
  EXPECT_FALSE(without.has_accel());
  std::string recognised;
  for (const std::string& note : without.recognised) recognised += note + "\n";
  EXPECT_THAT(recognised, HasSubstr("without gravity and is not read"));

  dir.Write("TotalAcceleration.csv", SensorFile(kEpoch_ns + 5'000'000, 10'000'000, 100, true));
  const Recording with = ReadGenericCsvRecording(gyro, LoadOptions{});
  ASSERT_TRUE(with.has_accel());
  ASSERT_EQ(with.accel_B.size(), with.size());
  // Sample 10 (t = 0.1 s) lies midway between accelerometer rows at 0.095 s and 0.105 s: the force at 0.1 s.
  EXPECT_LT((with.accel_B[10] - Force(0.1)).cwiseAbs().maxCoeff(), kInterpolationTolerance_m_s2);
}

}  // namespace
}  // namespace rockfit::io
