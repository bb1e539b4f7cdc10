// Text of a single-precision number exactly as the x-IMU GUI writes it: C# `float.ToString(
// CultureInfo.InvariantCulture)` of the .NET Framework ("G" format, 7 significant digits).
//
// Rules (checked against every number in the real x-IMU files, see tests/io/text/dotnet_float_format_test.cpp):
//  * the value is rounded to 7 significant digits, ties away from zero (0.0087890625 → "0.008789063");
//  * trailing zeros and a trailing decimal point are dropped ("2", "-0.125", "15.99951");
//  * fixed notation when the decimal exponent e of the rounded value satisfies −5 < e < 7, otherwise
//    scientific notation with a capital E, a sign and at least two exponent digits ("-6.113857E-05");
//  * zero (of either sign) is "0"; NaN is "NaN"; infinities are "Infinity" and "-Infinity".
#pragma once

#include <string>

namespace rockfit::io {

// Significant digits of the .NET Framework "G" format for System.Single.
inline constexpr int kDotNetSingleDigits = 7;

std::string FormatDotNetSingle(float value);

// Appends FormatDotNetSingle(value) to `out` (no allocation when `out` has capacity).
void AppendDotNetSingle(std::string& out, float value);

}  // namespace rockfit::io
