// Argument checks shared by every rockfit library. Each throws InvalidArgument (exit code 1) with a message that
// names the value and what it had to be: "block b1 must be a positive finite number of metres, got -0.05".
// A `Require…` throws unless its condition holds, a `Throw…` always throws, a `Check…` returns a verdict and
// never throws (docs/design.md §9, "The words of the checks"). Libraries wrap `what` to name their options
// instead of defining these again.
#pragma once

#include <string_view>

namespace rockfit {

void RequireFinite(double value, std::string_view what);
// Finite and > 0. `unit` (plural, "metres") is named in the message when given.
void RequirePositive(double value, std::string_view what, std::string_view unit = {});
// Finite and ≥ 0.
void RequireNonNegative(double value, std::string_view what, std::string_view unit = {});
void RequireAtLeast(long long value, long long minimum, std::string_view what);
// Both ends finite and lo < hi.
void RequireIncreasingRange(double lo, double hi, std::string_view what);

}  // namespace rockfit
