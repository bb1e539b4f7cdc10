#include "ximu/ximu_register_map.hpp"

#include <cmath>
#include <limits>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

// Highest rate register value: 2^(10−1) = 512 Hz.
constexpr int kMaxRateRegisterValue = 10;

struct RegisterSpec {
  const char* name;
  int q;          // −1: not fixed point
  int value;      // as a signed or unsigned 16-bit integer; stored as its uint16 bit pattern
};

// Firmware-7 register map (x-IMU API RegisterAddresses and Qvals) with the synthetic device's values.
// Calibration values are plausible for an x-IMU, not those of any real unit.
constexpr RegisterSpec kRegisterSpecs[kXimuRegisterCount] = {
    {"FirmwareVersionMajorNum", -1, 7},
    {"FirmwareVersionMinorNum", -1, 2},
    {"DeviceID", -1, 19007},
    {"ButtonMode", -1, 2},
    {"BatterySensitivity", 5, 19840},
    {"BatteryBias", 8, 0},
    {"ThermometerSensitivity", 6, 17984},
    {"ThermometerBias", 0, -23040},
    {"GyroscopeFullScale", -1, 3},  // ±2000 deg/s
    {"GyroscopeSensitivityX", 7, 2079},
    {"GyroscopeSensitivityY", 7, 2091},
    {"GyroscopeSensitivityZ", 7, 2085},
    {"GyroscopeSampledPlus200dpsX", 0, 3262},
    {"GyroscopeSampledPlus200dpsY", 0, 3251},
    {"GyroscopeSampledPlus200dpsZ", 0, 3258},
    {"GyroscopeSampledMinus200dpsX", 0, -3249},
    {"GyroscopeSampledMinus200dpsY", 0, -3266},
    {"GyroscopeSampledMinus200dpsZ", 0, -3252},
    {"GyroscopeBiasAt25degCX", 3, 131},
    {"GyroscopeBiasAt25degCY", 3, 24},
    {"GyroscopeBiasAt25degCZ", 3, -152},
    {"GyroscopeBiasTempSensitivityX", 11, -1312},
    {"GyroscopeBiasTempSensitivityY", 11, -2580},
    {"GyroscopeBiasTempSensitivityZ", 11, 4410},
    {"GyroscopeSample1Temp", 8, 3712},
    {"GyroscopeSample1BiasX", 3, 196},
    {"GyroscopeSample1BiasY", 3, 118},
    {"GyroscopeSample1BiasZ", 3, -322},
    {"GyroscopeSample2Temp", 8, 8640},
    {"GyroscopeSample2BiasX", 3, 92},
    {"GyroscopeSample2BiasY", 3, -73},
    {"GyroscopeSample2BiasZ", 3, 11},
    {"AccelerometerFullScale", -1, 2},  // ±8 g
    {"AccelerometerSensitivityX", 4, 4061},
    {"AccelerometerSensitivityY", 4, 4097},
    {"AccelerometerSensitivityZ", 4, 4139},
    {"AccelerometerBiasX", 8, -1180},
    {"AccelerometerBiasY", 8, -640},
    {"AccelerometerBiasZ", 8, -920},
    {"AccelerometerSampledPlus1gX", 4, 3980},
    {"AccelerometerSampledPlus1gY", 4, 4075},
    {"AccelerometerSampledPlus1gZ", 4, 4083},
    {"AccelerometerSampledMinus1gX", 4, -4141},
    {"AccelerometerSampledMinus1gY", 4, -4120},
    {"AccelerometerSampledMinus1gZ", 4, -4196},
    {"MagnetometerFullScale", -1, 1},
    {"MagnetometerSensitivityX", 4, 6302},
    {"MagnetometerSensitivityY", 4, 6417},
    {"MagnetometerSensitivityZ", 4, 6330},
    {"MagnetometerBiasX", 8, 1024},
    {"MagnetometerBiasY", 8, -471},
    {"MagnetometerBiasZ", 8, 2650},
    {"MagnetometerHardIronBiasX", 11, 84},
    {"MagnetometerHardIronBiasY", 11, 276},
    {"MagnetometerHardIronBiasZ", 11, -140},
    {"AlgorithmMode", -1, 1},  // IMU mode, as in the paper
    {"AlgorithmKp", 11, 1024},
    {"AlgorithmKi", 15, 0},
    {"AlgorithmInitKp", 11, 20480},
    {"AlgorithmInitPeriod", 11, 6144},
    {"AlgorithmMinValidMag", 11, 409},
    {"AlgorithmMaxValidMag", 11, 1433},
    {"AlgorithmTareQuat0", 15, 32767},
    {"AlgorithmTareQuat1", 15, 0},
    {"AlgorithmTareQuat2", 15, 0},
    {"AlgorithmTareQuat3", 15, 0},
    {"SensorDataMode", -1, 1},  // calibrated
    {"DateTimeDataRate", -1, 0},
    {"BatteryAndThermometerDataRate", -1, 0},
    {"InertialAndMagneticDataRate", -1, 0},
    {"QuaternionDataRate", -1, 0},
    {"SDcardNewFileName", -1, 3},
    {"BatteryShutdownVoltage", 12, 14336},
    {"SleepTimer", -1, 0},
    {"MotionTrigWakeUp", -1, 0},
    {"BluetoothPower", -1, 1},
    {"AuxiliaryPortMode", -1, 0},
    {"DigitalIOdirection", -1, 0},
    {"DigitalIOdataRate", -1, 0},
    {"AnalogueInputDataMode", -1, 1},
    {"AnalogueInputDataRate", -1, 0},
    {"AnalogueInputSensitivity", 4, 19840},
    {"AnalogueInputBias", 8, 0},
    {"PWMoutputFrequency", -1, 50},
    {"ADXL345busDataMode", -1, 1},
    {"ADXL345busDataRate", -1, 0},
    {"ADXL345AsensitivityX", 6, 16384},
    {"ADXL345AsensitivityY", 6, 16384},
    {"ADXL345AsensitivityZ", 6, 16384},
    {"ADXL345AbiasX", 8, 0},
    {"ADXL345AbiasY", 8, 0},
    {"ADXL345AbiasZ", 8, 0},
    {"ADXL345BsensitivityX", 6, 16384},
    {"ADXL345BsensitivityY", 6, 16384},
    {"ADXL345BsensitivityZ", 6, 16384},
    {"ADXL345BbiasX", 8, 0},
    {"ADXL345BbiasY", 8, 0},
    {"ADXL345BbiasZ", 8, 0},
    {"ADXL345CsensitivityX", 6, 16384},
    {"ADXL345CsensitivityY", 6, 16384},
    {"ADXL345CsensitivityZ", 6, 16384},
    {"ADXL345CbiasX", 8, 0},
    {"ADXL345CbiasY", 8, 0},
    {"ADXL345CbiasZ", 8, 0},
    {"ADXL345DsensitivityX", 6, 16384},
    {"ADXL345DsensitivityY", 6, 16384},
    {"ADXL345DsensitivityZ", 6, 16384},
    {"ADXL345DbiasX", 8, 0},
    {"ADXL345DbiasY", 8, 0},
    {"ADXL345DbiasZ", 8, 0},
};

}  // namespace

float XimuRegister::FixedPointValue() const {
  if (q < 0) return std::numeric_limits<float>::quiet_NaN();
  return static_cast<float>(static_cast<std::int16_t>(value)) / static_cast<float>(1 << q);
}

std::uint16_t XimuRateRegisterValue(double rate_hz, const std::string& what) {
  if (rate_hz == 0.0) return 0;
  for (int v = 1; v <= kMaxRateRegisterValue; ++v) {
    if (rate_hz == std::ldexp(1.0, v - 1)) return static_cast<std::uint16_t>(v);
  }
  throw InvalidArgument(what + " must be one of the x-IMU's rates 1, 2, 4, …, 512 Hz (2^(v−1) Hz) or 0 (off), got " +
                        std::to_string(rate_hz) + " Hz");
}

std::vector<XimuRegister> XimuRegisters(const XimuDeviceRates& settings) {
  std::vector<XimuRegister> registers;
  registers.reserve(kXimuRegisterCount);
  for (int address = 0; address < kXimuRegisterCount; ++address) {
    const RegisterSpec& spec = kRegisterSpecs[address];
    XimuRegister r;
    r.address = address;
    r.value = static_cast<std::uint16_t>(spec.value);
    r.q = spec.q;
    r.name = spec.name;
    registers.push_back(r);
  }
  registers[kXimuRegisterDateTimeDataRate].value = XimuRateRegisterValue(settings.date_time_rate_hz, "the date/time rate");
  registers[kXimuRegisterBatteryAndThermometerDataRate].value =
      XimuRateRegisterValue(settings.battery_rate_hz, "the battery/thermometer rate");
  registers[kXimuRegisterInertialAndMagneticDataRate].value =
      XimuRateRegisterValue(settings.inertial_rate_hz, "the inertial (gyroscope) rate");
  registers[kXimuRegisterQuaternionDataRate].value = XimuRateRegisterValue(settings.quaternion_rate_hz, "the quaternion rate");
  return registers;
}

}  // namespace rockfit::io
