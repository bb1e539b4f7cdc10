// Reader of one generic CSV file with a header and a column map (docs/design.md §5). Without a map the
// columns are recognised from headers with units in parentheses or brackets ("Time (s)", "Gyroscope X (deg/s)",
// "gx [dps]", "Roll (deg)", "Accelerometer X (g)", phyphox's "Gyroscope x (rad/s)") or rockfit-style names with the
// unit in the name ("time_s", "millis", "time_ns", "gyro_x_dps", "gyro_x_rad_s", "roll_deg", "accel_x_g",
// "accel_x_m_s2"), or as Sensor Logger's Gyroscope.csv. Recording::recognised says what was taken and why.
// Time from the time column (rate = 1 / median step, gaps as for the x-IMU3) or t_k = k / rate.
// Euler columns are ZYX angles of R_WS (roll φx, pitch φy, yaw φz), as written by x-io devices.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rockfit/io/column_map.hpp"
#include "text/csv_table.hpp"
#include "rockfit/io/load_options.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

// The column map implied by the header (see above), also phyphox's and Sensor Logger's exports; `notes` (if given)
// receives what was recognised and why, for `rockfit inspect`. Throws BadInput when no gyroscope columns are
// recognised, saying how to give a map.
ColumnMap DetectColumnMap(const CsvTable& table, std::vector<std::string>* notes = nullptr);

// The map of a named preset (column_map.hpp) for this file's header; notes as above. Throws InvalidArgument for
// an unknown name.
ColumnMap PresetColumnMap(const std::string& preset, const CsvTable& table, std::vector<std::string>* notes = nullptr);

Recording ReadGenericCsvRecording(const std::filesystem::path& file, const LoadOptions& options);

}  // namespace rockfit::io
