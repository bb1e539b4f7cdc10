// The synthetic x-IMU's register map: addresses, names, fixed-point values and the rate registers.
#include "ximu/ximu_register_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

TEST(XimuRegisterMap, RateRegisterValueIsLogTwoOfTheRatePlusOne) {
  // docs/file-formats.md §1.4: value v ↔ 2^(v−1) Hz, 0 = disabled.
  EXPECT_EQ(XimuRateRegisterValue(0.0, "r"), 0);
  EXPECT_EQ(XimuRateRegisterValue(1.0, "r"), 1);
  EXPECT_EQ(XimuRateRegisterValue(128.0, "r"), 8);
  EXPECT_EQ(XimuRateRegisterValue(256.0, "r"), 9);
  EXPECT_EQ(XimuRateRegisterValue(512.0, "r"), 10);
  for (int v = 1; v <= 10; ++v) EXPECT_EQ(XimuRateRegisterValue(std::ldexp(1.0, v - 1), "r"), v);
}

TEST(XimuRegisterMap, RateThatIsNotAPowerOfTwoIsRejectedWithTheAllowedRates) {
  try {
    XimuRateRegisterValue(100.0, "the inertial rate");
    FAIL() << "100 Hz accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("the inertial rate"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("512"), std::string::npos);
  }
  EXPECT_THROW(XimuRateRegisterValue(1024.0, "r"), InvalidArgument);
}

TEST(XimuRegisterMap, AllRegistersInAddressOrderWithTheRatesGiven) {
  XimuDeviceRates settings;
  settings.inertial_rate_hz = 256.0;
  settings.quaternion_rate_hz = 128.0;
  settings.date_time_rate_hz = 2.0;
  settings.battery_rate_hz = 4.0;
  const auto registers = XimuRegisters(settings);
  ASSERT_EQ(registers.size(), static_cast<std::size_t>(kXimuRegisterCount));
  for (int a = 0; a < kXimuRegisterCount; ++a) EXPECT_EQ(registers[a].address, a);
  EXPECT_EQ(registers[69].name, "InertialAndMagneticDataRate");
  EXPECT_EQ(registers[69].value, 9);
  EXPECT_EQ(registers[70].name, "QuaternionDataRate");
  EXPECT_EQ(registers[70].value, 8);
  EXPECT_EQ(registers[67].name, "DateTimeDataRate");
  EXPECT_EQ(registers[67].value, 2);
  EXPECT_EQ(registers[68].name, "BatteryAndThermometerDataRate");
  EXPECT_EQ(registers[68].value, 3);
  EXPECT_EQ(registers[55].name, "AlgorithmMode");
  EXPECT_EQ(registers[55].value, 1);  // IMU mode, as in the paper
  EXPECT_EQ(registers[8].name, "GyroscopeFullScale");
  EXPECT_EQ(registers[109].name, "ADXL345DbiasZ");
}

TEST(XimuRegisterMap, FixedPointValueIsTheSignedValueOverTwoToTheQ) {
  XimuRegister r;
  r.value = 19840;
  r.q = 5;
  EXPECT_EQ(r.FixedPointValue(), 620.0f);
  r.value = static_cast<std::uint16_t>(-23040);
  r.q = 0;
  EXPECT_EQ(r.FixedPointValue(), -23040.0f);
  r.value = static_cast<std::uint16_t>(-1312);
  r.q = 11;
  EXPECT_EQ(r.FixedPointValue(), -1312.0f / 2048.0f);
  r.q = -1;
  EXPECT_TRUE(std::isnan(r.FixedPointValue()));
}

}  // namespace
}  // namespace rockfit::io
