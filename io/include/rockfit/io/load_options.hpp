// What a caller may tell the readers beyond the path (docs/design.md §5, §8: a trial's format, rate and
// mounting come from the manifest or the command line).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "rockfit/io/column_map.hpp"
#include "rockfit/io/mounting.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

enum class RecordingFormat {
  kAuto,        // detect from the path
  kXimuGui,     // "ximu-gui": original x-IMU GUI CSV set <prefix>_<Type>.csv
  kXimu3,       // "ximu3": x-IMU3 data-logger directory
  kGenericCsv,  // "generic-csv": one CSV file with a column map
  kRockfitHdf5, // "rockfit-hdf5": rockfit's own HDF5 store
};
std::string FormatName(RecordingFormat format);  // "auto", "ximu-gui", "ximu3", "generic-csv", "rockfit-hdf5"
// Accepts the names above, and "csv" for generic-csv; std::nullopt otherwise.
std::optional<RecordingFormat> ParseFormatName(std::string_view name);

// Which attitude files to read.
enum class OrientationChoice {
  kAuto,            // x-IMU GUI: EulerAngles, else Quaternion, else RotationMatrix; x-IMU3: every AHRS
                    // output file present, merged by timestamp; generic CSV: the euler columns if mapped
  kEulerAngles,     // "euler"
  kQuaternion,      // "quaternion"
  kRotationMatrix,  // "matrix"
  kNone,            // "none": gyro (and accelerometer) only
};
std::string OrientationChoiceName(OrientationChoice choice);  // "auto", "euler", "quaternion", "matrix", "none"
std::optional<OrientationChoice> ParseOrientationChoice(std::string_view name);

struct LoadOptions {
  // Gyro sample rate [Hz] for files that do not state it (x-IMU GUI sets without _Registers.csv,
  // generic CSV without a time column). When the files do state it, the two must agree.
  std::optional<double> rate_hz;
  // How rate_hz was given: RateSource::kOption (--rate) or kManifest; reported as Recording::rate_source.
  RateSource rate_origin = RateSource::kOption;
  Mounting mounting;                 // sensor → block; identity by default
  // "--mounting auto": estimate the mounting from the recording (mounting_estimate.hpp), starting at `mounting`,
  // and read the recording again with the estimate. Without it the estimate only checks `mounting` (a warning
  // beyond kMountingWarningDeg).
  bool estimate_mounting = false;
  std::optional<ColumnMap> columns;  // generic CSV; detected from x-io style headers when absent
  OrientationChoice orientation = OrientationChoice::kAuto;
  RecordingFormat format = RecordingFormat::kAuto;

  // Throws InvalidArgument: rate not finite/positive or above kMaxRate_hz, a rate_origin other than option or
  // manifest, bad column map.
  void Validate() const;
};

// No IMU that rockfit reads samples faster (the x-IMU tops out at 512 Hz, the x-IMU3 at a few kHz).
inline constexpr double kMaxRate_hz = 1e5;

}  // namespace rockfit::io
