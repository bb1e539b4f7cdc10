#include "rockfit/io/column_map.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

std::string ParseError(const std::string& spec) {
  try {
    ColumnMap::Parse(spec);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(ColumnMap, ParsesNamesAndUnitsOfEachKey) {
  const ColumnMap map = ColumnMap::Parse("time=Time (s)@s; gyro=wx,wy,wz@rad/s;euler=Roll,Pitch,Yaw@deg;accel=ax,ay,az@m/s^2");
  EXPECT_EQ(map.time, "Time (s)");
  EXPECT_EQ(map.time_unit, TimeUnit::kSeconds);
  EXPECT_EQ(map.gyro[2], "wz");
  EXPECT_EQ(map.gyro_unit, AngularRateUnit::kRadiansPerSecond);
  EXPECT_EQ(map.euler[1], "Pitch");
  EXPECT_EQ(map.euler_unit, AngleUnit::kDegrees);
  EXPECT_EQ(map.accel_unit, AccelerationUnit::kMetresPerSecond2);
}

TEST(ColumnMap, UnitsMayBeLeftToTheHeader) {
  const ColumnMap map = ColumnMap::Parse("gyro=Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)");
  EXPECT_FALSE(map.gyro_unit);
  EXPECT_FALSE(map.has_time());
  EXPECT_FALSE(map.has_euler());
}

TEST(ColumnMap, TextFormRoundTrips) {
  const ColumnMap map = ColumnMap::Parse("time=t@ms;gyro=a,b,c@deg/s;accel=d,e,f@g");
  EXPECT_EQ(ColumnMap::Parse(map.ToString()).ToString(), map.ToString());
  EXPECT_EQ(map.ToString(), "time=t@ms;gyro=a,b,c@deg/s;accel=d,e,f@g");
}

TEST(ColumnMap, RefusesIncompleteOrContradictoryMaps) {
  EXPECT_THAT(ParseError("time=t@s"), HasSubstr("gyroscope columns (gyro=X,Y,Z) are required"));
  EXPECT_THAT(ParseError("gyro=a,b@deg/s"), HasSubstr("three column names"));
  EXPECT_THAT(ParseError("gyro=a,b,c@furlong"), HasSubstr("unit 'furlong' of gyro"));
  EXPECT_THAT(ParseError("gyro=a,b,c;gyro=d,e,f"), HasSubstr("appears twice"));
  EXPECT_THAT(ParseError("gyro=a,b,c;accel=a,e,f"), HasSubstr("column 'a' is used twice"));
  EXPECT_THAT(ParseError("gyro=a,b,c;mag=d,e,f"), HasSubstr("unknown key 'mag'"));
  EXPECT_THAT(ParseError("gyro"), HasSubstr("has no '='"));
}

}  // namespace
}  // namespace rockfit::io
