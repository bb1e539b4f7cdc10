#include "rockfit/core/attitude.hpp"

#include <algorithm>
#include <cmath>

namespace rockfit::core {

namespace {

// The entries of R_WB that the Euler angles read.
struct EulerEntries {
  double r00, r10, r20, r21, r22;
  double r01, r11;  // at the gimbal lock only
};

Eigen::Vector3d EulerZyxFromEntries(const EulerEntries& r) {
  // R = Rz Ry Rx has R(2,0) = −sin φy, R(2,1) = cos φy sin φx, R(2,2) = cos φy cos φx,
  // R(1,0) = sin φz cos φy, R(0,0) = cos φz cos φy.
  const double sin_y = std::clamp(-r.r20, -1.0, 1.0);
  const double phi_y = std::asin(sin_y);
  // cos φy below this the yaw and roll axes coincide to working precision.
  constexpr double kGimbalLockCos = 1e-12;
  if (std::sqrt(r.r21 * r.r21 + r.r22 * r.r22) < kGimbalLockCos) {
    // φy = ±π/2: only φz ∓ φx is defined; put it all into φz.
    const double phi_z = std::atan2(-r.r01, r.r11);
    return {phi_z, phi_y, 0.0};
  }
  const double phi_z = std::atan2(r.r10, r.r00);
  const double phi_x = std::atan2(r.r21, r.r22);
  return {phi_z, phi_y, phi_x};
}

}  // namespace

Eigen::Vector3d EulerZyxFromRotation(const Eigen::Matrix3d& R_WB) {
  return EulerZyxFromEntries({R_WB(0, 0), R_WB(1, 0), R_WB(2, 0), R_WB(2, 1), R_WB(2, 2), R_WB(0, 1), R_WB(1, 1)});
}

Eigen::Vector3d EulerZyxFromUnitQuaternion(const Eigen::Quaterniond& q_WB) {
  // Eigen's toRotationMatrix, term by term: t_ab = 2·a·b.
  const double tx = 2.0 * q_WB.x();
  const double ty = 2.0 * q_WB.y();
  const double tz = 2.0 * q_WB.z();
  const double twx = tx * q_WB.w();
  const double twy = ty * q_WB.w();
  const double twz = tz * q_WB.w();
  const double txx = tx * q_WB.x();
  const double txy = ty * q_WB.x();
  const double txz = tz * q_WB.x();
  const double tyy = ty * q_WB.y();
  const double tyz = tz * q_WB.y();
  const double tzz = tz * q_WB.z();
  return EulerZyxFromEntries({1.0 - (tyy + tzz), txy + twz, txz - twy, tyz + twx, 1.0 - (txx + tyy), txy - twz,
                              1.0 - (txx + tzz)});
}

Eigen::Vector3d EulerZyxFromQuaternion(const Eigen::Quaterniond& q_WB) {
  return EulerZyxFromUnitQuaternion(q_WB.normalized());
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
