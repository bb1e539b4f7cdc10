#include "ximu3/ximu3_reader.hpp"

#include <algorithm>
#include <cmath>
#include <system_error>
#include <tuple>

#include <fmt/format.h>

#include "recording/attitude.hpp"
#include "text/column_lookup.hpp"
#include "text/csv_table.hpp"
#include "text/header_matching.hpp"
#include "recording/recording_assembly.hpp"
#include "recording/time_base.hpp"
#include "rockfit/io/units.hpp"
#include "ximu/ximu_inertial_columns.hpp"
#include "ximu/rotation_matrix_row.hpp"
#include "ximu/ximu_gui_reader.hpp"

namespace rockfit::io {
namespace {

const char* const kTimestampRepeatTodo =
    "Each x-IMU3 message has its own device time: a repeated timestamp means the file was edited or two logs were "
    "joined. Delete the repeated line or restore the original log.";

// A file of the directory by name, compared case-insensitively.
std::optional<std::filesystem::path> FindFile(const std::filesystem::path& directory, const std::string& name) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    if (HeaderEquals(entry.path().filename().string(), name) && entry.is_regular_file(ec)) return entry.path();
  }
  return std::nullopt;
}

ColumnSpec TimestampSpec() { return {{"Timestamp"}, "device time in microseconds", true, true, "Timestamp (us)"}; }

// Timestamps of a table in µs (whole numbers, strictly increasing).
std::vector<double> Timestamps(const CsvTable& table, std::size_t column) {
  const TimeUnit unit = HeaderUnit(table, column, &ParseTimeUnit, "us, ms, s");
  std::vector<double> values = ReadIncreasingColumn(table, column, unit == TimeUnit::kMicroseconds, kTimestampRepeatTodo);
  for (double& value : values) value *= ToSi(unit) / ToSi(TimeUnit::kMicroseconds);
  return values;
}

struct TimedAttitude {
  std::int64_t timestamp_us = 0;
  int priority = 0;
  Eigen::Quaterniond q_WS;
};

enum class AhrsKind { kEuler, kQuaternion, kMatrix, kQuaternionColumns };

struct AhrsFile {
  std::string name;
  AhrsKind kind;
};

// Reads one AHRS output file into `out`; false when it lacks the columns of its kind and
// `optional_columns` is set (LinearAcceleration/EarthAcceleration without quaternion columns).
bool ReadAhrsFile(const std::filesystem::path& path, AhrsKind kind, int priority, bool optional_columns,
                  Recording& recording, std::vector<TimedAttitude>& out) {
  const CsvTable table = CsvTable::ReadFile(path, recording.warnings);
  const std::string file = path.filename().string();
  std::vector<ColumnSpec> specs = {TimestampSpec()};
  switch (kind) {
    case AhrsKind::kEuler:
      specs.push_back({{"Roll"}, "roll φx", true, true, "Roll (deg)"});
      specs.push_back({{"Pitch"}, "pitch φy", true, true, "Pitch (deg)"});
      specs.push_back({{"Yaw"}, "yaw φz", true, true, "Yaw (deg)"});
      break;
    case AhrsKind::kQuaternion:
      for (const char* axis : {"W", "X", "Y", "Z"}) {
        specs.push_back({{axis, std::string(axis) + " Element", std::string("Quaternion ") + axis}, "quaternion element"});
      }
      break;
    case AhrsKind::kQuaternionColumns:
      for (const char* axis : {"W", "X", "Y", "Z"}) {
        specs.push_back({{std::string("Quaternion ") + axis}, "quaternion element", !optional_columns});
      }
      break;
    case AhrsKind::kMatrix:
      for (const char* element : {"XX", "XY", "XZ", "YX", "YY", "YZ", "ZX", "ZY", "ZZ"}) {
        specs.push_back({{element}, "rotation matrix element"});
      }
      break;
  }
  const auto c = ResolveColumns(table, specs);
  for (std::size_t k = 1; k < c.size(); ++k) {
    if (!c[k]) return false;
  }
  const std::vector<double> timestamps = Timestamps(table, *c[0]);
  std::array<double, 3> angle_scale{1.0, 1.0, 1.0};
  if (kind == AhrsKind::kEuler) {
    for (std::size_t k = 0; k < 3; ++k) angle_scale[k] = ToSi(HeaderUnit(table, *c[k + 1], &ParseAngleUnit, "deg, rad"));
  }
  for (std::size_t row = 0; row < table.row_count(); ++row) {
    Eigen::Quaterniond q_WS;
    if (kind == AhrsKind::kEuler) {
      const double roll = table.Real(row, *c[1]) * angle_scale[0];
      const double pitch = table.Real(row, *c[2]) * angle_scale[1];
      const double yaw = table.Real(row, *c[3]) * angle_scale[2];
      q_WS = QuaternionFromEulerZyx({yaw, pitch, roll});
    } else if (kind == AhrsKind::kMatrix) {
      q_WS = RotationMatrixRow(table, row, c, 1);
    } else {
      const Eigen::Quaterniond q(table.Real(row, *c[1]), table.Real(row, *c[2]), table.Real(row, *c[3]),
                                 table.Real(row, *c[4]));
      if (!(std::abs(q.norm() - 1.0) <= kQuaternionNormTolerance)) {
        table.ThrowBadCell(row, *c[1], fmt::format("a quaternion of norm {:.6g}", q.norm()),
                           fmt::format("a unit quaternion (norm 1 within {:g})", kQuaternionNormTolerance),
                           "The row is damaged; correct or delete line " + std::to_string(table.Line(row)) + ".");
      }
      q_WS = q.normalized();  // sensor → Earth already (no conjugation on the x-IMU3)
    }
    out.push_back({static_cast<std::int64_t>(std::llround(timestamps[row])), priority, q_WS});
  }
  for (std::size_t k = 1; k < c.size(); ++k) recording.columns.push_back(file + ": " + table.header()[*c[k]]);
  return true;
}

}  // namespace

Recording ReadXimu3Recording(const std::filesystem::path& directory, const LoadOptions& options) {
  options.Validate();
  Recording recording;
  recording.format = FormatName(RecordingFormat::kXimu3);
  recording.source = directory.string();

  const std::optional<std::filesystem::path> inertial_path = FindFile(directory, "Inertial.csv");
  if (!inertial_path) {
    ThrowBadInput({{directory.string()}, "", "no Inertial.csv", "an x-IMU3 data-logger directory with Inertial.csv",
                   "Give the directory that the x-IMU3 GUI or API logger wrote for one device."});
  }
  const CsvTable inertial = CsvTable::ReadFile(*inertial_path, recording.warnings);
  const std::string inertial_name = inertial_path->filename().string();
  std::vector<ColumnSpec> specs = {TimestampSpec()};
  for (ColumnSpec& spec : XimuInertialColumnSpecs()) specs.push_back(std::move(spec));
  const auto c = ResolveColumns(inertial, specs);
  const std::vector<double> timestamps_us = Timestamps(inertial, *c[0]);
  const std::size_t n = inertial.row_count();
  if (n < 2) {
    ThrowBadInput({{inertial_path->string(), inertial.Line(0)}, "", "a single sample",
                   "at least two samples to find the rate from their timestamps", "Pick a longer recording."});
  }
  std::vector<double> times_s(n);
  for (std::size_t k = 0; k < n; ++k) times_s[k] = (timestamps_us[k] - timestamps_us[0]) * ToSi(TimeUnit::kMicroseconds);
  TimestampTimeBase base = TimeBaseFromTimestamps(times_s);
  recording.rate_hz = base.rate_hz;
  recording.rate_source = RateSource::kTimestamps;
  if (options.rate_hz && std::abs(*options.rate_hz / base.rate_hz - 1.0) > kGivenRateTolerance) {
    ThrowBadInput({{inertial_path->string(), inertial.header_line(), inertial.HeaderPosition(*c[0]).column},
                   inertial.DescribeColumn(*c[0]),
                   fmt::format("timestamps {:.0f} µs apart (median), i.e. {:.6g} Hz", base.median_step_s * 1e6, base.rate_hz),
                   fmt::format("the rate given {} ({:g} Hz)",
                               options.rate_origin == RateSource::kManifest ? "in the manifest" : "with --rate",
                               *options.rate_hz),
                   "x-IMU3 files carry their own time: leave the rate out, or correct it."});
  }

  SensorSamples samples;
  samples.t_s = std::move(base.t_s);
  samples.gaps = std::move(base.gaps);
  ReadXimuInertialColumns(inertial, c, 1, samples);
  for (std::size_t k = 0; k < c.size(); ++k) recording.columns.push_back(inertial_name + ": " + inertial.header()[*c[k]]);

  // AHRS outputs, in order of preference at equal timestamps.
  const std::vector<std::pair<std::string, AhrsKind>> kAhrsFiles = {{"EulerAngles.csv", AhrsKind::kEuler},
                                                                    {"Quaternion.csv", AhrsKind::kQuaternion},
                                                                    {"RotationMatrix.csv", AhrsKind::kMatrix},
                                                                    {"LinearAcceleration.csv", AhrsKind::kQuaternionColumns},
                                                                    {"EarthAcceleration.csv", AhrsKind::kQuaternionColumns}};
  std::vector<TimedAttitude> attitude;
  std::vector<std::string> used;
  const auto read = [&](std::size_t index, bool required) {
    const auto& [name, kind] = kAhrsFiles[index];
    const std::optional<std::filesystem::path> path = FindFile(directory, name);
    if (!path) {
      if (required) {
        ThrowBadInput({{directory.string()}, "", "no " + name, name + " for --orientation " + OrientationChoiceName(options.orientation),
                       "The x-IMU3 logs one AHRS output type at a time; choose the --orientation whose file exists, "
                       "or --orientation auto."});
      }
      return;
    }
    if (ReadAhrsFile(*path, kind, static_cast<int>(index), kind == AhrsKind::kQuaternionColumns, recording, attitude)) {
      used.push_back(path->filename().string());
    }
  };
  switch (options.orientation) {
    case OrientationChoice::kNone:
      break;
    case OrientationChoice::kAuto:
      for (std::size_t index = 0; index < kAhrsFiles.size(); ++index) read(index, false);
      break;
    case OrientationChoice::kEulerAngles:
      read(0, true);
      break;
    case OrientationChoice::kQuaternion:
      read(1, true);
      break;
    case OrientationChoice::kRotationMatrix:
      read(2, true);
      break;
  }
  if (!attitude.empty()) {
    std::sort(attitude.begin(), attitude.end(), [](const TimedAttitude& a, const TimedAttitude& b) {
      return std::tie(a.timestamp_us, a.priority) < std::tie(b.timestamp_us, b.priority);
    });
    std::vector<double> attitude_timestamps;
    for (std::size_t k = 0; k < attitude.size(); ++k) {
      if (k > 0 && attitude[k].timestamp_us == attitude[k - 1].timestamp_us) continue;
      samples.orientation.t_s.push_back((static_cast<double>(attitude[k].timestamp_us) - timestamps_us[0]) *
                                        ToSi(TimeUnit::kMicroseconds));
      samples.orientation.q_WS.push_back(attitude[k].q_WS);
    }
    for (const std::string& name : used) recording.orientation_source += (recording.orientation_source.empty() ? "" : " + ") + name;
    if (samples.orientation.t_s.size() >= 2) {
      recording.orientation_rate_hz = TimeBaseFromTimestamps(samples.orientation.t_s).rate_hz;
    }
  }

  AssembleRecording(std::move(samples), options.mounting, recording);
  return recording;
}

}  // namespace rockfit::io
