// Locale-independent parsing of numeric CSV cells with std::from_chars: the result never depends on
// the user's locale (a Hungarian or German setting would make strtod read "1.5" as 1).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace rockfit::io {

// How a cell writes the decimal separator. kComma is only used for ';'-separated files, where a
// comma cannot be a field separator (see io/README.md, "Reading recordings").
enum class DecimalSeparator { kPoint, kComma };

enum class NumberStatus {
  kOk,          // a finite number
  kEmpty,       // nothing but spaces
  kNaN,         // "NaN" (any case), as the x-IMU writes for an undefined pitch
  kInfinite,    // "Inf", "Infinity", "∞" is not accepted
  kOutOfRange,  // digits that overflow a double, e.g. 1e400
  kDecimalComma,  // "1,25" in a file that uses the decimal point
  kNotANumber,  // anything else
};

struct ParsedNumber {
  NumberStatus status = NumberStatus::kNotANumber;
  double value = 0.0;  // meaningful for kOk, kNaN (NaN) and kInfinite (±∞)
};

// Spaces and tabs removed at both ends.
std::string_view TrimSpaces(std::string_view text);

// Parses a real number: optional sign ('+' or '-'), digits with one decimal separator, optional
// exponent ("-6.113857E-05"); leading and trailing spaces are ignored.
ParsedNumber ParseReal(std::string_view cell, DecimalSeparator separator = DecimalSeparator::kPoint);

// Parses a whole number (optional sign, digits only). std::nullopt for anything else.
std::optional<std::int64_t> ParseInteger(std::string_view cell);

}  // namespace rockfit::io
