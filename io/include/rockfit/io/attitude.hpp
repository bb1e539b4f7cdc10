// Attitude conventions (DESIGN §2): R_WB = Rz(φz)·Ry(φy)·Rx(φx), Euler angles stored as (φz, φy, φx)
// — the x-IMU's yaw ψ, pitch θ, roll φ. Quaternions are Hamilton, scalar first, q_WB maps body
// vectors to world vectors.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rockfit::io {

// (φz, φy, φx) of a rotation: φy = −asin(R20) ∈ [−π/2, π/2], φx = atan2(R21, R22),
// φz = atan2(R10, R00), both in (−π, π]. At φy = ±π/2 only φz ∓ φx is defined; φx is then 0.
Eigen::Vector3d EulerZyxFromRotation(const Eigen::Matrix3d& R);
Eigen::Vector3d EulerZyxFromQuaternion(const Eigen::Quaterniond& q);

// Rz(φz)·Ry(φy)·Rx(φx) for euler_zyx = (φz, φy, φx).
Eigen::Matrix3d RotationFromEulerZyx(const Eigen::Vector3d& euler_zyx);
Eigen::Quaterniond QuaternionFromEulerZyx(const Eigen::Vector3d& euler_zyx);

// The rotation nearest to a 3×3 matrix that should be one (printed with few digits, e.g. the
// x-IMU3's 1.000486 diagonal): polar decomposition by SVD. `orthogonality_error` receives
// ‖MᵀM − I‖_max so that callers can refuse a matrix that is not a rotation at all, and
// `determinant` the sign that tells a rotation (+1) from a reflection (−1).
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M, double* orthogonality_error, double* determinant);

// Makes each component of a sequence of angles continuous: adds the multiple of 2π that brings each
// sample within π of the previous one (angles wrap at ±π in the files).
void UnwrapAngles(std::vector<Eigen::Vector3d>& angles);

}  // namespace rockfit::io
