#include "generic/generic_csv_reader.hpp"

#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "text/column_lookup.hpp"
#include "text/header_matching.hpp"
#include "recording/recording_assembly.hpp"
#include "recording/time_base.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {
namespace {

// The header cell whose name (before a "(unit)") is `name`, if any.
std::optional<std::size_t> FindByName(const CsvTable& table, std::string_view name) {
  for (std::size_t column = 0; column < table.column_count(); ++column) {
    if (HeaderEquals(SplitHeaderUnit(table.header()[column]).name, name)) return column;
  }
  return std::nullopt;
}

std::optional<std::size_t> FindExact(const CsvTable& table, std::string_view name) {
  for (std::size_t column = 0; column < table.column_count(); ++column) {
    if (HeaderEquals(table.header()[column], name)) return column;
  }
  return std::nullopt;
}

// Three columns "<prefix> X/Y/Z (unit)" or "<snake>_{x,y,z}_<suffix>"; true when all were found.
bool FindTriple(const CsvTable& table, const std::array<std::string, 3>& names, std::array<std::string, 3>& out,
                bool by_name) {
  std::array<std::string, 3> found;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::optional<std::size_t> column = by_name ? FindByName(table, names[k]) : FindExact(table, names[k]);
    if (!column) return false;
    found[k] = table.header()[*column];
  }
  out = found;
  return true;
}

template <typename Unit>
Unit ResolveUnit(const CsvTable& table, std::size_t column, const std::optional<Unit>& given,
                 std::optional<Unit> (*parse)(std::string_view), const std::string& allowed) {
  const std::string header_unit = SplitHeaderUnit(table.header()[column]).unit;
  const std::optional<Unit> from_header = parse(header_unit);
  if (given) {
    if (from_header && *from_header != *given) {
      ThrowBadInput({table.HeaderPosition(column), table.DescribeColumn(column), "the unit '" + header_unit + "'",
                     "'" + UnitName(*given) + "' as the column map says",
                     "Correct the unit in the column map (name@unit) or in the header."});
    }
    return *given;
  }
  return HeaderUnit(table, column, parse, allowed);
}

}  // namespace

ColumnMap DetectColumnMap(const CsvTable& table) {
  ColumnMap map;
  // Gyroscope.
  if (!FindTriple(table, {"Gyroscope X", "Gyroscope Y", "Gyroscope Z"}, map.gyro, true)) {
    if (FindTriple(table, {"gyro_x_dps", "gyro_y_dps", "gyro_z_dps"}, map.gyro, false)) {
      map.gyro_unit = AngularRateUnit::kDegreesPerSecond;
    } else if (FindTriple(table, {"gyro_x_rad_s", "gyro_y_rad_s", "gyro_z_rad_s"}, map.gyro, false)) {
      map.gyro_unit = AngularRateUnit::kRadiansPerSecond;
    } else {
      ThrowBadInput({{table.name(), table.header_line()}, "", "no gyroscope columns that rockfit recognises",
                     "columns 'Gyroscope X (deg/s)', 'Gyroscope Y (deg/s)', 'Gyroscope Z (deg/s)' (or gyro_x_dps, "
                     "gyro_x_rad_s, …)",
                     "Say which columns hold what with a column map, e.g. --columns \"time=t@s;gyro=wx,wy,wz@rad/s\" "
                     "(see rockfit inspect --help), or pick the right file."});
    }
  }
  // Time.
  for (const char* name : {"Time", "Timestamp", "t"}) {
    if (const auto column = FindByName(table, name)) {
      if (ParseTimeUnit(SplitHeaderUnit(table.header()[*column]).unit)) {
        map.time = table.header()[*column];
        break;
      }
    }
  }
  if (map.time.empty()) {
    for (const auto& [name, unit] : {std::pair{"time_s", TimeUnit::kSeconds}, std::pair{"t_s", TimeUnit::kSeconds},
                                     std::pair{"timestamp_us", TimeUnit::kMicroseconds}}) {
      if (const auto column = FindExact(table, name)) {
        map.time = table.header()[*column];
        map.time_unit = unit;
        break;
      }
    }
  }
  // Attitude and accelerometer, when all three columns are there.
  if (!FindTriple(table, {"Roll", "Pitch", "Yaw"}, map.euler, true)) {
    if (FindTriple(table, {"roll_deg", "pitch_deg", "yaw_deg"}, map.euler, false)) map.euler_unit = AngleUnit::kDegrees;
    else if (FindTriple(table, {"roll_rad", "pitch_rad", "yaw_rad"}, map.euler, false)) map.euler_unit = AngleUnit::kRadians;
    else map.euler = {};
  }
  if (!FindTriple(table, {"Accelerometer X", "Accelerometer Y", "Accelerometer Z"}, map.accel, true)) {
    if (FindTriple(table, {"accel_x_g", "accel_y_g", "accel_z_g"}, map.accel, false)) {
      map.accel_unit = AccelerationUnit::kG;
    } else if (FindTriple(table, {"accel_x_m_s2", "accel_y_m_s2", "accel_z_m_s2"}, map.accel, false)) {
      map.accel_unit = AccelerationUnit::kMetresPerSecond2;
    } else {
      map.accel = {};
    }
  }
  return map;
}

Recording ReadGenericCsvRecording(const std::filesystem::path& file, const LoadOptions& options) {
  options.Validate();
  Recording recording;
  recording.format = FormatName(RecordingFormat::kGenericCsv);
  recording.source = file.string();
  const CsvTable table = CsvTable::ReadFile(file, recording.warnings);
  const std::string file_name = file.filename().string();
  const ColumnMap map = options.columns ? *options.columns : DetectColumnMap(table);
  map.Validate();

  if (options.orientation == OrientationChoice::kQuaternion || options.orientation == OrientationChoice::kRotationMatrix) {
    throw InvalidArgument("--orientation " + OrientationChoiceName(options.orientation) +
                          " is not available for generic CSV files; map Euler angle columns (euler=…) and use "
                          "--orientation auto, euler or none");
  }
  const bool use_euler = map.has_euler() && options.orientation != OrientationChoice::kNone;
  if (options.orientation == OrientationChoice::kEulerAngles && !map.has_euler()) {
    ThrowBadInput({{file.string(), table.header_line()}, "", "no Euler angle columns in the column map",
                   "euler=ROLL,PITCH,YAW columns for --orientation euler",
                   "Add them to the column map, or use --orientation none."});
  }

  std::vector<ColumnSpec> specs;
  const std::string map_note = options.columns ? " (from the column map)" : "";
  if (map.has_time()) specs.push_back({{map.time}, "time" + map_note});
  static const std::array<const char*, 3> kAxis = {"x", "y", "z"};
  for (std::size_t k = 0; k < 3; ++k) specs.push_back({{map.gyro[k]}, std::string("gyroscope ") + kAxis[k] + map_note});
  if (use_euler) {
    static const std::array<const char*, 3> kRole = {"roll φx", "pitch φy", "yaw φz"};
    for (std::size_t k = 0; k < 3; ++k) specs.push_back({{map.euler[k]}, std::string(kRole[k]) + map_note});
  }
  if (map.has_accel()) {
    for (std::size_t k = 0; k < 3; ++k) specs.push_back({{map.accel[k]}, std::string("accelerometer ") + kAxis[k] + map_note});
  }
  const auto columns = ResolveColumns(table, specs);
  std::size_t next = 0;
  const std::size_t time_column = map.has_time() ? *columns[next++] : 0;
  std::array<std::size_t, 3> gyro{};
  for (std::size_t& column : gyro) column = *columns[next++];
  std::array<std::size_t, 3> euler{};
  if (use_euler) {
    for (std::size_t& column : euler) column = *columns[next++];
  }
  std::array<std::size_t, 3> accel{};
  if (map.has_accel()) {
    for (std::size_t& column : accel) column = *columns[next++];
  }
  for (const auto& column : columns) recording.columns.push_back(file_name + ": " + table.header()[*column]);

  const std::size_t n = table.row_count();
  SensorSamples samples;
  if (map.has_time()) {
    const double scale = ToSi(ResolveUnit(table, time_column, map.time_unit, &ParseTimeUnit, "s, ms, us"));
    std::vector<double> times = ReadIncreasingColumn(
        table, time_column, false,
        "Each sample needs its own time: a repeated time means a duplicated line or a clock of too coarse a "
        "resolution. Delete the repeated line, or leave the time column out and give the rate.");
    if (n < 2) {
      ThrowBadInput({{file.string(), table.Line(0)}, "", "a single sample",
                     "at least two samples to find the rate from their times", "Pick a longer recording."});
    }
    for (double& t : times) t *= scale;
    TimestampTimeBase base = TimeBaseFromTimestamps(times);
    // No IMU samples faster than 1 MHz: closer times are a wrong unit or a broken clock (and 1/step overflows).
    constexpr double kMinMedianStep_s = 1e-6;
    if (!(base.median_step_s >= kMinMedianStep_s)) {
      ThrowBadInput({table.HeaderPosition(time_column), table.DescribeColumn(time_column),
                     fmt::format("times {:.6g} s apart (median), too close for a sample rate", base.median_step_s),
                     "times at least a microsecond apart",
                     "Check the time column's unit in the column map (time=NAME@s, @ms or @us)."});
    }
    recording.rate_hz = base.rate_hz;
    recording.rate_source = RateSource::kTimestamps;
    if (options.rate_hz && std::abs(*options.rate_hz / base.rate_hz - 1.0) > kGivenRateTolerance) {
      ThrowBadInput({table.HeaderPosition(time_column), table.DescribeColumn(time_column),
                     fmt::format("times {:.6g} s apart (median), i.e. {:.6g} Hz", base.median_step_s, base.rate_hz),
                     fmt::format("the rate given {} ({:g} Hz)",
                                 options.rate_origin == RateSource::kManifest ? "in the manifest" : "with --rate",
                                 *options.rate_hz),
                     "The file carries its own time: leave the rate out, or correct it."});
    }
    samples.t_s = std::move(base.t_s);
    samples.gaps = std::move(base.gaps);
  } else if (options.rate_hz) {
    recording.rate_hz = *options.rate_hz;
    recording.rate_source = options.rate_origin;
    samples.t_s = UniformTimes(n, *options.rate_hz);
  } else {
    ThrowBadInput({{file.string(), table.header_line()}, "", "no time column",
                   "a time column or a sample rate",
                   "Pass --rate HZ (or `rate` in the manifest), or name the time column in the column map "
                   "(time=NAME@s)."});
  }

  std::array<double, 3> gyro_scale{};
  for (std::size_t k = 0; k < 3; ++k) {
    gyro_scale[k] = ToSi(ResolveUnit(table, gyro[k], map.gyro_unit, &ParseAngularRateUnit, "deg/s, rad/s"));
  }
  samples.w_S.resize(n);
  for (std::size_t row = 0; row < n; ++row) {
    for (std::size_t k = 0; k < 3; ++k) samples.w_S[row][static_cast<Eigen::Index>(k)] = table.RealInSi(row, gyro[k], gyro_scale[k]);
  }
  if (map.has_accel()) {
    std::array<double, 3> scale{};
    for (std::size_t k = 0; k < 3; ++k) {
      scale[k] = ToSi(ResolveUnit(table, accel[k], map.accel_unit, &ParseAccelerationUnit, "g, m/s^2"));
    }
    samples.accel_S.resize(n);
    for (std::size_t row = 0; row < n; ++row) {
      for (std::size_t k = 0; k < 3; ++k) samples.accel_S[row][static_cast<Eigen::Index>(k)] = table.RealInSi(row, accel[k], scale[k]);
    }
  }
  if (use_euler) {
    std::array<double, 3> scale{};
    for (std::size_t k = 0; k < 3; ++k) scale[k] = ToSi(ResolveUnit(table, euler[k], map.euler_unit, &ParseAngleUnit, "deg, rad"));
    samples.orientation.t_s = samples.t_s;
    samples.orientation.q_WS.resize(n);
    for (std::size_t row = 0; row < n; ++row) {
      const double roll = table.RealInSi(row, euler[0], scale[0]);
      const double pitch = table.RealInSi(row, euler[1], scale[1]);
      const double yaw = table.RealInSi(row, euler[2], scale[2]);
      samples.orientation.q_WS[row] = QuaternionFromEulerZyx({yaw, pitch, roll});
    }
    recording.orientation_source = file_name;
    recording.orientation_rate_hz = recording.rate_hz;
  }

  AssembleRecording(std::move(samples), options.mounting, recording);
  return recording;
}

}  // namespace rockfit::io
