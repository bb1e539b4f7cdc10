#include "generic/generic_csv_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "text/column_lookup.hpp"
#include "text/header_matching.hpp"
#include "recording/recording_assembly.hpp"
#include "recording/time_base.hpp"
#include "generic/csv_time_column.hpp"
#include "generic/sensor_logger_accelerometer.hpp"
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

namespace {

// The first name of `names` that finds three columns "<name> x/y/z" (the unit in the header); true when found.
bool FindAxes(const CsvTable& table, std::initializer_list<std::array<const char*, 3>> names,
              std::array<std::string, 3>& out, std::string* matched) {
  for (const auto& triple : names) {
    if (FindTriple(table, {triple[0], triple[1], triple[2]}, out, true)) {
      *matched = triple[0];
      return true;
    }
  }
  return false;
}

std::string FileName(const CsvTable& table) { return std::filesystem::path(table.name()).filename().string(); }

bool StartsWithNoCase(const std::string& text, std::string_view prefix) {
  return NormalizeHeader(text.substr(0, prefix.size())) == NormalizeHeader(prefix);
}

void Note(std::vector<std::string>* notes, std::string text) {
  if (notes) notes->push_back(std::move(text));
}

// Sensor Logger's files: time (ns since 1970), seconds_elapsed, and x, y, z (in the order z, y, x).
bool IsSensorLoggerHeader(const CsvTable& table) {
  return FindExact(table, "time") && FindExact(table, "seconds_elapsed") && FindExact(table, "x") &&
         FindExact(table, "y") && FindExact(table, "z");
}

}  // namespace

ColumnMap PresetColumnMap(const std::string& preset, const CsvTable& table, std::vector<std::string>* notes) {
  ColumnMap map;
  if (preset == "phyphox") {
    map.time = "Time (s)";
    map.time_unit = TimeUnit::kSeconds;
    map.gyro = {"Gyroscope x (rad/s)", "Gyroscope y (rad/s)", "Gyroscope z (rad/s)"};
    map.gyro_unit = AngularRateUnit::kRadiansPerSecond;
    std::array<std::string, 3> accel;
    if (FindTriple(table, {"Acceleration x (m/s^2)", "Acceleration y (m/s^2)", "Acceleration z (m/s^2)"}, accel, false)) {
      map.accel = accel;
      map.accel_unit = AccelerationUnit::kMetresPerSecond2;
    }
    Note(notes, "layout: phyphox export (preset phyphox): 'Time (s)', 'Gyroscope x/y/z (rad/s)'" +
                    std::string(map.has_accel() ? ", 'Acceleration x/y/z (m/s^2)' (acceleration with g)" : ""));
  } else if (preset == "sensor-logger") {
    map.time = "time";
    map.time_unit = TimeUnit::kNanoseconds;
    map.gyro = {"x", "y", "z"};
    map.gyro_unit = AngularRateUnit::kRadiansPerSecond;
    Note(notes, "layout: Sensor Logger Gyroscope.csv (preset sensor-logger): 'time' in ns since 1970, 'x', 'y', 'z' "
                "in rad/s ('seconds_elapsed' is not read)");
  } else {
    throw InvalidArgument("unknown column map preset '" + preset + "' (presets: phyphox, sensor-logger)");
  }
  return map;
}

ColumnMap DetectColumnMap(const CsvTable& table, std::vector<std::string>* notes) {
  ColumnMap map;
  std::string matched;
  const std::string file_name = FileName(table);
  // Sensor Logger: x, y, z could be any of its sensors; the file name says which.
  if (IsSensorLoggerHeader(table)) {
    if (!StartsWithNoCase(file_name, "Gyroscope")) {
      ThrowBadInput({{table.name(), table.header_line()}, "",
                     "Sensor Logger's columns time, seconds_elapsed, x, y, z in a file not named Gyroscope*.csv",
                     "the gyroscope's file (Gyroscope.csv of the export)",
                     "Pick Gyroscope.csv, or if this file holds the gyroscope under another name, say so with "
                     "--columns sensor-logger (or columns = \"sensor-logger\" in the manifest)."});
    }
    ColumnMap preset = PresetColumnMap("sensor-logger", table, notes);
    Note(notes, "why: the header is time, seconds_elapsed, z, y, x and the file is named " + file_name);
    return preset;
  }
  // Gyroscope.
  if (FindAxes(table, {{"Gyroscope X", "Gyroscope Y", "Gyroscope Z"}, {"gyro_x", "gyro_y", "gyro_z"},
                       {"gyro x", "gyro y", "gyro z"}, {"gyr_x", "gyr_y", "gyr_z"}, {"gyrX", "gyrY", "gyrZ"},
                       {"gx", "gy", "gz"}, {"wx", "wy", "wz"}},
               map.gyro, &matched)) {
    Note(notes, "gyroscope: columns '" + matched + "' … with the unit in each header");
  } else if (FindTriple(table, {"gyro_x_dps", "gyro_y_dps", "gyro_z_dps"}, map.gyro, false)) {
    map.gyro_unit = AngularRateUnit::kDegreesPerSecond;
    Note(notes, "gyroscope: columns gyro_x_dps … (deg/s, from the names)");
  } else if (FindTriple(table, {"gyro_x_rad_s", "gyro_y_rad_s", "gyro_z_rad_s"}, map.gyro, false)) {
    map.gyro_unit = AngularRateUnit::kRadiansPerSecond;
    Note(notes, "gyroscope: columns gyro_x_rad_s … (rad/s, from the names)");
  } else {
    ThrowBadInput({{table.name(), table.header_line()}, "", "no gyroscope columns that rockfit recognises",
                   "columns 'Gyroscope X (deg/s)', 'Gyroscope Y (deg/s)', 'Gyroscope Z (deg/s)' (or gx [dps], "
                   "gyro_x (rad/s), gyro_x_dps, gyro_x_rad_s, …)",
                   "Say which columns hold what with a column map, e.g. --columns \"time=t@s;gyro=wx,wy,wz@rad/s\" "
                   "or a preset (--columns phyphox, --columns sensor-logger; see rockfit inspect --help), or pick "
                   "the right file."});
  }
  // Time: a unit in the header, or in the name.
  for (const char* name : {"Time", "Timestamp", "t"}) {
    if (const auto column = FindByName(table, name)) {
      if (ParseTimeUnit(SplitHeaderUnit(table.header()[*column]).unit)) {
        map.time = table.header()[*column];
        Note(notes, "time: column '" + map.time + "' with the unit in its header");
        break;
      }
    }
  }
  if (map.time.empty()) {
    for (const auto& [name, unit] :
         {std::pair{"time_s", TimeUnit::kSeconds}, std::pair{"t_s", TimeUnit::kSeconds},
          std::pair{"time_ms", TimeUnit::kMilliseconds}, std::pair{"timestamp_ms", TimeUnit::kMilliseconds},
          std::pair{"millis", TimeUnit::kMilliseconds}, std::pair{"time_us", TimeUnit::kMicroseconds},
          std::pair{"timestamp_us", TimeUnit::kMicroseconds}, std::pair{"micros", TimeUnit::kMicroseconds},
          std::pair{"time_ns", TimeUnit::kNanoseconds}, std::pair{"timestamp_ns", TimeUnit::kNanoseconds}}) {
      if (const auto column = FindExact(table, name)) {
        map.time = table.header()[*column];
        map.time_unit = unit;
        Note(notes, "time: column '" + map.time + "' (" + UnitName(unit) + ", from the name)");
        break;
      }
    }
  }
  // Attitude and accelerometer, when all three columns are there.
  if (FindAxes(table, {{"Roll", "Pitch", "Yaw"}}, map.euler, &matched)) {
    Note(notes, "attitude: columns Roll, Pitch, Yaw (ZYX Euler angles) with the unit in each header");
  } else if (FindTriple(table, {"roll_deg", "pitch_deg", "yaw_deg"}, map.euler, false)) {
    map.euler_unit = AngleUnit::kDegrees;
    Note(notes, "attitude: columns roll_deg, pitch_deg, yaw_deg");
  } else if (FindTriple(table, {"roll_rad", "pitch_rad", "yaw_rad"}, map.euler, false)) {
    map.euler_unit = AngleUnit::kRadians;
    Note(notes, "attitude: columns roll_rad, pitch_rad, yaw_rad");
  } else {
    map.euler = {};
  }
  if (FindAxes(table, {{"Accelerometer X", "Accelerometer Y", "Accelerometer Z"},
                       {"Acceleration x", "Acceleration y", "Acceleration z"}, {"accel_x", "accel_y", "accel_z"},
                       {"acc_x", "acc_y", "acc_z"}, {"accX", "accY", "accZ"}, {"ax", "ay", "az"}},
               map.accel, &matched)) {
    Note(notes, "accelerometer: columns '" + matched + "' … with the unit in each header");
  } else if (FindTriple(table, {"accel_x_g", "accel_y_g", "accel_z_g"}, map.accel, false)) {
    map.accel_unit = AccelerationUnit::kG;
    Note(notes, "accelerometer: columns accel_x_g … (g, from the names)");
  } else if (FindTriple(table, {"accel_x_m_s2", "accel_y_m_s2", "accel_z_m_s2"}, map.accel, false)) {
    map.accel_unit = AccelerationUnit::kMetresPerSecond2;
    Note(notes, "accelerometer: columns accel_x_m_s2 … (m/s², from the names)");
  } else {
    map.accel = {};
  }
  if (StartsWithNoCase(FileName(table), "Gyroscope") && !map.has_accel() && FindExact(table, "Absolute (rad/s)")) {
    Note(notes, "layout: the columns of a phyphox gyroscope export (read as with --columns phyphox)");
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
  std::vector<std::string> notes;
  ColumnMap map;
  if (!options.columns) {
    map = DetectColumnMap(table, &notes);
  } else if (options.columns->is_preset()) {
    map = PresetColumnMap(options.columns->preset, table, &notes);
    notes.push_back("why: the column map names the preset");
  } else {
    map = *options.columns;
    notes.push_back("layout: the column map " + map.ToString());
  }
  map.Validate();
  notes.insert(notes.begin(), fmt::format("table: header on line {}, fields separated by {}, decimal {}",
                                          table.header_line(), table.delimiter() == '\t' ? std::string("tab")
                                                                                         : fmt::format("'{}'", table.delimiter()),
                                          table.decimal_separator() == DecimalSeparator::kPoint ? "points" : "commas"));

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
  TimeUnit time_unit = TimeUnit::kSeconds;
  std::vector<double> file_t_s;  // the time column relative to its first row (before gaps are looked for)
  if (map.has_time()) {
    time_unit = ResolveUnit(table, time_column, map.time_unit, &ParseTimeUnit, "s, ms, us, ns");
    if (n < 2) {
      ThrowBadInput({{file.string(), table.Line(0)}, "", "a single sample",
                     "at least two samples to find the rate from their times", "Pick a longer recording."});
    }
    CsvTimeColumn time = ReadCsvTimeColumn(table, time_column, time_unit);
    for (std::string& note : time.notes) notes.push_back(std::move(note));
    if (time.wraps > 0) {
      recording.warnings.push_back(fmt::format("{}: the time counter wrapped {} time(s) at 2^{}; the times were unwrapped",
                                               file_name, time.wraps, time.wrap_modulus == (1u << 16) ? 16 : 32));
    }
    file_t_s = time.t_s;
    TimestampTimeBase base = TimeBaseFromTimestamps(file_t_s);
    // No IMU samples faster than 1 MHz: closer times are a wrong unit or a broken clock (and 1/step overflows).
    constexpr double kMinMedianStep_s = 1e-6;
    if (!(base.median_step_s >= kMinMedianStep_s)) {
      ThrowBadInput({table.HeaderPosition(time_column), table.DescribeColumn(time_column),
                     fmt::format("times {:.6g} s apart (median), too close for a sample rate", base.median_step_s),
                     "times at least a microsecond apart",
                     "Check the time column's unit in the column map (time=NAME@s, @ms, @us or @ns)."});
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
  // Sensor Logger writes its accelerometer to a file of its own beside Gyroscope.csv (sensor_logger_accelerometer.hpp).
  if (!map.has_accel() && map.has_time() && IsSensorLoggerHeader(table)) {
    const std::filesystem::path companion = file.parent_path() / kSensorLoggerTotalAcceleration;
    std::error_code error;
    if (std::filesystem::is_regular_file(companion, error)) {
      const CsvTable accel_table = CsvTable::ReadFile(companion, recording.warnings);
      SensorLoggerAccelerometer accel =
          ResampleSensorLoggerAccelerometer(accel_table, table, time_column, time_unit, file_t_s);
      samples.accel_S = std::move(accel.accel_S);
      for (std::string& column : accel.columns) recording.columns.push_back(std::move(column));
      for (std::string& note : accel.notes) notes.push_back(std::move(note));
    } else {
      notes.push_back(fmt::format("accelerometer: none (no {} beside the file; Sensor Logger's Accelerometer.csv holds "
                                  "the acceleration without gravity and is not read)",
                                  kSensorLoggerTotalAcceleration));
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

  for (std::size_t k = 0; k < 3; ++k) {
    notes.push_back(fmt::format("gyroscope {}: {} in {}", "xyz"[k], table.DescribeColumn(gyro[k]),
                                UnitName(ResolveUnit(table, gyro[k], map.gyro_unit, &ParseAngularRateUnit, "deg/s, rad/s"))));
  }
  if (!map.has_accel() && samples.accel_S.empty() &&
      std::none_of(notes.begin(), notes.end(), [](const std::string& note) { return note.rfind("accelerometer:", 0) == 0; })) {
    notes.push_back("accelerometer: none");
  }
  if (!use_euler) notes.push_back("attitude: none in the file (metrics integrate it from the gyro)");
  recording.recognised = std::move(notes);
  AssembleRecording(std::move(samples), options.mounting, recording);
  return recording;
}

}  // namespace rockfit::io
