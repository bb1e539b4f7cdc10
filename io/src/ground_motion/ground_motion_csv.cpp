#include "rockfit/io/ground_motion_csv.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "text/csv_table.hpp"
#include "text/input_problem.hpp"

namespace rockfit::io {
namespace {

// Time steps may differ from the first by this fraction of it (rounding of printed times).
constexpr double kUniformStepRelTol = 1e-6;

// Lower case, without a unit in brackets and without spaces: "Time [s]" → "time".
std::string BareName(const std::string& header) {
  std::string out;
  for (char c : header) {
    if (c == '[' || c == '(') break;
    if (c != ' ') out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

std::string RoleOf(const std::string& bare) {
  if (bare == "x" || bare == "h1" || bare == "ax") return "h1";
  if (bare == "y" || bare == "h2" || bare == "ay") return "h2";
  if (bare == "z" || bare == "v" || bare == "vertical" || bare == "az") return "v";
  return "";
}

// "h1" → "first horizontal component (x)", for messages.
std::string RoleName(const std::string& role) {
  if (role == "h1") return "first horizontal component (x)";
  if (role == "h2") return "second horizontal component (y)";
  return "vertical component (z)";
}

}  // namespace

GroundAccelerationUnit ParseGroundAccelerationUnit(const std::string& text) {
  if (text == "g") return GroundAccelerationUnit::kG;
  if (text == "m/s2" || text == "m/s^2") return GroundAccelerationUnit::kMetrePerSecond2;
  if (text == "cm/s2" || text == "cm/s^2" || text == "gal") return GroundAccelerationUnit::kCentimetrePerSecond2;
  throw InvalidArgument("unknown acceleration unit '" + text + "'; use g, m/s2 or cm/s2");
}

const char* UnitName(GroundAccelerationUnit unit) {
  switch (unit) {
    case GroundAccelerationUnit::kG: return "g";
    case GroundAccelerationUnit::kMetrePerSecond2: return "m/s2";
    case GroundAccelerationUnit::kCentimetrePerSecond2: return "cm/s2";
  }
  return "g";
}

double ToMetrePerSecond2(GroundAccelerationUnit unit) {
  switch (unit) {
    case GroundAccelerationUnit::kG: return core::kRecordGravity;
    case GroundAccelerationUnit::kMetrePerSecond2: return 1.0;
    case GroundAccelerationUnit::kCentimetrePerSecond2: return 0.01;
  }
  return 1.0;
}

GroundMotionComponents ReadGroundMotionCsv(const std::filesystem::path& path, const CsvGroundMotionOptions& options) {
  std::vector<std::string> warnings;
  const CsvTable table = CsvTable::ReadFile(path, warnings);
  GroundMotionComponents out;
  out.source = path.string();
  int time_column = -1;
  std::vector<std::size_t> columns;
  for (std::size_t c = 0; c < table.column_count(); ++c) {
    const std::string bare = BareName(table.header()[c]);
    if (bare == "t" || bare == "time" || bare == "time_s") {
      time_column = static_cast<int>(c);
    } else {
      columns.push_back(c);
    }
  }
  if (columns.empty() || columns.size() > 3) {
    ThrowBadInput({table.HeaderPosition(0), "header", std::to_string(columns.size()) + " acceleration columns",
                   "one to three (first horizontal, second horizontal, vertical) besides an optional time column",
                   "Write a header such as `time,x,y,z` and one row per sample."});
  }
  // Roles: by name when every column has a known one, else in order.
  std::vector<std::string> named;
  for (std::size_t c : columns) named.push_back(RoleOf(BareName(table.header()[c])));
  const bool by_name = std::none_of(named.begin(), named.end(), [](const std::string& r) { return r.empty(); });
  static const char* kOrder[] = {"h1", "h2", "v"};
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const std::string role = by_name ? named[k] : kOrder[k];
    const auto first = std::find(out.roles.begin(), out.roles.end(), role);
    if (first != out.roles.end()) {
      const std::size_t first_column = columns[static_cast<std::size_t>(first - out.roles.begin())];
      ThrowBadInput({table.HeaderPosition(columns[k]), table.DescribeColumn(columns[k]),
                     "a second column for the " + RoleName(role) + ", which " + table.DescribeColumn(first_column) +
                         " already is",
                     "each of x, y and z (or h1, h2, v) at most once", "Rename the columns."});
    }
    out.roles.push_back(role);
  }
  const std::size_t rows = table.row_count();
  if (rows < 2) {
    ThrowBadInput({{table.name(), table.header_line() + 1}, "", std::to_string(rows) + " data rows", "at least two samples",
                   "A record needs samples below the header."});
  }
  if (time_column >= 0) {
    const auto tc = static_cast<std::size_t>(time_column);
    const double t0 = table.Real(0, tc);
    out.dt_s = table.Real(1, tc) - t0;
    if (!(out.dt_s > 0.0)) {
      table.ThrowBadCell(1, tc, "a time not after the one before", "increasing times", "Sort the rows by time.");
    }
    for (std::size_t r = 1; r < rows; ++r) {
      const double step = table.Real(r, tc) - table.Real(r - 1, tc);
      if (std::abs(step - out.dt_s) > kUniformStepRelTol * out.dt_s) {
        table.ThrowBadCell(r, tc, "a step of " + std::to_string(step) + " s",
                           "the uniform step of the first two rows, " + std::to_string(out.dt_s) + " s",
                           "Resample the record to a uniform step.");
      }
    }
  } else {
    if (!options.dt_s) {
      ThrowBadInput({table.HeaderPosition(0), "header", "no time column", "a column named time (s), or --dt",
                     "Add a time column or give the step with --dt SECONDS."});
    }
    if (!(*options.dt_s > 0.0) || !std::isfinite(*options.dt_s)) {
      ThrowBadInput({table.HeaderPosition(0), "header",
                     "no time column, and the step given is " + std::to_string(*options.dt_s) + " s",
                     "a positive step (--dt SECONDS) for a record without a time column",
                     "Give the record's step with --dt, or add a time column."});
    }
    out.dt_s = *options.dt_s;
  }
  const double factor = ToMetrePerSecond2(options.unit);
  for (std::size_t c : columns) {
    std::vector<double> values(rows);
    for (std::size_t r = 0; r < rows; ++r) {
      values[r] = factor * table.Real(r, c);
      // A finite value in the file's unit can overflow in m/s² (1e308 g); such a cell is as bad as "inf".
      if (!std::isfinite(values[r])) {
        table.ThrowBadCell(r, c, "a value too large to convert to m/s²", "a ground acceleration",
                           "Check the column's unit and the value on this line.");
      }
    }
    out.accel_m_s2.push_back(std::move(values));
  }
  return out;
}

}  // namespace rockfit::io
