#include "ximu/ximu_registers.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "imu_test_files.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

CsvTable Registers(const std::string& rows) {
  std::vector<std::string> warnings;
  return CsvTable::FromText(testing::kGuiRegistersHeader + "\n" + rows, "R.csv", warnings);
}

TEST(XimuRateFromRegisterValue, IsTwoToTheValueMinusOneHertz) {
  EXPECT_EQ(XimuRateFromRegisterValue(0), 0.0);
  EXPECT_EQ(XimuRateFromRegisterValue(1), 1.0);
  EXPECT_EQ(XimuRateFromRegisterValue(9), 256.0);
  EXPECT_EQ(XimuRateFromRegisterValue(10), 512.0);
  EXPECT_FALSE(XimuRateFromRegisterValue(11));
  EXPECT_FALSE(XimuRateFromRegisterValue(-1));
}

TEST(ReadXimuRegisters, ReadsRegisters69And70AmongOthers) {
  // The example row of docs/file-formats.md §1.2 plus two other registers.
  const XimuRegisterSettings rates = ReadXimuRegisters(Registers(
      "68,8,3,NaN,GyroscopeFullScale\n70,69,9,NaN,InertialAndMagneticDataRate\n71,70,8,NaN,QuaternionDataRate\n"
      "72,67,1,NaN,DateTimeDataRate\n70,69,9,NaN,InertialAndMagneticDataRate\n"));
  ASSERT_TRUE(rates.inertial && rates.orientation);
  EXPECT_EQ(rates.inertial->rate_hz, 256.0);
  EXPECT_EQ(rates.orientation->rate_hz, 128.0);
  EXPECT_EQ(FormatPosition(rates.orientation->at), "R.csv:4:7");
  EXPECT_EQ(rates.gyroscope_full_scale_dps, 2000.0);
}

TEST(ReadXimuRegisters, GyroscopeFullScaleIs250TimesTwoToTheValue) {
  EXPECT_EQ(ReadXimuRegisters(Registers("1,8,0,NaN,GyroscopeFullScale\n")).gyroscope_full_scale_dps, 250.0);
  EXPECT_EQ(ReadXimuRegisters(Registers("1,8,2,NaN,GyroscopeFullScale\n")).gyroscope_full_scale_dps, 1000.0);
  EXPECT_FALSE(ReadXimuRegisters(Registers("1,8,7,NaN,GyroscopeFullScale\n")).gyroscope_full_scale_dps);
  EXPECT_FALSE(ReadXimuRegisters(Registers("1,8,0,NaN,GyroscopeFullScale\n2,8,1,NaN,GyroscopeFullScale\n"))
                   .gyroscope_full_scale_dps);
}

TEST(ReadXimuRegisters, RefusesARateThatChangesOrIsOutOfRange) {
  try {
    ReadXimuRegisters(Registers("1,69,9,NaN,InertialAndMagneticDataRate\n500,69,8,NaN,InertialAndMagneticDataRate\n"));
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("R.csv:3:8"), HasSubstr("= 8 (128 Hz), but R.csv:2:6 it was 9 (256 Hz)")));
  }
  EXPECT_THROW(ReadXimuRegisters(Registers("1,69,12,NaN,InertialAndMagneticDataRate\n")), BadInput);
  EXPECT_FALSE(ReadXimuRegisters(Registers("1,8,3,NaN,GyroscopeFullScale\n")).inertial);
}

}  // namespace
}  // namespace rockfit::io
