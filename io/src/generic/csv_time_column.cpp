#include "generic/csv_time_column.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

namespace rockfit::io {
namespace {

// GCC's and Clang's 128-bit integer (not ISO C++, hence __extension__): the difference of two 64-bit counts and the
// offset of their wraps, exactly.
__extension__ typedef __int128 Int128;

constexpr const char* kRepeatTodo =
    "Each sample needs its own time: a repeated time means a duplicated line or a clock of too coarse a resolution. "
    "Delete the repeated line, or leave the time column out and give the rate.";
constexpr const char* kBackwardsTodo =
    "Time cannot run backwards: the file mixes two recordings or was edited or sorted. Split it where the values "
    "restart, or restore the original file.";

[[noreturn]] void ThrowNotIncreasing(const CsvTable& table, std::size_t row, std::size_t column, bool repeated) {
  const std::string cell(table.Cell(row, column));
  const std::string previous_line = std::to_string(table.Line(row - 1));
  if (repeated) {
    table.ThrowBadCell(row, column, "'" + cell + "' again (as on line " + previous_line + ")",
                       "a value larger than on the line before", kRepeatTodo);
  }
  table.ThrowBadCell(
      row, column,
      "'" + cell + "', smaller than '" + std::string(table.Cell(row - 1, column)) + "' on line " + previous_line,
      "values that increase from line to line (or a counter that wraps at 2^16 or 2^32)", kBackwardsTodo);
}

// Whole numbers: exact differences from the first, unwrapping 16- and 32-bit counters.
bool ReadIntegers(const CsvTable& table, std::size_t column, double to_si, CsvTimeColumn& out) {
  const std::size_t n = table.row_count();
  std::vector<std::int64_t> values(n);
  for (std::size_t row = 0; row < n; ++row) {
    const auto value = ParseInteger(table.Cell(row, column));
    if (!value) return false;
    values[row] = *value;
  }
  out.t_s.assign(n, 0.0);
  Int128 offset = 0;  // added by wraps so far
  Int128 longest_step = 0;
  for (std::size_t row = 1; row < n; ++row) {
    const Int128 step = static_cast<Int128>(values[row]) - values[row - 1];
    if (step > 0) {
      longest_step = std::max(longest_step, step);
    } else {
      if (step == 0) ThrowNotIncreasing(table, row, column, true);
      std::optional<std::uint64_t> modulus;
      for (const std::uint64_t m : {std::uint64_t{1} << 16, std::uint64_t{1} << 32}) {
        if (values[row] < 0 || values[row - 1] >= static_cast<std::int64_t>(m)) continue;
        const Int128 across = step + static_cast<Int128>(m);
        if (across > 0 && longest_step > 0 &&
            static_cast<double>(across) <= kWrapStepFactor * static_cast<double>(longest_step)) {
          modulus = m;
          break;
        }
      }
      if (!modulus || (out.wrap_modulus != 0 && out.wrap_modulus != *modulus))
        ThrowNotIncreasing(table, row, column, false);
      out.wrap_modulus = *modulus;
      ++out.wraps;
      offset += static_cast<Int128>(*modulus);
      out.notes.push_back(fmt::format("{}: the time counter wraps at 2^{} between lines {} and {} ('{}' → '{}'); "
                                      "unwrapped",
                                      FormatPosition(table.PositionOf(row, column)), *modulus == (1u << 16) ? 16 : 32,
                                      table.Line(row - 1), table.Line(row), table.Cell(row - 1, column),
                                      table.Cell(row, column)));
    }
    const Int128 relative = static_cast<Int128>(values[row]) - values[0] + offset;
    out.t_s[row] = static_cast<double>(relative) * to_si;
  }
  out.absolute = static_cast<double>(values[0]) * to_si >= kEpochThreshold_s;
  return true;
}

void ReadReals(const CsvTable& table, std::size_t column, double to_si, CsvTimeColumn& out) {
  const std::size_t n = table.row_count();
  out.t_s.assign(n, 0.0);
  const double first = table.Real(0, column);
  double previous = first;
  for (std::size_t row = 1; row < n; ++row) {
    const double value = table.Real(row, column);
    if (!(value > previous)) ThrowNotIncreasing(table, row, column, value == previous);
    out.t_s[row] = (value - first) * to_si;
    previous = value;
  }
  out.absolute = first * to_si >= kEpochThreshold_s;
}

}  // namespace

CsvTimeColumn ReadCsvTimeColumn(const CsvTable& table, std::size_t column, TimeUnit unit) {
  CsvTimeColumn out;
  const double to_si = ToSi(unit);
  const bool integers = ReadIntegers(table, column, to_si, out);
  if (!integers) ReadReals(table, column, to_si, out);
  for (std::size_t row = 1; row < out.t_s.size(); ++row) {
    if (!std::isfinite(out.t_s[row])) {
      table.ThrowBadCell(row, column, "a time too large to convert to seconds", "a time within a recording's span",
                         "Check the time column's unit in the column map (time=NAME@s, @ms, @us or @ns).");
    }
  }
  std::string how = fmt::format("time from {} in {}{}", table.DescribeColumn(column), UnitName(unit),
                                integers ? ", whole numbers read exactly" : "");
  if (out.absolute) {
    how += fmt::format("; absolute (Unix epoch) times, the first {} s after 1970-01-01 UTC, taken relative to it",
                       fmt::format("{:.3f}", table.Real(0, column) * to_si));
  }
  out.notes.insert(out.notes.begin(), how);
  return out;
}

}  // namespace rockfit::io
