#include "rockfit/io/units.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace rockfit::io {
namespace {

TEST(Units, ConvertToSiWithTheDefiningFactors) {
  EXPECT_DOUBLE_EQ(180.0 * ToSi(AngleUnit::kDegrees), std::acos(-1.0));
  EXPECT_DOUBLE_EQ(360.0 * ToSi(AngularRateUnit::kDegreesPerSecond), 2.0 * std::acos(-1.0));
  EXPECT_DOUBLE_EQ(ToSi(AngleUnit::kRadians), 1.0);
  EXPECT_DOUBLE_EQ(ToSi(AccelerationUnit::kG), core::kStandardGravity);
  EXPECT_DOUBLE_EQ(ToSi(AccelerationUnit::kMetresPerSecond2), 1.0);
  EXPECT_DOUBLE_EQ(19990.0 * ToSi(TimeUnit::kMicroseconds), 0.01999);
  EXPECT_DOUBLE_EQ(ToSi(TimeUnit::kMilliseconds), 1e-3);
}

TEST(Units, ParseTheSpellingsOfTheIMUHeaders) {
  EXPECT_EQ(ParseAngularRateUnit("deg/s"), AngularRateUnit::kDegreesPerSecond);
  EXPECT_EQ(ParseAngularRateUnit("RAD/S"), AngularRateUnit::kRadiansPerSecond);
  EXPECT_EQ(ParseAngleUnit("degrees"), AngleUnit::kDegrees);
  EXPECT_EQ(ParseAngleUnit("deg"), AngleUnit::kDegrees);
  EXPECT_EQ(ParseAccelerationUnit("g"), AccelerationUnit::kG);
  EXPECT_EQ(ParseAccelerationUnit("m/s^2"), AccelerationUnit::kMetresPerSecond2);
  EXPECT_EQ(ParseTimeUnit("us"), TimeUnit::kMicroseconds);
  EXPECT_FALSE(ParseAngularRateUnit("deg"));
  EXPECT_FALSE(ParseAngleUnit(""));
  EXPECT_FALSE(ParseTimeUnit("h"));
}

TEST(Units, NamesRoundTripThroughTheParsers) {
  for (auto unit : {AngularRateUnit::kDegreesPerSecond, AngularRateUnit::kRadiansPerSecond}) {
    EXPECT_EQ(ParseAngularRateUnit(UnitName(unit)), unit);
  }
  for (auto unit : {AngleUnit::kDegrees, AngleUnit::kRadians}) EXPECT_EQ(ParseAngleUnit(UnitName(unit)), unit);
  for (auto unit : {AccelerationUnit::kG, AccelerationUnit::kMetresPerSecond2}) {
    EXPECT_EQ(ParseAccelerationUnit(UnitName(unit)), unit);
  }
  for (auto unit : {TimeUnit::kSeconds, TimeUnit::kMilliseconds, TimeUnit::kMicroseconds, TimeUnit::kNanoseconds}) {
    EXPECT_EQ(ParseTimeUnit(UnitName(unit)), unit);
  }
}

TEST(Units, SpellingsOfLoggersAndPhoneAppsAreRecognised) {
  EXPECT_EQ(ParseTimeUnit("ns"), TimeUnit::kNanoseconds);
  EXPECT_DOUBLE_EQ(ToSi(TimeUnit::kNanoseconds), 1e-9);
  EXPECT_EQ(ParseAngularRateUnit("dps"), AngularRateUnit::kDegreesPerSecond);
  EXPECT_EQ(ParseAngularRateUnit("deg/sec"), AngularRateUnit::kDegreesPerSecond);
  EXPECT_EQ(ParseAngularRateUnit("rad/sec"), AngularRateUnit::kRadiansPerSecond);
  EXPECT_EQ(ParseAccelerationUnit("ms^-2"), AccelerationUnit::kMetresPerSecond2);
  EXPECT_EQ(ParseAccelerationUnit("m/s/s"), AccelerationUnit::kMetresPerSecond2);
  EXPECT_FALSE(ParseAccelerationUnit("G/s"));
}

}  // namespace
}  // namespace rockfit::io
