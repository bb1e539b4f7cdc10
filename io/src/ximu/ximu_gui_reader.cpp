#include "ximu/ximu_gui_reader.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "text/column_lookup.hpp"
#include "text/csv_table.hpp"
#include "recording/recording_assembly.hpp"
#include "recording/time_base.hpp"
#include "rockfit/io/units.hpp"
#include "ximu/ximu_dropped_rows.hpp"
#include "ximu/ximu_inertial_columns.hpp"
#include "ximu/rotation_matrix_row.hpp"
#include "ximu/ximu_registers.hpp"
#include "ximu/ximu_rtc_rate.hpp"

namespace rockfit::io {
namespace {

const char* const kPacketRepeatTodo =
    "The x-IMU's packet counter is shared by all files of a recording and never repeats: the file was edited or "
    "two exports were joined. Restore the original export.";
const char* const kRateTodo =
    "Pass --rate HZ on the command line or `rate = HZ` for this trial in the manifest (the x-IMU rates are "
    "powers of two; the paper's recordings use 256 Hz).";

std::string FileName(const std::filesystem::path& path) { return path.filename().string(); }

// The packet numbers of a table (empty when it has no packet-number column).
std::vector<double> PacketNumbers(const CsvTable& table, const std::optional<std::size_t>& column) {
  if (!column) return {};
  return ReadIncreasingColumn(table, *column, true, kPacketRepeatTodo);
}

// Attitude rows of one file, before pairing.
struct AttitudeRows {
  std::string file;              // file name
  std::vector<double> packets;   // empty without a packet-number column
  std::vector<Eigen::Quaterniond> q_WS;
};

// Converts the file's quaternion (Earth relative to sensor, reference §1.6) to q_WS.
Eigen::Quaterniond QuaternionRow(const CsvTable& table, std::size_t row, const std::vector<std::optional<std::size_t>>& c) {
  const Eigen::Quaterniond q_file(table.Real(row, *c[1]), table.Real(row, *c[2]), table.Real(row, *c[3]),
                                  table.Real(row, *c[4]));
  const double norm = q_file.norm();
  if (!(std::abs(norm - 1.0) <= kQuaternionNormTolerance)) {
    table.ThrowBadCell(row, *c[1], fmt::format("a quaternion of norm {:.6g}", norm),
                       fmt::format("a unit quaternion (norm 1 within {:g})", kQuaternionNormTolerance),
                       "The row is damaged; correct or delete line " + std::to_string(table.Line(row)) + ".");
  }
  return q_file.conjugate().normalized();  // q_WS = conj(q_file)
}

std::vector<ColumnSpec> QuaternionSpecs() {
  return {{{"Packet number"}, "the shared packet counter", false},
          {{"Element 1"}, "quaternion element 1 (scalar)"},
          {{"Element 2"}, "quaternion element 2"},
          {{"Element 3"}, "quaternion element 3"},
          {{"Element 4"}, "quaternion element 4"}};
}

AttitudeRows ReadQuaternionFile(const std::filesystem::path& path, Recording& recording) {
  const CsvTable table = CsvTable::ReadFile(path, recording.warnings);
  const auto c = ResolveColumns(table, QuaternionSpecs());
  AttitudeRows rows{FileName(path), PacketNumbers(table, c[0]), {}};
  rows.q_WS.reserve(table.row_count());
  for (std::size_t row = 0; row < table.row_count(); ++row) rows.q_WS.push_back(QuaternionRow(table, row, c));
  for (std::size_t k = 1; k < 5; ++k) recording.columns.push_back(rows.file + ": " + table.header()[*c[k]]);
  return rows;
}

AttitudeRows ReadRotationMatrixFile(const std::filesystem::path& path, Recording& recording) {
  const CsvTable table = CsvTable::ReadFile(path, recording.warnings);
  std::vector<ColumnSpec> specs = {{{"Packet number"}, "the shared packet counter", false}};
  for (int i = 1; i <= 3; ++i) {
    for (int j = 1; j <= 3; ++j) specs.push_back({{fmt::format("Element {}{}", i, j)}, "rotation matrix element"});
  }
  const auto c = ResolveColumns(table, specs);
  AttitudeRows rows{FileName(path), PacketNumbers(table, c[0]), {}};
  rows.q_WS.reserve(table.row_count());
  for (std::size_t row = 0; row < table.row_count(); ++row) rows.q_WS.push_back(RotationMatrixRow(table, row, c, 1));
  for (std::size_t k = 1; k < c.size(); ++k) recording.columns.push_back(rows.file + ": " + table.header()[*c[k]]);
  return rows;
}

// A quaternion file read only to repair NaN pitch rows: packet number → q_WS.
struct QuaternionLookup {
  std::vector<double> packets;
  std::vector<Eigen::Quaterniond> q_WS;
};

AttitudeRows ReadEulerFile(const std::filesystem::path& path, const std::optional<std::filesystem::path>& quaternion_path,
                           Recording& recording) {
  const CsvTable table = CsvTable::ReadFile(path, recording.warnings);
  const auto c = ResolveColumns(table, {{{"Packet number"}, "the shared packet counter", false},
                                        {{"Roll | Phi | X"}, "roll φx in degrees", true, true, "Roll | Phi | X (degrees)"},
                                        {{"Pitch | Theta | Y"}, "pitch φy in degrees", true, true, "Pitch | Theta | Y (degrees)"},
                                        {{"Yaw | Psi | Z"}, "yaw φz in degrees", true, true, "Yaw | Psi | Z (degrees)"}});
  std::array<double, 3> scale{};
  for (std::size_t k = 0; k < 3; ++k) {
    scale[k] = ToSi(HeaderUnit(table, *c[k + 1], &ParseAngleUnit, "degrees, deg, rad"));
  }
  AttitudeRows rows{FileName(path), PacketNumbers(table, c[0]), {}};
  rows.q_WS.reserve(table.row_count());
  std::optional<QuaternionLookup> lookup;
  std::size_t repaired = 0;
  std::size_t first_repaired_line = 0;
  for (std::size_t row = 0; row < table.row_count(); ++row) {
    const double roll = table.Real(row, *c[1]) * scale[0];
    const double pitch = table.RealOrNaN(row, *c[2]) * scale[1];
    const double yaw = table.Real(row, *c[3]) * scale[2];
    if (!std::isnan(pitch)) {
      rows.q_WS.push_back(QuaternionFromEulerZyx({yaw, pitch, roll}));
      continue;
    }
    // The GUI writes NaN when rounding puts |2(q1q3 + q0q2)| above 1, i.e. at pitch ±90°.
    const std::string line = std::to_string(table.Line(row));
    if (!quaternion_path) {
      table.ThrowBadCell(
          row, *c[2], "'NaN'", "a finite pitch",
          "The x-IMU GUI writes NaN when the pitch is ±90°. Put the recording's _Quaternion.csv beside this "
          "file so that rockfit can recompute the angles of this sample, read the attitude from it with "
          "--orientation quaternion, or read the gyro data alone with --orientation none.");
    }
    if (rows.packets.empty()) {
      table.ThrowBadCell(row, *c[2], "'NaN'", "a finite pitch",
                         "The file has no packet numbers, so the quaternion of this sample cannot be found; read the "
                         "attitude with --orientation quaternion instead.");
    }
    if (!lookup) {
      std::vector<std::string> ignored;
      const CsvTable quaternions = CsvTable::ReadFile(*quaternion_path, ignored);
      const auto qc = ResolveColumns(quaternions, QuaternionSpecs());
      if (!qc[0]) {
        table.ThrowBadCell(row, *c[2], "'NaN'", "a finite pitch",
                           FileName(*quaternion_path) +
                               " has no packet numbers to find this sample in; read the attitude "
                               "with --orientation quaternion instead.");
      }
      lookup = QuaternionLookup{PacketNumbers(quaternions, qc[0]), {}};
      for (std::size_t q = 0; q < quaternions.row_count(); ++q) lookup->q_WS.push_back(QuaternionRow(quaternions, q, qc));
    }
    const auto hit = std::lower_bound(lookup->packets.begin(), lookup->packets.end(), rows.packets[row]);
    if (hit == lookup->packets.end() || *hit != rows.packets[row]) {
      table.ThrowBadCell(row, *c[2], "'NaN'", "a finite pitch",
                         fmt::format("{} has no row with packet number {:.0f} to recompute it from; read the attitude "
                                     "with --orientation quaternion, or cut the recording before line {}.",
                                     FileName(*quaternion_path), rows.packets[row], line));
    }
    rows.q_WS.push_back(lookup->q_WS[static_cast<std::size_t>(hit - lookup->packets.begin())]);
    if (repaired++ == 0) first_repaired_line = table.Line(row);
  }
  if (repaired > 0) {
    recording.warnings.push_back(fmt::format(
        "{}: pitch is NaN (the GUI's value at ±90°) on {} line(s), first line {}; those samples were recomputed from "
        "the quaternion of the same packet in {}",
        FormatPosition({table.name(), first_repaired_line}), repaired, first_repaired_line, FileName(*quaternion_path)));
  }
  for (std::size_t k = 1; k < 4; ++k) recording.columns.push_back(rows.file + ": " + table.header()[*c[k]]);
  return rows;
}

// Rounds rate × ratio to the nearest power-of-two multiple of `rate` when close (x-IMU rates are
// powers of two), else returns it unrounded.
double NearestPowerOfTwoRate(double rate, double ratio) {
  const double exponent = std::round(std::log2(ratio));
  const double rounded = rate * std::exp2(exponent);
  return std::abs(rate * ratio / rounded - 1.0) <= kRateMismatchTolerance ? rounded : rate * ratio;
}

[[noreturn]] void MissingFile(const XimuGuiFileSet& files, const std::string& wanted, const std::string& todo) {
  std::string found;
  for (const auto& path : files.all) found += (found.empty() ? "" : ", ") + FileName(path);
  ThrowBadInput({{files.prefix.string()}, "",
                 found.empty() ? "no files '" + files.prefix.filename().string() + "_*.csv'" : "only " + found,
                 wanted, todo});
}

// The calibrated inertial file must be there: raw counts alone cannot be converted.
void RequireCalibratedInertial(const XimuGuiFileSet& files) {
  if (!files.cal_inertial) {
    if (files.raw_inertial) {
      ThrowBadInput({{files.raw_inertial->string()}, "", "only raw sensor counts (lsb)",
                     "calibrated data in " + files.prefix.filename().string() + "_CalInertialAndMag.csv (deg/s, g)",
                     "rockfit does not know the device's calibration: set the x-IMU's SensorDataMode register (66) "
                     "to calibrated and record again."});
    }
    MissingFile(files, "'" + files.prefix.filename().string() + "_CalInertialAndMag.csv' (gyroscope and accelerometer)",
                "Check the prefix: it is the file name without '_CalInertialAndMag.csv'.");
  }

}

// The inertial sample rate: register 69, else the rate given (--rate or the manifest); cross-checked with the
// real-time clock of the _DateTime.csv file when there is one. Sets recording->rate_hz and rate_source.
void DetermineRate(const XimuGuiFileSet& files, const std::optional<XimuRegisterSettings>& registers,
                   const LoadOptions& options, const std::vector<double>& packets, const std::string& inertial_name,
                   Recording* recording) {
  std::vector<std::string>& warnings = recording->warnings;
  double rate_hz = 0.0;
  if (registers && registers->inertial) {
    const XimuRegisterRate& reg = *registers->inertial;
    if (reg.rate_hz == 0.0) {
      ThrowBadInput({reg.at, "InertialAndMagneticDataRate (register 69)", "0 (inertial output disabled)",
                     "the rate of the inertial rows in " + inertial_name,
                     "The registers do not belong to this recording; delete " + FileName(*files.registers) +
                         " and give the rate with --rate."});
    }
    rate_hz = reg.rate_hz;
    recording->rate_source = RateSource::kRegisters;
    if (options.rate_hz && std::abs(*options.rate_hz - rate_hz) > 1e-9 * rate_hz) {
      ThrowBadInput({reg.at, "InertialAndMagneticDataRate (register 69)",
                     fmt::format("{} ({:g} Hz)", reg.value, rate_hz),
                     fmt::format("the rate given {} ({:g} Hz)",
                                 options.rate_origin == RateSource::kManifest ? "in the manifest" : "with --rate",
                                 *options.rate_hz),
                     "The registers record what the device was set to: remove the given rate or correct it."});
    }
  } else if (options.rate_hz) {
    rate_hz = *options.rate_hz;
    recording->rate_source = options.rate_origin;
  }

  // Cross-check with the real-time clock.
  std::optional<RtcRateEstimate> rtc;
  if (files.date_time && !packets.empty()) {
    try {
      std::vector<std::string> ignored;
      rtc = EstimateRateFromDateTime(CsvTable::ReadFile(*files.date_time, ignored), packets);
    } catch (const BadInput& e) {
      warnings.push_back(std::string("the rate was not cross-checked with the real-time clock: ") + e.what());
    }
  }
  if (rate_hz == 0.0) {
    std::string hint;
    if (rtc) {
      hint = fmt::format(" ({} has {:g} inertial rows per real-time-clock second, which suggests --rate {:g}.)",
                         FileName(*files.date_time), rtc->rows_per_second, NearestPowerOfTwoRate(1.0, rtc->rows_per_second));
    }
    ThrowBadInput({{files.cal_inertial->string()}, "",
                   files.registers ? "no register 69 (InertialAndMagneticDataRate) in " + FileName(*files.registers)
                                   : "no " + files.prefix.filename().string() + "_Registers.csv beside it",
                   "the inertial sample rate, which x-IMU CSV files do not contain (packet numbers are not time)",
                   kRateTodo + hint});
  }
  if (rtc) {
    const double relative = rtc->rows_per_second / rate_hz - 1.0;
    if (std::abs(relative) > kRateMismatchTolerance) {
      ThrowBadInput({{files.date_time->string()}, "",
                     fmt::format("{:g} inertial rows per real-time-clock second (median of {} s)", rtc->rows_per_second,
                                 rtc->seconds),
                     fmt::format("{:g} rows per second, the rate from {}", rate_hz,
                                 recording->rate_source == RateSource::kRegisters  ? "the registers"
                                 : recording->rate_source == RateSource::kManifest ? "the manifest"
                                                                                  : "--rate"),
                     "The rate is wrong: correct it (the clock counts real seconds)."});
    }
    if (relative < -kLostPacketTolerance) {
      warnings.push_back(fmt::format(
          "{}: {:g} inertial rows per real-time-clock second at {:g} Hz: about {:.1f} % of the inertial packets were "
          "lost in transmission; the x-IMU does not number lost packets, so the time base k/f_s runs short by that much",
          FileName(*files.date_time), rtc->rows_per_second, rate_hz, -100.0 * relative));
    }
  }
  recording->rate_hz = rate_hz;

}

// Gyroscope samples at the rail of the full scale (register 8) are clipped: the block turned faster than the
// gyroscope can tell. One warning with the count and the first.
void WarnClippedGyro(const std::optional<XimuRegisterSettings>& registers, const SensorSamples& samples,
                     const CsvTable& inertial, const std::string& inertial_name, std::vector<std::string>& warnings) {
  if (!registers || !registers->gyroscope_full_scale_dps) return;
  const std::size_t n = samples.w_S.size();
  // Samples at the rail are clipped: the block turned faster than the gyroscope can tell.
  const double rail_rad_s = (*registers->gyroscope_full_scale_dps - kGyroscopeRailMargin_dps) * kRadPerDeg;
  std::size_t clipped = 0;
  std::size_t first = 0;
  for (std::size_t row = 0; row < n; ++row) {
    if (samples.w_S[row].cwiseAbs().maxCoeff() < rail_rad_s) continue;
    if (clipped++ == 0) first = row;
  }
  if (clipped > 0) {
    warnings.push_back(fmt::format(
        "{}: {} gyroscope sample(s) at the ±{:g} °/s full scale of the x-IMU (register 8), first on line {} "
        "(t = {:.4f} s): the angular velocity there is clipped",
        inertial_name, clipped, *registers->gyroscope_full_scale_dps, inertial.Line(first), samples.t_s[first]));
  }
}

// The attitude file that --orientation asks for (auto: Euler angles, then quaternion, then rotation matrix).
std::optional<AttitudeRows> ReadAttitude(const XimuGuiFileSet& files, OrientationChoice choice, Recording& recording) {
  std::optional<AttitudeRows> attitude;
  const std::string prefix_name = files.prefix.filename().string();
  switch (choice) {
    case OrientationChoice::kNone:
      break;
    case OrientationChoice::kAuto:
      if (files.euler_angles) attitude = ReadEulerFile(*files.euler_angles, files.quaternion, recording);
      else if (files.quaternion) attitude = ReadQuaternionFile(*files.quaternion, recording);
      else if (files.rotation_matrix) attitude = ReadRotationMatrixFile(*files.rotation_matrix, recording);
      break;
    case OrientationChoice::kEulerAngles:
      if (!files.euler_angles) MissingFile(files, "'" + prefix_name + "_EulerAngles.csv' (--orientation euler)", "Choose another --orientation.");
      attitude = ReadEulerFile(*files.euler_angles, files.quaternion, recording);
      break;
    case OrientationChoice::kQuaternion:
      if (!files.quaternion) MissingFile(files, "'" + prefix_name + "_Quaternion.csv' (--orientation quaternion)", "Choose another --orientation.");
      attitude = ReadQuaternionFile(*files.quaternion, recording);
      break;
    case OrientationChoice::kRotationMatrix:
      if (!files.rotation_matrix) MissingFile(files, "'" + prefix_name + "_RotationMatrix.csv' (--orientation matrix)", "Choose another --orientation.");
      attitude = ReadRotationMatrixFile(*files.rotation_matrix, recording);
      break;
  }

  return attitude;
}

// Pairs each attitude row with the last inertial row at or before its packet (the x-IMU numbers all packets of a
// recording from one counter) and sets the attitude rate from register 70 or from the ratio of rows.
void PairAttitude(const XimuGuiFileSet& files, const AttitudeRows& attitude, const std::vector<double>& packets,
                  const std::optional<XimuRegisterSettings>& registers, const std::string& inertial_name,
                  SensorSamples& samples, Recording* recording) {
  std::vector<std::string>& warnings = recording->warnings;
  const std::size_t n = samples.t_s.size();
  const double rate_hz = recording->rate_hz;
  recording->orientation_source = attitude.file;
  const std::size_t m = attitude.q_WS.size();
  std::size_t before_first = 0;
  std::size_t decimated = 0;
  std::size_t within_span = 0;  // attitude rows between the first and last inertial packet
  if (!packets.empty() && !attitude.packets.empty()) {
    std::size_t i = 0;
    std::size_t last_paired = n;  // none yet
    for (std::size_t j = 0; j < m; ++j) {
      const double packet = attitude.packets[j];
      while (i < n && packets[i] < packet) ++i;
      if (i < n && packets[i] == packet) {
        ThrowBadInput({{(files.prefix.parent_path() / attitude.file).string()}, "",
                       fmt::format("packet number {:.0f}, which is also an inertial packet in {}", packet, inertial_name),
                       "packet numbers that never repeat across the files of one recording", kPacketRepeatTodo});
      }
      if (i == 0) {
        ++before_first;
        continue;
      }
      if (i < n) ++within_span;
      const std::size_t k = i - 1;
      if (k == last_paired) {
        ++decimated;
        continue;
      }
      samples.orientation.t_s.push_back(samples.t_s[k]);
      samples.orientation.q_WS.push_back(attitude.q_WS[j]);
      last_paired = k;
    }
  } else if (m == n) {
    samples.orientation.t_s = samples.t_s;
    samples.orientation.q_WS = attitude.q_WS;
    within_span = n;
    warnings.push_back(attitude.file + ": no packet numbers to pair attitude rows with inertial rows; they were "
                       "paired row by row, as both files have " + std::to_string(n) + " rows");
  } else {
    ThrowBadInput({{(files.prefix.parent_path() / attitude.file).string()}, "",
                   fmt::format("{} attitude rows and {} inertial rows, and no packet numbers in {}", m, n,
                               packets.empty() ? inertial_name : attitude.file),
                   "a 'Packet number' column to pair the rows of the two files",
                   "Export the recording again with a GUI that writes packet numbers, or read the gyro data alone "
                   "with --orientation none."});
  }
  if (before_first > 0) {
    warnings.push_back(fmt::format("{}: {} attitude row(s) before the first inertial packet were not used",
                                   attitude.file, before_first));
  }

  // The attitude rate, from register 70 or from the ratio of rows, and its cross-check.
  const double observed = rate_hz * static_cast<double>(within_span) / static_cast<double>(n);
  if (registers && registers->orientation && registers->orientation->rate_hz > 0.0) {
    const XimuRegisterRate& reg = *registers->orientation;
    recording->orientation_rate_hz = reg.rate_hz;
    if (within_span > 1 && std::abs(observed / reg.rate_hz - 1.0) > kRateMismatchTolerance) {
      ThrowBadInput({reg.at, "QuaternionDataRate (register 70)", fmt::format("{} ({:g} Hz)", reg.value, reg.rate_hz),
                     fmt::format("the rate of the attitude rows in {}: {:g} per {:g} inertial rows at {:g} Hz, i.e. "
                                 "{:.4g} Hz", attitude.file, static_cast<double>(within_span), static_cast<double>(n),
                                 rate_hz, observed),
                     "The files do not belong together, or the inertial rate is wrong: check the prefix and the rate."});
    }
  } else {
    recording->orientation_rate_hz = NearestPowerOfTwoRate(rate_hz, observed / rate_hz);
  }
  if (decimated > 0 && recording->orientation_rate_hz > rate_hz) {
    warnings.push_back(fmt::format("{}: attitude at {:g} Hz is faster than the gyro ({:g} Hz); the first attitude "
                                   "row after each inertial row was used ({} rows left out)",
                                   attitude.file, recording->orientation_rate_hz, rate_hz, decimated));
  }
}

}  // namespace

Recording ReadXimuGuiRecording(const XimuGuiFileSet& files, const LoadOptions& options) {
  options.Validate();
  Recording recording;
  recording.format = FormatName(RecordingFormat::kXimuGui);
  recording.source = files.prefix.string();
  std::vector<std::string>& warnings = recording.warnings;
  RequireCalibratedInertial(files);

  // Inertial rows: packet numbers, gyroscope, accelerometer.
  const CsvTable inertial = CsvTable::ReadFile(*files.cal_inertial, warnings);
  const std::string inertial_name = FileName(*files.cal_inertial);
  std::vector<ColumnSpec> specs = {{{"Packet number"}, "the shared packet counter", false}};
  for (ColumnSpec& spec : XimuInertialColumnSpecs()) specs.push_back(std::move(spec));
  const auto c = ResolveColumns(inertial, specs);
  const std::vector<double> packets = PacketNumbers(inertial, c[0]);
  const std::size_t n = inertial.row_count();

  std::optional<XimuRegisterSettings> registers;
  if (files.registers) registers = ReadXimuRegisters(CsvTable::ReadFile(*files.registers, warnings));
  DetermineRate(files, registers, options, packets, inertial_name, &recording);

  const std::optional<AttitudeRows> attitude = ReadAttitude(files, options.orientation, recording);

  // Gyroscope and accelerometer in SI, sensor axes; rows that the attitude packets show missing are skipped
  // in the time base (ximu_dropped_rows.hpp).
  SensorSamples samples;
  const std::vector<MissingRows> missing =
      attitude ? FindMissingInertialRows(packets, attitude->packets) : std::vector<MissingRows>{};
  samples.t_s = TimesWithMissingRows(n, recording.rate_hz, missing);
  std::size_t missing_total = 0;
  for (const MissingRows& m : missing) {
    samples.gaps.push_back({m.after_index, samples.t_s[m.after_index],
                            samples.t_s[m.after_index + 1] - samples.t_s[m.after_index], m.missing});
    missing_total += m.missing;
  }
  if (missing_total > 0) {
    warnings.push_back(fmt::format(
        "{}: {} inertial row(s) missing in {} place(s), first after line {} (t = {:.4f} s): {} holds two or more "
        "attitude packets between those rows where it holds one elsewhere; the time base skips the missing rows",
        inertial_name, missing_total, missing.size(), inertial.Line(missing.front().after_index),
        samples.t_s[missing.front().after_index], attitude->file));
  }
  ReadXimuInertialColumns(inertial, c, 1, samples);
  for (std::size_t k = 1; k < c.size(); ++k) {
    if (c[k]) recording.columns.push_back(inertial_name + ": " + inertial.header()[*c[k]]);
  }
  WarnClippedGyro(registers, samples, inertial, inertial_name, warnings);

  if (attitude) PairAttitude(files, *attitude, packets, registers, inertial_name, samples, &recording);
  AssembleRecording(std::move(samples), options.mounting, recording);
  return recording;
}

}  // namespace rockfit::io
