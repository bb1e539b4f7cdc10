#include "recording/attitude.hpp"

#include <cmath>

#include <Eigen/SVD>

#include "rockfit/io/units.hpp"

namespace rockfit::io {

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
