// The register map of the original x-IMU (firmware 7, 110 registers, names as the x-IMU GUI v13 writes them
// to <prefix>_Registers.csv) and the values of the synthetic device. The device sends every register once at
// start-up; the rate registers tell a reader the sample rates (docs/file-formats.md §1.4).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rockfit::io {

// Register addresses a reader needs.
inline constexpr int kXimuRegisterAlgorithmMode = 55;
inline constexpr int kXimuRegisterDateTimeDataRate = 67;
inline constexpr int kXimuRegisterBatteryAndThermometerDataRate = 68;
inline constexpr int kXimuRegisterInertialAndMagneticDataRate = 69;
inline constexpr int kXimuRegisterQuaternionDataRate = 70;
inline constexpr int kXimuRegisterCount = 110;

struct XimuRegister {
  int address = 0;
  std::uint16_t value = 0;
  int q = -1;          // fixed-point fraction bits; −1: not a fixed-point register ("NaN" in the file)
  std::string name;
  // The "Fixed-point value" column: int16(value) / 2^q in single precision, NaN without q.
  float FixedPointValue() const;
};

// Rate register value of a data rate: v with rate = 2^(v−1) Hz, v = 1 … 10 (1 … 512 Hz); 0 for 0 Hz (disabled).
// Throws InvalidArgument for any other rate, naming `what`.
std::uint16_t XimuRateRegisterValue(double rate_hz, const std::string& what);

// The rates the synthetic device reports in its rate registers.
struct XimuDeviceRates {
  double inertial_rate_hz = 256.0;    // register 69
  double quaternion_rate_hz = 256.0;  // register 70
  double date_time_rate_hz = 1.0;     // register 67
  double battery_rate_hz = 4.0;       // register 68
};

// All 110 registers of the synthetic device in address order: IMU algorithm mode (the paper's setting), ±2000
// deg/s gyroscope, ±8 g accelerometer, plausible calibration values, and the given rates.
std::vector<XimuRegister> XimuRegisters(const XimuDeviceRates& settings);

}  // namespace rockfit::io
