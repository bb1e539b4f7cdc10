#include "rockfit/core/checks.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit {
namespace {

// Enough digits to tell the offending value from a valid neighbour, without the trailing zeros of to_string.
constexpr int kMessageDigits = 10;

std::string Number(double value) {
  std::ostringstream out;
  out.precision(kMessageDigits);
  out << value;
  return out.str();
}

std::string OfUnit(std::string_view unit) { return unit.empty() ? std::string() : " of " + std::string(unit); }

}  // namespace

void RequireFinite(double value, std::string_view what) {
  if (!std::isfinite(value)) throw InvalidArgument(std::string(what) + " must be a finite number, got " + Number(value));
}

void RequirePositive(double value, std::string_view what, std::string_view unit) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InvalidArgument(std::string(what) + " must be a positive finite number" + OfUnit(unit) + ", got " + Number(value));
  }
}

void RequireNonNegative(double value, std::string_view what, std::string_view unit) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw InvalidArgument(std::string(what) + " must be a finite number ≥ 0" + OfUnit(unit) + ", got " + Number(value));
  }
}

void RequireAtLeast(long long value, long long minimum, std::string_view what) {
  if (value < minimum) {
    throw InvalidArgument(std::string(what) + " must be at least " + std::to_string(minimum) + ", got " +
                          std::to_string(value));
  }
}

void RequireIncreasingRange(double lo, double hi, std::string_view what) {
  RequireFinite(lo, std::string("the lower end of ") + std::string(what));
  RequireFinite(hi, std::string("the upper end of ") + std::string(what));
  if (!(lo < hi)) {
    throw InvalidArgument("the range of " + std::string(what) + " must have min < max, got [" + Number(lo) + ", " +
                          Number(hi) + "]");
  }
}

}  // namespace rockfit
