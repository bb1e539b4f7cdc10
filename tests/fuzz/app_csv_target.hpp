// Fuzz target body: the CSV files labs bring (phone apps, loggers, quoted spreadsheet exports) and the attitude
// integrated from their gyro. The first byte of the input picks how the file is read (its value modulo 4):
//   0  --columns phyphox                      (quoted header, time in s, rad/s)
//   1  detected, the file named Gyroscope.csv (phyphox or Sensor Logger recognition by header and name)
//   2  --columns sensor-logger                (time in ns since 1970, read exactly; x, y, z)
//   3  a microcontroller map: time=micros@us, gyro in dps, accel in g (counter wraps at 2^16/2^32)
// the rest is the file. With bit 0x40 of the first byte set, the rest is split at its first form feed ('\f') into
// Gyroscope.csv and, beside it, Sensor Logger's TotalAcceleration.csv, which the reader resamples onto the gyro's
// times (sensor_logger_accelerometer.hpp). A file that loads must keep the reader's promises, and the attitude
// integrated from it (gyro_attitude.hpp) must be finite with one sample per gyro sample, or end in a documented error.
#pragma once
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "recording_invariants.hpp"
#include "rockfit/io/column_map.hpp"
#include "rockfit/io/gyro_attitude.hpp"
#include "rockfit/io/load_recording.hpp"

namespace rockfit::fuzz {

inline void AppCsv(std::string_view input) {
  static const ScratchDir dir;
  if (input.empty()) return;
  const int layout = static_cast<unsigned char>(input.front()) % 4;
  const bool companion = (static_cast<unsigned char>(input.front()) & 0x40) != 0;
  input.remove_prefix(1);
  std::string_view accel;
  if (companion) {
    const std::size_t split = input.find('\f');
    if (split != std::string_view::npos) {
      accel = input.substr(split + 1);
      input = input.substr(0, split);
    }
  }
  dir.Clear();  // no TotalAcceleration.csv left from the previous input
  if (companion) dir.Write("TotalAcceleration.csv", accel);
  const auto file = dir.Write(layout == 1 || companion ? "Gyroscope.csv" : "recording.csv", input);
  ExpectDocumentedOutcome([&] {
    io::LoadOptions options;
    options.format = io::RecordingFormat::kGenericCsv;
    if (layout == 0) options.columns = io::ColumnMap::Parse("phyphox");
    if (layout == 2) options.columns = io::ColumnMap::Parse("sensor-logger");
    if (layout == 3) {
      options.columns = io::ColumnMap::Parse("time=micros@us;gyro=gx [dps],gy [dps],gz [dps];accel=ax [g],ay [g],az [g]");
    }
    const io::Recording recording = io::LoadRecording(file, options);
    CheckRecording(recording);
    const io::GyroAttitude attitude = io::IntegrateGyroAttitude(recording);
    if (attitude.euler_zyx.size() != recording.size()) Violated("integrated attitude and t_s differ in length");
    for (const auto& e : attitude.euler_zyx) {
      if (!e.allFinite()) Violated("non-finite integrated attitude");
    }
  });
}

}  // namespace rockfit::fuzz
