// Which reader a path needs (docs/design.md §5 "format detection from a path"; io/README.md):
//  * a directory with Inertial.csv → x-IMU3 logger directory;
//  * a directory with one x-IMU GUI set (<base>_CalInertialAndMag.csv) → that set; several → BadInput
//    listing them;
//  * a directory whose only sub-directory with Inertial.csv is a device directory → that one (the
//    x-IMU3 logger writes one sub-directory per device);
//  * a file "<base>_<Type>.csv" of a known x-IMU GUI type, or a prefix "dir/base" with such files → x-IMU GUI set;
//  * a file of an x-IMU3 directory (beside Inertial.csv) → that directory;
//  * ".h5"/".hdf5" → rockfit's HDF5; ".bin"/".ximu3" → BadInput saying how to convert;
//  * any other file → generic CSV.
#pragma once

#include <filesystem>
#include <string>

#include "rockfit/io/load_options.hpp"

namespace rockfit::io {

struct DetectedSource {
  RecordingFormat format = RecordingFormat::kAuto;
  // What the reader takes: the x-IMU GUI prefix "dir/base", the x-IMU3 directory, or the file.
  std::filesystem::path path;
};

// `forced` other than kAuto skips detection but still resolves the path for that format. Throws
// BadInput when the path does not exist or holds no recording, with what to give instead.
DetectedSource DetectRecordingSource(const std::filesystem::path& path, RecordingFormat forced = RecordingFormat::kAuto);

}  // namespace rockfit::io
