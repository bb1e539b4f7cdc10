#include "ximu/ximu_inertial_columns.hpp"

#include <array>

#include "rockfit/io/units.hpp"

namespace rockfit::io {

std::vector<ColumnSpec> XimuInertialColumnSpecs() {
  return {{{"Gyroscope X"}, "the gyroscope's x axis in deg/s", true, true, "Gyroscope X (deg/s)"},
          {{"Gyroscope Y"}, "the gyroscope's y axis in deg/s", true, true, "Gyroscope Y (deg/s)"},
          {{"Gyroscope Z"}, "the gyroscope's z axis in deg/s", true, true, "Gyroscope Z (deg/s)"},
          {{"Accelerometer X"}, "the accelerometer's x axis in g", true, true, "Accelerometer X (g)"},
          {{"Accelerometer Y"}, "the accelerometer's y axis in g", true, true, "Accelerometer Y (g)"},
          {{"Accelerometer Z"}, "the accelerometer's z axis in g", true, true, "Accelerometer Z (g)"}};
}

void ReadXimuInertialColumns(const CsvTable& table, const std::vector<std::optional<std::size_t>>& c, std::size_t first,
                             SensorSamples& samples) {
  const std::size_t n = table.row_count();
  samples.w_S.resize(n);
  samples.accel_S.resize(n);
  std::array<double, 3> gyro_scale{};
  std::array<double, 3> accel_scale{};
  for (std::size_t k = 0; k < 3; ++k) {
    gyro_scale[k] = ToSi(HeaderUnit(table, *c[first + k], &ParseAngularRateUnit, "deg/s, rad/s"));
    accel_scale[k] = ToSi(HeaderUnit(table, *c[first + 3 + k], &ParseAccelerationUnit, "g, m/s^2"));
  }
  for (std::size_t row = 0; row < n; ++row) {
    for (std::size_t k = 0; k < 3; ++k) {
      samples.w_S[row][static_cast<Eigen::Index>(k)] = table.RealInSi(row, *c[first + k], gyro_scale[k]);
      samples.accel_S[row][static_cast<Eigen::Index>(k)] = table.RealInSi(row, *c[first + 3 + k], accel_scale[k]);
    }
  }
}

}  // namespace rockfit::io
