// Writes DeviceSamples as the CSV set the original x-IMU GUI makes from a recording (docs/file-formats.md §1):
//
//   <prefix>_Registers.csv         every register once, sent at start-up (rates in registers 67–70)
//   <prefix>_DateTime.csv          the real-time clock: once at start-up, then at the date/time rate
//   <prefix>_CalBattAndTherm.csv   battery voltage and temperature at their rate
//   <prefix>_CalInertialAndMag.csv gyroscope, accelerometer, magnetometer at the inertial rate
//   <prefix>_Quaternion.csv        Earth relative to sensor, at the quaternion rate
//   <prefix>_RotationMatrix.csv    derived from each quaternion packet (optional)
//   <prefix>_EulerAngles.csv       derived from each quaternion packet
//
// Headers are verbatim (leading spaces included), numbers are C# single-precision text
// (dotnet_float_format.hpp), lines end in LF (as the copies of real files) or CRLF (as the GUI itself).
// The first column is the global packet counter shared by all files: start-up packets (DateTime, all
// registers, DateTime, battery), then per inertial tick the inertial packet, the quaternion packet when one is
// due, then any DateTime and battery packets due — so inertial numbers step by 2 with gaps of 3–4 where the
// housekeeping packets fall, exactly as on a real device. Packet numbers are not time: time is n / rate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rockfit/io/synth_measurement.hpp"

namespace rockfit::io {

struct XimuGuiWriterOptions {
  double quaternion_rate_hz = 256.0;  // ≤ the inertial rate and dividing it; register 70
  double date_time_rate_hz = 1.0;     // register 67; 0: only the start-up DateTime packet
  double battery_rate_hz = 4.0;       // register 68; 0: no battery packets
  bool rotation_matrix_file = true;   // the GUI always writes it; it is the largest file of the set
  bool crlf_line_endings = false;
  std::int64_t rtc_start_s = 0;       // real-time clock at start-up, seconds after 2000-01-01 00:00:00
  std::uint64_t seed = 1;             // battery voltage and temperature noise

  // Throws InvalidArgument naming the bad option (rates must be x-IMU rates, 2^(v−1) Hz).
  void Validate(double inertial_rate_hz) const;
};

// The packet-number layout of a recording, for tests and the truth file.
struct XimuPacketLayout {
  std::vector<std::int64_t> inertial;    // packet number of each inertial sample
  std::vector<std::int64_t> quaternion;  // packet number of each quaternion sample
  std::int64_t total_packets = 0;
};

// Writes the files of the set for `samples`. Each file is written to a temporary name beside it and flushed to
// disk, and the files are renamed only when all are complete (WriteFilesAtomically, atomic_file.hpp), so
// existing files are never left half-overwritten. Returns the paths written.
// Throws InvalidArgument for bad options, OutputError when a file cannot be written.
std::vector<std::string> WriteXimuGuiCsv(const std::string& prefix, const DeviceSamples& samples,
                                         const XimuGuiWriterOptions& options, XimuPacketLayout* layout = nullptr);

// Calendar date and time of `seconds` after 2000-01-01 00:00:00 (proleptic Gregorian, no leap seconds).
struct CalendarTime {
  int year, month, day, hours, minutes, seconds;
};
CalendarTime CalendarTimeSince2000(std::int64_t seconds);

}  // namespace rockfit::io
