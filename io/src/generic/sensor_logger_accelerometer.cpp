#include "generic/sensor_logger_accelerometer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <fmt/format.h>

#include "generic/csv_time_column.hpp"
#include "text/column_lookup.hpp"
#include "text/input_problem.hpp"
#include "text/number_parsing.hpp"

namespace rockfit::io {
namespace {

std::string FileName(const CsvTable& table) { return std::filesystem::path(table.name()).filename().string(); }

// First time of `accel` minus first time of `gyro` [s]: exact for whole numbers (nanoseconds since 1970 are 1.7·10^18,
// beyond a double's 2^53; their difference is small), else from the numbers as read.
double StartOffset_s(const CsvTable& accel, std::size_t accel_column, const CsvTable& gyro, std::size_t gyro_column,
                     TimeUnit unit) {
  const auto a = ParseInteger(accel.Cell(0, accel_column));
  const auto g = ParseInteger(gyro.Cell(0, gyro_column));
  std::int64_t difference = 0;
  if (a && g && !__builtin_sub_overflow(*a, *g, &difference)) return static_cast<double>(difference) * ToSi(unit);
  return (accel.Real(0, accel_column) - gyro.Real(0, gyro_column)) * ToSi(unit);
}

double MedianStep_s(const std::vector<double>& t_s) {
  std::vector<double> steps;
  for (std::size_t k = 1; k < t_s.size(); ++k) steps.push_back(t_s[k] - t_s[k - 1]);
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

[[noreturn]] void FailCoverage(const CsvTable& accel, std::size_t row, std::size_t column, const CsvTable& gyro,
                               std::size_t gyro_row, std::size_t gyro_column, const std::string& found,
                               double edge_s) {
  const TextPosition gyro_at = gyro.PositionOf(gyro_row, gyro_column);
  ThrowBadInput({accel.PositionOf(row, column), fmt::format("{}'s time", FileName(accel)),
                 fmt::format("{} the gyro's sample at {}", found, FormatPosition(gyro_at)),
                 fmt::format("the accelerometer's times to cover the gyro's, to within {:.3g} s ({:g} of its sample "
                             "steps)",
                             edge_s, kAccelerometerEdgeSteps),
                 fmt::format("Both files must come from the same recording, with times in the same base (Sensor "
                             "Logger writes nanoseconds since 1970 in both). Export them again together, or move {} "
                             "away to integrate the attitude from the gyro alone.",
                             FileName(accel))});
}

}  // namespace

SensorLoggerAccelerometer ResampleSensorLoggerAccelerometer(const CsvTable& accel, const CsvTable& gyro,
                                                            std::size_t gyro_time_column, TimeUnit time_unit,
                                                            const std::vector<double>& gyro_t_s) {
  const auto columns = ResolveColumns(accel, {{{"time"}, "time (ns since 1970)"},
                                              {{"x"}, "accelerometer x"},
                                              {{"y"}, "accelerometer y"},
                                              {{"z"}, "accelerometer z"}});
  const std::size_t time_column = *columns[0];
  const std::array<std::size_t, 3> axis{*columns[1], *columns[2], *columns[3]};
  const std::size_t n = accel.row_count();
  if (n < 2) {
    ThrowBadInput({{accel.name(), n == 0 ? accel.header_line() : accel.Line(0)}, "", n == 0 ? "no samples" : "a single sample",
                   "at least two accelerometer samples to interpolate between",
                   "Export the recording with its accelerometer, or move the file away."});
  }
  if (gyro_t_s.empty()) return {};
  CsvTimeColumn time = ReadCsvTimeColumn(accel, time_column, time_unit);
  const double offset_s = StartOffset_s(accel, time_column, gyro, gyro_time_column, time_unit);
  std::vector<double> t_s(n);  // on the gyro's time axis
  for (std::size_t k = 0; k < n; ++k) t_s[k] = time.t_s[k] + offset_s;
  const double edge_s = kAccelerometerEdgeSteps * MedianStep_s(t_s);
  if (gyro_t_s.front() < t_s.front() - edge_s) {
    FailCoverage(accel, 0, time_column, gyro, 0, gyro_time_column,
                 fmt::format("the first sample {:.6g} s after", t_s.front() - gyro_t_s.front()), edge_s);
  }
  if (gyro_t_s.back() > t_s.back() + edge_s) {
    FailCoverage(accel, n - 1, time_column, gyro, gyro_t_s.size() - 1, gyro_time_column,
                 fmt::format("the last sample {:.6g} s before", gyro_t_s.back() - t_s.back()), edge_s);
  }

  std::vector<Eigen::Vector3d> values(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (int i = 0; i < 3; ++i) values[k][i] = accel.RealInSi(k, axis[static_cast<std::size_t>(i)], 1.0);  // m/s²
  }
  SensorLoggerAccelerometer out;
  out.accel_S.resize(gyro_t_s.size());
  std::size_t j = 0;  // t_s[j] ≤ t < t_s[j + 1] for the current gyro time, both in increasing order
  for (std::size_t k = 0; k < gyro_t_s.size(); ++k) {
    const double t = gyro_t_s[k];
    while (j + 2 < n && t_s[j + 1] <= t) ++j;
    if (t <= t_s.front()) {
      out.accel_S[k] = values.front();
    } else if (t >= t_s.back()) {
      out.accel_S[k] = values.back();
    } else {
      const double w = (t - t_s[j]) / (t_s[j + 1] - t_s[j]);
      out.accel_S[k] = (1.0 - w) * values[j] + w * values[j + 1];
    }
  }
  const std::string name = FileName(accel);
  for (std::size_t i = 0; i < 3; ++i) out.columns.push_back(name + ": " + accel.header()[axis[i]]);
  out.notes.push_back(fmt::format(
      "accelerometer: {} beside the gyroscope file (Sensor Logger's specific force, gravity included), columns x, y, "
      "z in m/s², {} samples, its first {:+.6f} s from the gyro's; interpolated linearly onto the gyro's times",
      name, n, offset_s));
  for (std::string& note : time.notes) out.notes.push_back(name + " " + note);
  return out;
}

}  // namespace rockfit::io
