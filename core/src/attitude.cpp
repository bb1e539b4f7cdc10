#include "rockfit/core/attitude.hpp"

#include <algorithm>
#include <cmath>

namespace rockfit::core {

Eigen::Vector3d EulerZyxFromRotation(const Eigen::Matrix3d& R_WB) {
  // R = Rz Ry Rx has R(2,0) = −sin φy, R(2,1) = cos φy sin φx, R(2,2) = cos φy cos φx,
  // R(1,0) = sin φz cos φy, R(0,0) = cos φz cos φy.
  const double sin_y = std::clamp(-R_WB(2, 0), -1.0, 1.0);
  const double phi_y = std::asin(sin_y);
  // cos φy below this the yaw and roll axes coincide to working precision.
  constexpr double kGimbalLockCos = 1e-12;
  if (std::sqrt(R_WB(2, 1) * R_WB(2, 1) + R_WB(2, 2) * R_WB(2, 2)) < kGimbalLockCos) {
    // φy = ±π/2: only φz ∓ φx is defined; put it all into φz.
    const double phi_z = std::atan2(-R_WB(0, 1), R_WB(1, 1));
    return {phi_z, phi_y, 0.0};
  }
  const double phi_z = std::atan2(R_WB(1, 0), R_WB(0, 0));
  const double phi_x = std::atan2(R_WB(2, 1), R_WB(2, 2));
  return {phi_z, phi_y, phi_x};
}

Eigen::Vector3d EulerZyxFromQuaternion(const Eigen::Quaterniond& q_WB) {
  return EulerZyxFromRotation(q_WB.normalized().toRotationMatrix());
}

Eigen::Quaterniond QuaternionFromEulerZyx(const Eigen::Vector3d& euler_zyx_rad) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(euler_zyx_rad[0], Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(euler_zyx_rad[1], Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(euler_zyx_rad[2], Eigen::Vector3d::UnitX());
  return CanonicalQuaternion(q);
}

Eigen::Matrix3d RotationFromEulerZyx(const Eigen::Vector3d& euler_zyx_rad) {
  return QuaternionFromEulerZyx(euler_zyx_rad).toRotationMatrix();
}

Eigen::Quaterniond YawQuaternion(double angle_rad) {
  return Eigen::Quaterniond(std::cos(0.5 * angle_rad), 0.0, 0.0, std::sin(0.5 * angle_rad));
}

Eigen::Quaterniond CanonicalQuaternion(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond unit = q.normalized();
  if (unit.w() < 0.0) unit.coeffs() = -unit.coeffs();
  return unit;
}

}  // namespace rockfit::core
