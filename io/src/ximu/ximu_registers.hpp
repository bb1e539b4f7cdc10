// Settings from an x-IMU GUI "<prefix>_Registers.csv" (docs/file-formats.md §1.4, §1.5): register
// 69 InertialAndMagneticDataRate and 70 QuaternionDataRate hold a value v, the rate is 2^(v−1) Hz
// (v = 1 … 10 → 1 … 512 Hz) and v = 0 means the output is disabled. The device sends every register
// at start-up and whenever one is read or written, so a register may appear several times.
// Register 8 (gyroscope full scale, v = 0 … 3 → ±250, 500, 1000, 2000 °/s) tells where the gyroscope
// saturates.
#pragma once

#include <cstddef>
#include <optional>

#include "text/csv_table.hpp"

namespace rockfit::io {

inline constexpr int kXimuInertialRateRegister = 69;
inline constexpr int kXimuQuaternionRateRegister = 70;
inline constexpr int kXimuGyroscopeFullScaleRegister = 8;

// 2^(v−1) Hz for v = 1 … 10, 0 for v = 0 (disabled); std::nullopt for other v.
std::optional<double> XimuRateFromRegisterValue(long long value);

struct XimuRegisterRate {
  double rate_hz = 0.0;   // 0 = output disabled
  long long value = 0;    // the register value v
  TextPosition at;        // the cell it was read from
};

struct XimuRegisterSettings {
  std::optional<XimuRegisterRate> inertial;     // register 69
  std::optional<XimuRegisterRate> orientation;  // register 70
  // Register 8 as ±°/s; empty when absent, outside 0 … 3, or changed within the recording.
  std::optional<double> gyroscope_full_scale_dps;
};

// Reads columns "Address" and "Value". Throws BadInput for a rate value outside 0 … 10, or a rate
// register that holds two different values in one recording (the rate changed while recording).
XimuRegisterSettings ReadXimuRegisters(const CsvTable& registers);

}  // namespace rockfit::io
