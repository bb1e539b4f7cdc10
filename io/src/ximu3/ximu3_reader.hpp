// Reader of an x-IMU3 data-logger directory (docs/design.md §5; docs/file-formats.md §2): Inertial.csv
// and the AHRS outputs EulerAngles.csv, Quaternion.csv, RotationMatrix.csv and the quaternion columns
// of LinearAcceleration.csv / EarthAcceleration.csv (firmware of 2024). Decisions (io/README.md):
//  * Columns by trimmed, case-insensitive name; units from the header ("(deg/s)", "(g)", "(us)").
//  * Time from "Timestamp (us)" relative to the first inertial row (device time, not zero-based in
//    the file); the rate is 1 / the median step; longer steps are Gaps (dropped messages).
//    Repeated or decreasing timestamps: BadInput.
//  * Quaternions are q_WS (no conjugation, unlike the original x-IMU); RotationMatrix is R_WS row by row.
//  * The device sends one AHRS output type at a time; with --orientation auto every output file
//    present is used and merged by timestamp (at equal timestamps: Euler, quaternion, matrix,
//    linear, earth), then resampled onto the inertial timestamps.
#pragma once

#include <filesystem>

#include "rockfit/io/load_options.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

Recording ReadXimu3Recording(const std::filesystem::path& directory, const LoadOptions& options);

}  // namespace rockfit::io
