// The C# single-precision text of the x-IMU GUI: hand-picked cases and every number of a real recording.
#include "text/dotnet_float_format.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "test_paths.hpp"

namespace rockfit::io {
namespace {

TEST(DotNetFloatFormat, IntegersAndShortFractionsHaveNoTrailingZeros) {
  EXPECT_EQ(FormatDotNetSingle(0.0f), "0");
  EXPECT_EQ(FormatDotNetSingle(2.0f), "2");
  EXPECT_EQ(FormatDotNetSingle(-0.125f), "-0.125");
  EXPECT_EQ(FormatDotNetSingle(-0.0625f), "-0.0625");
  EXPECT_EQ(FormatDotNetSingle(1234567.0f), "1234567");
}

TEST(DotNetFloatFormat, NegativeZeroIsPrintedAsZero) { EXPECT_EQ(FormatDotNetSingle(-0.0f), "0"); }

TEST(DotNetFloatFormat, RoundsToSevenSignificantDigitsTiesAwayFromZero) {
  // 0.0087890625 = 18/2048 is exactly halfway; the real files print 0.008789063 (half-even would give …062).
  EXPECT_EQ(FormatDotNetSingle(18.0f / 2048.0f), "0.008789063");
  EXPECT_EQ(FormatDotNetSingle(-10.0f / 2048.0f), "-0.004882813");
  EXPECT_EQ(FormatDotNetSingle(32767.0f / 2048.0f), "15.99951");
  EXPECT_EQ(FormatDotNetSingle(2047.9375f), "2047.938");
}

TEST(DotNetFloatFormat, RoundingCarryMovesTheDecimalExponent) {
  EXPECT_EQ(FormatDotNetSingle(0.01f), "0.01");  // float(0.01) = 0.0099999997764825820…
  EXPECT_EQ(FormatDotNetSingle(-0.01f), "-0.01");
}

TEST(DotNetFloatFormat, SmallAndLargeValuesUseTheExponentForm) {
  EXPECT_EQ(FormatDotNetSingle(-6.113857e-05f), "-6.113857E-05");
  EXPECT_EQ(FormatDotNetSingle(1e-5f), "1E-05");
  EXPECT_EQ(FormatDotNetSingle(0.0001f), "0.0001");  // exponent −4 is still fixed notation
  EXPECT_EQ(FormatDotNetSingle(12345678.0f), "1.234568E+07");
  EXPECT_EQ(FormatDotNetSingle(1e-20f), "1E-20");
  EXPECT_EQ(FormatDotNetSingle(3.4e38f), "3.4E+38");
}

TEST(DotNetFloatFormat, NonFiniteValuesUseTheDotNetWords) {
  EXPECT_EQ(FormatDotNetSingle(std::numeric_limits<float>::quiet_NaN()), "NaN");
  EXPECT_EQ(FormatDotNetSingle(std::numeric_limits<float>::infinity()), "Infinity");
  EXPECT_EQ(FormatDotNetSingle(-std::numeric_limits<float>::infinity()), "-Infinity");
}

// Every number the x-IMU GUI wrote in a real recording is reproduced from the float it denotes.
// (A 7-digit decimal maps to a unique float and back, since float spacing is below 10⁻⁶ relative.)
TEST(DotNetFloatFormat, ReproducesEveryNumberOfARealRecording) {
  ROCKFIT_REQUIRE_REAL_IMU();
  const auto dir = rockfit::testing::RealImuDir() / "Oscillatory-Motion-Tracking-With-x-IMU" / "LoggedData";
  std::size_t checked = 0;
  for (const char* type : {"CalInertialAndMag", "Quaternion", "EulerAngles", "RotationMatrix", "CalBattAndTherm"}) {
    const auto path = dir / (std::string("LoggedData_") + type + ".csv");
    std::ifstream in(path);
    ASSERT_TRUE(in) << path;
    std::string line;
    std::getline(in, line);  // header
    std::size_t line_number = 1;
    while (std::getline(in, line)) {
      ++line_number;
      std::stringstream cells(line);
      std::string cell;
      std::getline(cells, cell, ',');  // packet number
      while (std::getline(cells, cell, ',')) {
        const float value = std::strtof(cell.c_str(), nullptr);
        ASSERT_EQ(FormatDotNetSingle(value), cell) << path << " line " << line_number;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 200000u);
}

}  // namespace
}  // namespace rockfit::io
