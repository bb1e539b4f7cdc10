// Attitude conventions (docs/design.md §2): R_WB = Rz(φz)·Ry(φy)·Rx(φx), Euler angles stored as (φz, φy, φx)
// — the x-IMU's yaw ψ, pitch θ, roll φ. Quaternions are Hamilton, scalar first, q_WB maps body
// vectors to world vectors.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/attitude.hpp"

namespace rockfit::io {

// The Euler ZYX and quaternion conversions are core's (rockfit/core/attitude.hpp), one implementation for
// the simulator and the readers; they are named here so that io code and its users can keep writing
// io::EulerZyxFromRotation and so on. EulerZyxFromRotation returns φy = −asin(R20) ∈ [−π/2, π/2],
// φx = atan2(R21, R22), φz = atan2(R10, R00), both in (−π, π]; at φy = ±π/2 φx is 0.
// QuaternionFromEulerZyx returns the unit quaternion with a non-negative scalar part.
using core::EulerZyxFromQuaternion;
using core::EulerZyxFromRotation;
using core::QuaternionFromEulerZyx;
using core::RotationFromEulerZyx;

// The rotation nearest to a 3×3 matrix that should be one (printed with few digits, e.g. the
// x-IMU3's 1.000486 diagonal): polar decomposition by SVD. `orthogonality_error` receives
// ‖MᵀM − I‖_max so that callers can refuse a matrix that is not a rotation at all, and
// `determinant` the sign that tells a rotation (+1) from a reflection (−1).
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M, double* orthogonality_error, double* determinant);

// Makes each component of a sequence of angles continuous: adds the multiple of 2π that brings each
// sample within π of the previous one (angles wrap at ±π in the files).
void UnwrapAngles(std::vector<Eigen::Vector3d>& angles);

}  // namespace rockfit::io
