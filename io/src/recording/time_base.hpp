// Time bases of the readers. Either uniform, t_k = k/f_s (x-IMU GUI files, which have no time
// column), or device timestamps (x-IMU3, generic CSV with a time column): then the rate is 1 / the
// median step and steps longer than kGapStepFactor × median are gaps (dropped samples).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "text/csv_table.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

// A step longer than this many median steps is a gap. The x-IMU3 clock jitters by < 0.1 % of a
// step; one lost sample doubles the step.
inline constexpr double kGapStepFactor = 1.5;
// A rate given (--rate, manifest) for a file with timestamps must agree with 1 / median step to this
// relative tolerance: device clocks are good to < 0.1 %, a mistaken rate is off by far more.
inline constexpr double kGivenRateTolerance = 0.05;

// The numbers of `column` (whole numbers when `integers`), which must increase strictly from row to
// row. A repeated or smaller value throws BadInput naming both lines; `todo_on_repeat` says what to
// do about a repeated value in this kind of file.
std::vector<double> ReadIncreasingColumn(const CsvTable& table, std::size_t column, bool integers,
                                         const std::string& todo_on_repeat);

// t_k = k / rate_hz, k = 0 … n−1.
std::vector<double> UniformTimes(std::size_t n, double rate_hz);

struct TimestampTimeBase {
  std::vector<double> t_s;     // timestamps relative to the first one [s]
  double median_step_s = 0.0;  // median of the steps [s]
  double rate_hz = 0.0;        // 1 / median_step_s
  std::vector<Gap> gaps;       // steps longer than kGapStepFactor × median
};

// From strictly increasing times [s] (any origin), at least two of them.
TimestampTimeBase TimeBaseFromTimestamps(const std::vector<double>& times_s);

// Steps of t_s longer than kGapStepFactor × nominal_step_s.
std::vector<Gap> FindGaps(const std::vector<double>& t_s, double nominal_step_s);

}  // namespace rockfit::io
