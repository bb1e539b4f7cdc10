#include "text/number_parsing.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

namespace rockfit::io {
namespace {

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

// True for "<digits>,<digits>" with an optional sign: a number written with a decimal comma.
bool LooksLikeDecimalComma(std::string_view text) {
  if (!text.empty() && (text.front() == '-' || text.front() == '+')) text.remove_prefix(1);
  const std::size_t comma = text.find(',');
  if (comma == std::string_view::npos || comma == 0 || comma + 1 >= text.size()) return false;
  if (text.find(',', comma + 1) != std::string_view::npos) return false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (i != comma && !IsDigit(text[i]) && text[i] != 'e' && text[i] != 'E' && text[i] != '-' && text[i] != '+') {
      return false;
    }
  }
  return IsDigit(text[comma - 1]) && IsDigit(text[comma + 1]);
}

}  // namespace

std::string_view TrimSpaces(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

ParsedNumber ParseReal(std::string_view cell, DecimalSeparator separator) {
  std::string_view text = TrimSpaces(cell);
  if (text.empty()) return {NumberStatus::kEmpty, 0.0};

  // A number is short; a copy lets us drop a '+' and turn a decimal comma into a point.
  constexpr std::size_t kMaxNumberLength = 64;  // characters; longer cells are not numbers
  if (text.size() > kMaxNumberLength) return {NumberStatus::kNotANumber, 0.0};
  std::array<char, kMaxNumberLength> buffer{};
  std::size_t length = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (i == 0 && c == '+') {
      if (text.size() == 1 || text[1] == '-' || text[1] == '+') return {NumberStatus::kNotANumber, 0.0};
      continue;  // from_chars rejects a leading '+'
    }
    if (c == ',') {
      if (separator == DecimalSeparator::kPoint) {
        return {LooksLikeDecimalComma(text) ? NumberStatus::kDecimalComma : NumberStatus::kNotANumber, 0.0};
      }
      c = '.';
    } else if (c == '.' && separator == DecimalSeparator::kComma) {
      return {NumberStatus::kNotANumber, 0.0};  // "1.234,5" (thousands point) is not accepted
    }
    buffer[length++] = c;
  }

  double value = 0.0;
  const char* begin = buffer.data();
  const char* end = buffer.data() + length;
  const std::from_chars_result result = std::from_chars(begin, end, value, std::chars_format::general);
  if (result.ec == std::errc::result_out_of_range) return {NumberStatus::kOutOfRange, 0.0};
  if (result.ec != std::errc() || result.ptr != end) return {NumberStatus::kNotANumber, 0.0};
  if (std::isnan(value)) return {NumberStatus::kNaN, value};
  if (std::isinf(value)) return {NumberStatus::kInfinite, value};
  return {NumberStatus::kOk, value};
}

std::optional<std::int64_t> ParseInteger(std::string_view cell) {
  std::string_view text = TrimSpaces(cell);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  std::int64_t value = 0;
  const std::from_chars_result result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace rockfit::io
