#include "generic/generic_csv_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/units.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;

CsvTable Table(const std::string& text) {
  std::vector<std::string> warnings;
  return CsvTable::FromText(text, "g.csv", warnings);
}

std::string LoadError(const std::filesystem::path& file, const LoadOptions& options) {
  try {
    ReadGenericCsvRecording(file, options);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(DetectColumnMap, RecognisesXioHeadersWithUnitsInParentheses) {
  // The NGIMU / Fusion layout: time in seconds, gyroscope in deg/s, accelerometer in g.
  const ColumnMap map = DetectColumnMap(Table(
      "Time (s),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),Accelerometer Y (g),"
      "Accelerometer Z (g)\n0,1,2,3,4,5,6\n"));
  EXPECT_EQ(map.time, "Time (s)");
  EXPECT_EQ(map.gyro[1], "Gyroscope Y (deg/s)");
  EXPECT_TRUE(map.has_accel());
  EXPECT_FALSE(map.has_euler());
  EXPECT_FALSE(map.gyro_unit);  // taken from the header when reading
}

TEST(DetectColumnMap, RecognisesUnitSuffixedNames) {
  const ColumnMap map = DetectColumnMap(Table("t_s,gyro_x_rad_s,gyro_y_rad_s,gyro_z_rad_s,roll_deg,pitch_deg,yaw_deg\n0,1,2,3,4,5,6\n"));
  EXPECT_EQ(map.time, "t_s");
  EXPECT_EQ(map.time_unit, TimeUnit::kSeconds);
  EXPECT_EQ(map.gyro_unit, AngularRateUnit::kRadiansPerSecond);
  EXPECT_EQ(map.euler[2], "yaw_deg");
  EXPECT_EQ(map.euler_unit, AngleUnit::kDegrees);
}

TEST(DetectColumnMap, SaysHowToGiveAMapWhenNothingIsRecognised) {
  try {
    DetectColumnMap(Table("a,b\n1,2\n"));
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("g.csv:1"), HasSubstr("--columns")));
  }
}

TEST(ReadGenericCsvRecording, ConvertsUnitsAndTakesTimeFromTheTimeColumn) {
  const ScratchDir dir("generic_time");
  const auto file = dir.Write("walk.csv",
                              "Time (s),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),"
                              "Accelerometer Y (g),Accelerometer Z (g)\n"
                              "10.0000,180,0,0,0,0,1\n10.0025,0,90,0,0,0,1\n10.0050,0,0,-45,0,0,1\n10.0100,0,0,0,0,0,1\n");
  const Recording r = ReadGenericCsvRecording(file, {});
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r.format, "generic-csv");
  EXPECT_NEAR(r.rate_hz, 400.0, 1e-6);
  EXPECT_EQ(r.rate_source, RateSource::kTimestamps);
  EXPECT_NEAR(r.t_s[3], 0.01, 1e-12);
  EXPECT_NEAR(r.w_B[0].x(), kPi, 1e-12);
  EXPECT_NEAR(r.w_B[2].z(), -kPi / 4, 1e-12);
  EXPECT_NEAR(r.accel_B[1].z(), kMetresPerSecond2PerG, 1e-12);
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].index, 2u);
}

TEST(ReadGenericCsvRecording, UsesTheGivenRateWithoutATimeColumnAndAnExplicitMap) {
  const ScratchDir dir("generic_rate");
  const auto file = dir.Write("w.csv", "wx;wy;wz;r;p;y\n0,5;0;0;0;0;90\n0,5;0;0;0;0;91\n");
  LoadOptions options;
  options.rate_hz = 100.0;
  options.columns = ColumnMap::Parse("gyro=wx,wy,wz@rad/s;euler=r,p,y@deg");
  const Recording r = ReadGenericCsvRecording(file, options);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.rate_source, RateSource::kOption);
  EXPECT_DOUBLE_EQ(r.t_s[1], 0.01);
  EXPECT_DOUBLE_EQ(r.w_B[0].x(), 0.5);
  EXPECT_NEAR(r.euler_zyx[1][0], 91.0 * kRadPerDeg, 1e-12);
  EXPECT_EQ(r.warnings.size(), 2u);  // ';' separator, decimal commas
}

TEST(ReadGenericCsvRecording, ReportsMissingMappedColumnsAndRepeatedTimes) {
  const ScratchDir dir("generic_errors");
  const auto file = dir.Write("w.csv", "t,wx,wy,wz\n0,1,2,3\n0.01,1,2,3\n0.01,1,2,3\n");
  LoadOptions options;
  options.columns = ColumnMap::Parse("time=t@s;gyro=wx,wy,wq@rad/s");
  EXPECT_THAT(LoadError(file, options), AllOf(HasSubstr("w.csv:1"), HasSubstr("expected a column 'wq'")));
  options.columns = ColumnMap::Parse("time=t@s;gyro=wx,wy,wz@rad/s");
  EXPECT_THAT(LoadError(file, options), AllOf(HasSubstr("w.csv:4:1"), HasSubstr("'0.01' again (as on line 3)")));
}

TEST(ReadGenericCsvRecording, AMappedColumnWithoutAUnitNeedsOne) {
  const ScratchDir dir("generic_unit");
  const auto file = dir.Write("w.csv", "t,wx,wy,wz\n0,1,2,3\n0.01,1,2,3\n");
  LoadOptions options;
  options.columns = ColumnMap::Parse("time=t@s;gyro=wx,wy,wz");
  EXPECT_THAT(LoadError(file, options), AllOf(HasSubstr("w.csv:1:3"), HasSubstr("no unit in parentheses")));
}

}  // namespace
}  // namespace rockfit::io
