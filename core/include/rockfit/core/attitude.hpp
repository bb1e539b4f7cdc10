// Attitude helpers: Euler angles ZYX (the x-IMU convention of docs/design.md §2), yaw rotations and quaternion
// conventions used in every output of rockfit.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rockfit::core {

// (φz, φy, φx) with R_WB = Rz(φz)·Ry(φy)·Rx(φx); φy ∈ [−π/2, π/2], φz, φx ∈ (−π, π].
// At the gimbal lock (|φy| = π/2) φx is set to 0 and the whole yaw–roll goes into φz.
Eigen::Vector3d EulerZyxFromRotation(const Eigen::Matrix3d& R_WB);
Eigen::Vector3d EulerZyxFromQuaternion(const Eigen::Quaterniond& q_WB);
// EulerZyxFromQuaternion of a quaternion already of unit norm (to round-off): no normalisation, and of R_WB only
// the entries the angles need, each as Eigen's toRotationMatrix forms it.
Eigen::Vector3d EulerZyxFromUnitQuaternion(const Eigen::Quaterniond& q_WB);
// Inverse of EulerZyxFromRotation: Rz(φz)·Ry(φy)·Rx(φx) as a unit quaternion.
Eigen::Quaterniond QuaternionFromEulerZyx(const Eigen::Vector3d& euler_zyx_rad);
// Rz(φz)·Ry(φy)·Rx(φx) for euler_zyx_rad = (φz, φy, φx).
Eigen::Matrix3d RotationFromEulerZyx(const Eigen::Vector3d& euler_zyx_rad);

// Rotation by `angle_rad` about the world vertical.
Eigen::Quaterniond YawQuaternion(double angle_rad);

// The unit quaternion of the same rotation with a non-negative scalar part (rockfit's output convention).
Eigen::Quaterniond CanonicalQuaternion(const Eigen::Quaterniond& q);
// CanonicalQuaternion of a quaternion already of unit norm (to round-off): the sign alone.
inline Eigen::Quaterniond CanonicalUnitQuaternion(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond out = q;
  if (out.w() < 0.0) out.coeffs() = -out.coeffs();
  return out;
}

}  // namespace rockfit::core
