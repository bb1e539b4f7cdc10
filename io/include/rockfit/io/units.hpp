// Units at the file boundary (docs/design.md §2): files hold deg/s, g, degrees, µs; rockfit holds SI.
// Each unit is converted once, where a reader takes a number out of a file.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "rockfit/core/block.hpp"

namespace rockfit::io {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kRadPerDeg = kPi / 180.0;
// m/s² per g for accelerometer readings: the model's gravity (docs/design.md §2, 9.81), so that a block at
// rest reads exactly the g of the simulations. It differs from standard gravity 9.80665 by 0.03 %,
// below the calibration accuracy of the x-IMU accelerometer.
inline constexpr double kMetresPerSecond2PerG = core::kStandardGravity;

enum class AngularRateUnit { kDegreesPerSecond, kRadiansPerSecond };
enum class AngleUnit { kDegrees, kRadians };
enum class AccelerationUnit { kG, kMetresPerSecond2 };
enum class TimeUnit { kSeconds, kMilliseconds, kMicroseconds, kNanoseconds };

// Factor from the unit to SI (rad/s, rad, m/s², s).
double ToSi(AngularRateUnit unit);
double ToSi(AngleUnit unit);
double ToSi(AccelerationUnit unit);
double ToSi(TimeUnit unit);

// Spellings accepted in headers ("Gyroscope X (deg/s)", "gx [dps]") and column maps; case-insensitive.
// Angular rate: deg/s, dps, °/s, degrees/s, deg/sec, rad/s, rad/sec. Angle: deg, degrees, °, rad, radians.
// Acceleration: g, m/s2, m/s^2, m/s², ms^-2, m/s/s. Time: s, sec, ms, us, µs, ns.
std::optional<AngularRateUnit> ParseAngularRateUnit(std::string_view text);
std::optional<AngleUnit> ParseAngleUnit(std::string_view text);
std::optional<AccelerationUnit> ParseAccelerationUnit(std::string_view text);
std::optional<TimeUnit> ParseTimeUnit(std::string_view text);

// Canonical spelling: "deg/s", "rad/s", "deg", "rad", "g", "m/s^2", "s", "ms", "us", "ns".
std::string UnitName(AngularRateUnit unit);
std::string UnitName(AngleUnit unit);
std::string UnitName(AccelerationUnit unit);
std::string UnitName(TimeUnit unit);

}  // namespace rockfit::io
