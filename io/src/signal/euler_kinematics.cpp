#include "signal/euler_kinematics.hpp"

#include <cmath>


namespace rockfit::io {
namespace {
// |cos φy| below this is treated as gimbal lock (φy within 1e-9 rad of ±π/2).
constexpr double kGimbalLockCos = 1e-9;
}  // namespace

Eigen::Vector3d BodyRatesFromEulerZyx(const Eigen::Vector3d& euler_zyx, const Eigen::Vector3d& euler_rates_zyx) {
  const double phi_y = euler_zyx[1], phi_x = euler_zyx[2];
  const double rate_z = euler_rates_zyx[0], rate_y = euler_rates_zyx[1], rate_x = euler_rates_zyx[2];
  const double cy = std::cos(phi_y), sy = std::sin(phi_y), cx = std::cos(phi_x), sx = std::sin(phi_x);
  return {rate_x - sy * rate_z, cx * rate_y + sx * cy * rate_z, -sx * rate_y + cx * cy * rate_z};
}

Eigen::Vector3d EulerZyxRates(const Eigen::Vector3d& euler_zyx, const Eigen::Vector3d& w_B) {
  const double phi_y = euler_zyx[1], phi_x = euler_zyx[2];
  const double cy = std::cos(phi_y), sy = std::sin(phi_y), cx = std::cos(phi_x), sx = std::sin(phi_x);
  const double rate_y = cx * w_B.y() - sx * w_B.z();
  if (std::abs(cy) < kGimbalLockCos) return {0.0, rate_y, 0.0};
  const double yz = sx * w_B.y() + cx * w_B.z();
  return {yz / cy, rate_y, w_B.x() + sy / cy * yz};
}

}  // namespace rockfit::io
