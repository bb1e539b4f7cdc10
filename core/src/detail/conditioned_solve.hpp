// A 3×3 linear solve with a conditioning test, for the impact maps' systems (18) and (18)+(24). Internal.
//
// The inverse comes from the adjugate, so the 1-norm reciprocal condition 1/(‖A‖₁·‖A⁻¹‖₁) is exact rather than
// estimated, at a fraction of the cost of an LU factorisation with a condition estimate.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

namespace rockfit::core::detail {

// A⁻¹ when the exact 1-norm reciprocal condition of A is at least `min_rcond`; false otherwise (A_inv untouched).
// A NaN anywhere counts as singular. For several right-hand sides of one A: SolveConditioned3's test once, and each
// solution A_inv·b bit for bit SolveConditioned3's.
inline bool InvertConditioned3(const Eigen::Matrix3d& A, double min_rcond, Eigen::Matrix3d* A_inv) {
  const double det = A.determinant();
  if (!(det != 0.0) || !std::isfinite(det)) return false;
  const Eigen::Matrix3d inverse = A.inverse();
  const double norm_A = A.cwiseAbs().colwise().sum().maxCoeff();
  const double norm_A_inv = inverse.cwiseAbs().colwise().sum().maxCoeff();
  // Written as !(x >= min) so that a NaN norm counts as singular.
  if (!(1.0 / (norm_A * norm_A_inv) >= min_rcond)) return false;
  *A_inv = inverse;
  return true;
}

// x = A⁻¹ b when the exact 1-norm reciprocal condition of A is at least `min_rcond` and x is finite; false
// otherwise (x untouched). A NaN anywhere counts as singular.
inline bool SolveConditioned3(const Eigen::Matrix3d& A, const Eigen::Vector3d& b, double min_rcond, Eigen::Vector3d* x) {
  Eigen::Matrix3d A_inv;
  if (!InvertConditioned3(A, min_rcond, &A_inv)) return false;
  const Eigen::Vector3d solution = A_inv * b;
  if (!solution.allFinite()) return false;
  *x = solution;
  return true;
}

}  // namespace rockfit::core::detail
