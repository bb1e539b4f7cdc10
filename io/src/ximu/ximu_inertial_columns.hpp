// The inertial columns that the x-IMU GUI's CalInertialAndMag file and the x-IMU3's Inertial file share
// (docs/file-formats.md): gyroscope X–Z and accelerometer X–Z, each with its unit in the header.
// One reading of them for both readers.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "text/column_lookup.hpp"
#include "text/csv_table.hpp"
#include "recording/recording_assembly.hpp"

namespace rockfit::io {

// The six column specs in the order gyroscope X, Y, Z, accelerometer X, Y, Z (matched by the name
// before the unit, so that "(deg/s)" and "(rad/s)" both resolve and the unit is checked on reading).
std::vector<ColumnSpec> XimuInertialColumnSpecs();

// Fills samples.w_S [rad/s] and samples.accel_S [m/s²] (sensor axes, one entry per row of `table`) from
// the resolved columns c[first], …, c[first + 5] of XimuInertialColumnSpecs(), in the units their
// headers name. Throws BadInput for a header unit that is not an angular rate (gyroscope) or an
// acceleration (accelerometer), and for a cell that is not a number.
void ReadXimuInertialColumns(const CsvTable& table, const std::vector<std::optional<std::size_t>>& c, std::size_t first,
                             SensorSamples& samples);

}  // namespace rockfit::io
