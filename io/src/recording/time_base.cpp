#include "recording/time_base.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

std::vector<double> ReadIncreasingColumn(const CsvTable& table, std::size_t column, bool integers,
                                         const std::string& todo_on_repeat) {
  std::vector<double> values(table.row_count());
  for (std::size_t row = 0; row < table.row_count(); ++row) {
    values[row] = integers ? static_cast<double>(table.Integer(row, column)) : table.Real(row, column);
    if (row == 0 || values[row] > values[row - 1]) continue;
    const std::string cell(table.Cell(row, column));
    const std::string previous_line = std::to_string(table.Line(row - 1));
    if (values[row] == values[row - 1]) {
      table.ThrowBadCell(row, column, "'" + cell + "' again (as on line " + previous_line + ")",
                         "a value larger than on the line before", todo_on_repeat);
    }
    table.ThrowBadCell(
        row, column,
        "'" + cell + "', smaller than '" + std::string(table.Cell(row - 1, column)) + "' on line " + previous_line,
        "values that increase from line to line",
        "Time cannot run backwards: the file mixes two recordings or was edited or sorted. Split it "
        "where the values restart, or restore the original file.");
  }
  return values;
}

std::vector<double> UniformTimes(std::size_t n, double rate_hz) {
  std::vector<double> t_s(n);
  for (std::size_t k = 0; k < n; ++k) t_s[k] = static_cast<double>(k) / rate_hz;
  return t_s;
}

TimestampTimeBase TimeBaseFromTimestamps(const std::vector<double>& times_s) {
  if (times_s.size() < 2) {
    throw InvalidArgument("TimeBaseFromTimestamps needs at least two timestamps");
  }
  TimestampTimeBase base;
  base.t_s.resize(times_s.size());
  for (std::size_t k = 0; k < times_s.size(); ++k) base.t_s[k] = times_s[k] - times_s[0];
  std::vector<double> steps(times_s.size() - 1);
  for (std::size_t k = 0; k + 1 < times_s.size(); ++k) steps[k] = times_s[k + 1] - times_s[k];
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  double median = *middle;
  if (steps.size() % 2 == 0) median = 0.5 * (median + *std::max_element(steps.begin(), middle));
  base.median_step_s = median;
  base.rate_hz = 1.0 / median;
  base.gaps = FindGaps(base.t_s, median);
  return base;
}

std::vector<Gap> FindGaps(const std::vector<double>& t_s, double nominal_step_s) {
  std::vector<Gap> gaps;
  for (std::size_t k = 0; k + 1 < t_s.size(); ++k) {
    const double step = t_s[k + 1] - t_s[k];
    if (step <= kGapStepFactor * nominal_step_s) continue;
    Gap gap;
    gap.index = k;
    gap.t_s = t_s[k];
    gap.duration_s = step;
    // Clamped where a double still counts exactly (2^53): a time jump of 10^19 steps is a bad file, not a count.
    constexpr double kMaxMissing = 9007199254740992.0;
    gap.missing = static_cast<std::size_t>(std::clamp(std::round(step / nominal_step_s) - 1.0, 1.0, kMaxMissing));
    gaps.push_back(gap);
  }
  return gaps;
}

}  // namespace rockfit::io
