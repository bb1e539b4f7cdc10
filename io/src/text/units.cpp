#include "rockfit/io/units.hpp"

#include "text/header_matching.hpp"

namespace rockfit::io {
namespace {

bool OneOf(std::string_view text, std::initializer_list<std::string_view> spellings) {
  const std::string normalized = NormalizeHeader(text);
  for (std::string_view spelling : spellings) {
    if (normalized == spelling) return true;
  }
  return false;
}

}  // namespace

double ToSi(AngularRateUnit unit) { return unit == AngularRateUnit::kDegreesPerSecond ? kRadPerDeg : 1.0; }
double ToSi(AngleUnit unit) { return unit == AngleUnit::kDegrees ? kRadPerDeg : 1.0; }
double ToSi(AccelerationUnit unit) { return unit == AccelerationUnit::kG ? kMetresPerSecond2PerG : 1.0; }
double ToSi(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kSeconds:
      return 1.0;
    case TimeUnit::kMilliseconds:
      return 1e-3;
    case TimeUnit::kMicroseconds:
      return 1e-6;
    case TimeUnit::kNanoseconds:
      return 1e-9;
  }
  return 1.0;
}

std::optional<AngularRateUnit> ParseAngularRateUnit(std::string_view text) {
  if (OneOf(text, {"deg/s", "dps", "°/s", "degrees/s", "degree/s", "deg s^-1", "deg/sec", "°/sec", "deg s-1"})) return AngularRateUnit::kDegreesPerSecond;
  if (OneOf(text, {"rad/s", "radians/s", "rad s^-1", "rad/sec", "rad s-1", "rads/s"})) return AngularRateUnit::kRadiansPerSecond;
  return std::nullopt;
}

std::optional<AngleUnit> ParseAngleUnit(std::string_view text) {
  if (OneOf(text, {"deg", "degrees", "degree", "°"})) return AngleUnit::kDegrees;
  if (OneOf(text, {"rad", "radians", "radian"})) return AngleUnit::kRadians;
  return std::nullopt;
}

std::optional<AccelerationUnit> ParseAccelerationUnit(std::string_view text) {
  // "G" (upper case) is Gauss in x-IMU headers, but this parser is case-insensitive, so it is only
  // applied to accelerometer columns.
  if (OneOf(text, {"g"})) return AccelerationUnit::kG;
  if (OneOf(text, {"m/s2", "m/s^2", "m/s²", "m s^-2", "m s-2", "ms^-2", "ms-2", "m/s/s", "m/sec^2"})) return AccelerationUnit::kMetresPerSecond2;
  return std::nullopt;
}

std::optional<TimeUnit> ParseTimeUnit(std::string_view text) {
  if (OneOf(text, {"s", "sec", "seconds"})) return TimeUnit::kSeconds;
  if (OneOf(text, {"ms", "milliseconds"})) return TimeUnit::kMilliseconds;
  if (OneOf(text, {"us", "µs", "μs", "microseconds"})) return TimeUnit::kMicroseconds;
  if (OneOf(text, {"ns", "nanoseconds"})) return TimeUnit::kNanoseconds;
  return std::nullopt;
}

std::string UnitName(AngularRateUnit unit) { return unit == AngularRateUnit::kDegreesPerSecond ? "deg/s" : "rad/s"; }
std::string UnitName(AngleUnit unit) { return unit == AngleUnit::kDegrees ? "deg" : "rad"; }
std::string UnitName(AccelerationUnit unit) { return unit == AccelerationUnit::kG ? "g" : "m/s^2"; }
std::string UnitName(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kSeconds:
      return "s";
    case TimeUnit::kMilliseconds:
      return "ms";
    case TimeUnit::kMicroseconds:
      return "us";
    case TimeUnit::kNanoseconds:
      return "ns";
  }
  return "s";
}

}  // namespace rockfit::io
