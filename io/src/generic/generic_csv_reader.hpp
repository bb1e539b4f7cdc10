// Reader of one generic CSV file with a header and a column map (docs/design.md §5). Without a map the
// columns are recognised from x-io style headers with units in parentheses ("Time (s)",
// "Gyroscope X (deg/s)", "Roll (deg)", "Accelerometer X (g)") or rockfit-style names with the unit
// in the name ("time_s", "gyro_x_dps", "gyro_x_rad_s", "roll_deg", "accel_x_g", "accel_x_m_s2").
// Time from the time column (rate = 1 / median step, gaps as for the x-IMU3) or t_k = k / rate.
// Euler columns are ZYX angles of R_WS (roll φx, pitch φy, yaw φz), as written by x-io devices.
#pragma once

#include <filesystem>

#include "rockfit/io/column_map.hpp"
#include "text/csv_table.hpp"
#include "rockfit/io/load_options.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

// The column map implied by the header (see above). Throws BadInput when no gyroscope columns are
// recognised, saying how to give a map.
ColumnMap DetectColumnMap(const CsvTable& table);

Recording ReadGenericCsvRecording(const std::filesystem::path& file, const LoadOptions& options);

}  // namespace rockfit::io
