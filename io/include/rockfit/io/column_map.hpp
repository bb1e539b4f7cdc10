// Which columns of a generic CSV file hold what, and in which units (docs/design.md §5: "generic CSV with a
// header and a column map (time or rate, units given)").
//
// Text form, for --columns and manifests: entries "key=names@unit" separated by ';', e.g.
//   time=Time (s)@s;gyro=Gx,Gy,Gz@deg/s;euler=Roll,Pitch,Yaw@deg;accel=Ax,Ay,Az@g
// keys: time (one column; s, ms or us), gyro (x,y,z; deg/s or rad/s), euler (roll φx, pitch φy,
// yaw φz — ZYX angles of R_WS, as the x-IMU writes them; deg or rad), accel (x,y,z; g or m/s^2).
// gyro is required; without time the rate must be given. "@unit" may be left out when the header
// cell ends with the unit in parentheses or brackets, "Gyroscope X (deg/s)", "gx [dps]".
// Time units: s, ms, us, ns; absolute (epoch) times and wrapping counters are recognised (csv_time_column.hpp).
//
// Instead of entries, the name of a preset: "phyphox" (phyphox's CSV export: "Time (s)", "Gyroscope x (rad/s)", …,
// and "Acceleration x (m/s^2)", … when present) or "sensor-logger" (Sensor Logger's Gyroscope.csv: "time" in
// nanoseconds since 1970, "x", "y", "z" in rad/s). The reader resolves a preset against the file's header.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rockfit/io/units.hpp"

namespace rockfit::io {

// The preset names, "phyphox" and "sensor-logger".
const std::vector<std::string>& ColumnMapPresets();

struct ColumnMap {
  std::string preset;  // non-empty: a named preset, resolved by the reader (the fields below are then unused)
  std::string time;  // empty: no time column, t = k / rate
  std::optional<TimeUnit> time_unit;
  std::array<std::string, 3> gyro;  // x, y, z in sensor axes
  std::optional<AngularRateUnit> gyro_unit;
  std::array<std::string, 3> euler;  // roll φx, pitch φy, yaw φz; all empty: no attitude
  std::optional<AngleUnit> euler_unit;
  std::array<std::string, 3> accel;  // x, y, z in sensor axes; all empty: no accelerometer
  std::optional<AccelerationUnit> accel_unit;

  bool is_preset() const { return !preset.empty(); }
  bool has_time() const { return !time.empty(); }
  bool has_euler() const { return !euler[0].empty(); }
  bool has_accel() const { return !accel[0].empty(); }

  // Throws InvalidArgument quoting the spec and showing the syntax.
  static ColumnMap Parse(std::string_view spec);
  // Throws InvalidArgument: gyro names missing, euler/accel given partly, a column named twice.
  void Validate() const;
  // The text form (round-trips through Parse).
  std::string ToString() const;
};

}  // namespace rockfit::io
