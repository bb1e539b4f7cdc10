// The acceptance criteria of the automatic fit (docs/design.md §12), shared by the library's system tests
// (tests/fitting/trial_problem_test.cpp) and the command-line ones (tests/tools/cli_fit_recovery_test.cpp).
#pragma once

namespace rockfit::testing {

constexpr double kT0Tolerance_s = 2e-3;
constexpr double kAlphaTolerance_rad = 2e-3;
constexpr double kLambdaLonTolerance = 0.03;
constexpr double kLambdaLatRelative = 0.10;  // of |λ_lat|, with the sign always right
constexpr double kLambdaTolerance = 0.1;     // when edge impacts happen in the window
constexpr double kEpsilonRatio = 1.05;       // ε of the fit over ε of the true parameters

// True when the interval i = [lower, upper] holds the value; a NaN end is open (an interval the data leave open).
template <typename Interval>
bool IntervalHolds(const Interval& i, double value) {
  return !(i[0] > value) && !(i[1] < value);
}

}  // namespace rockfit::testing
