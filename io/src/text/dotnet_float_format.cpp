#include "text/dotnet_float_format.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rockfit::io {
namespace {

// Digits printed by "%.16e": 17 significant digits, correctly rounded from the exact binary value.
// They decide the 7-digit rounding exactly: a float (24-bit significand) that is not itself a 7-digit tie
// lies at least ~6e-16 (relative) away from one, far more than the 1e-17 resolution of 17 digits.
constexpr int kExactDigits = 17;

}  // namespace

void AppendDotNetSingle(std::string& out, float value) {
  if (std::isnan(value)) {
    out += "NaN";
    return;
  }
  if (std::isinf(value)) {
    out += value > 0 ? "Infinity" : "-Infinity";
    return;
  }
  if (value == 0.0f) {
    out += '0';
    return;
  }
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.16e", static_cast<double>(std::fabs(value)));
  // buffer: "d.dddddddddddddddde±XX"
  char digits[kExactDigits];
  digits[0] = buffer[0];
  for (int i = 1; i < kExactDigits; ++i) digits[i] = buffer[i + 1];
  int exponent = std::atoi(buffer + kExactDigits + 2);

  // Round to 7 significant digits, ties away from zero (the .NET Framework rule).
  if (digits[kDotNetSingleDigits] >= '5') {
    int i = kDotNetSingleDigits - 1;
    while (i >= 0 && digits[i] == '9') digits[i--] = '0';
    if (i >= 0) {
      ++digits[i];
    } else {
      digits[0] = '1';
      for (int k = 1; k < kDotNetSingleDigits; ++k) digits[k] = '0';
      ++exponent;
    }
  }
  int significant = kDotNetSingleDigits;
  while (significant > 1 && digits[significant - 1] == '0') --significant;

  if (value < 0) out += '-';
  if (exponent < -4 || exponent >= kDotNetSingleDigits) {
    out += digits[0];
    if (significant > 1) {
      out += '.';
      out.append(digits + 1, significant - 1);
    }
    out += 'E';
    out += exponent < 0 ? '-' : '+';
    const int magnitude = std::abs(exponent);
    if (magnitude < 10) out += '0';
    out += std::to_string(magnitude);
  } else if (exponent >= 0) {
    for (int i = 0; i <= exponent; ++i) out += i < significant ? digits[i] : '0';
    if (significant > exponent + 1) {
      out += '.';
      out.append(digits + exponent + 1, significant - exponent - 1);
    }
  } else {
    out += "0.";
    out.append(static_cast<std::size_t>(-exponent - 1), '0');
    out.append(digits, significant);
  }
}

std::string FormatDotNetSingle(float value) {
  std::string text;
  AppendDotNetSingle(text, value);
  return text;
}

}  // namespace rockfit::io
