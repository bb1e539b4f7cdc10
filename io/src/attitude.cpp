#include "rockfit/io/attitude.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "rockfit/io/units.hpp"

namespace rockfit::io {

Eigen::Vector3d EulerZyxFromRotation(const Eigen::Matrix3d& R) {
  const double sin_pitch = std::clamp(-R(2, 0), -1.0, 1.0);
  const double phi_y = std::asin(sin_pitch);
  // cos φy = √(R21² + R22²); below this the roll/yaw split is undefined (gimbal lock).
  constexpr double kGimbalLockCos = 1e-12;  // |cos φy|; beyond double-precision rounding of a unit matrix
  if (std::hypot(R(2, 1), R(2, 2)) < kGimbalLockCos) {
    // R = Rz(φz)·Ry(±π/2)·Rx(φx) depends on φz ∓ φx only: R01 = −sin(φz ∓ φx), R11 = cos(φz ∓ φx).
    return {std::atan2(-R(0, 1), R(1, 1)), phi_y, 0.0};
  }
  return {std::atan2(R(1, 0), R(0, 0)), phi_y, std::atan2(R(2, 1), R(2, 2))};
}

Eigen::Vector3d EulerZyxFromQuaternion(const Eigen::Quaterniond& q) {
  return EulerZyxFromRotation(q.normalized().toRotationMatrix());
}

Eigen::Matrix3d RotationFromEulerZyx(const Eigen::Vector3d& euler_zyx) {
  return QuaternionFromEulerZyx(euler_zyx).toRotationMatrix();
}

Eigen::Quaterniond QuaternionFromEulerZyx(const Eigen::Vector3d& euler_zyx) {
  return Eigen::AngleAxisd(euler_zyx[0], Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(euler_zyx[1], Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(euler_zyx[2], Eigen::Vector3d::UnitX());
}

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M, double* orthogonality_error, double* determinant) {
  if (orthogonality_error) *orthogonality_error = (M.transpose() * M - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (determinant) *determinant = M.determinant();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0.0) {
    Eigen::Matrix3d U = svd.matrixU();
    U.col(2) *= -1.0;
    R = U * svd.matrixV().transpose();
  }
  return R;
}

void UnwrapAngles(std::vector<Eigen::Vector3d>& angles) {
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k < angles.size(); ++k) {
    const Eigen::Vector3d raw_previous = angles[k - 1] - offset;  // the previous sample before unwrapping
    const Eigen::Vector3d step = angles[k] - raw_previous;
    for (int i = 0; i < 3; ++i) offset[i] -= 2.0 * kPi * std::round(step[i] / (2.0 * kPi));
    angles[k] += offset;
  }
}

}  // namespace rockfit::io
