#include "rockfit/fitting/profile_steps.hpp"

#include <algorithm>
#include <cmath>

namespace rockfit::fitting {
namespace {

// A refined point keeps this fraction of the bracket's width from either end: a point on an end adds nothing.
constexpr double kRefineMargin = 0.1;

}  // namespace

double NextProfileOffset(const ProfileStepPoint& before, const ProfileStepPoint& last, const ProfileAim& aim) {
  const double lowest = aim.min_growth * last.offset, highest = aim.max_growth * last.offset;
  const double d_offset = last.offset - before.offset, d_rho = last.rho - before.rho;
  if (!(d_offset > 0.0) || !(d_rho > 0.0) || !std::isfinite(d_rho)) return highest;
  const double secant = last.offset + (aim.target_rho - last.rho) * d_offset / d_rho;
  return std::clamp(secant, lowest, highest);
}

double RefineProfileOffset(const ProfileStepPoint& inner, const ProfileStepPoint& outer, double target_rho) {
  const double width = outer.offset - inner.offset;
  const double lowest = inner.offset + kRefineMargin * width, highest = outer.offset - kRefineMargin * width;
  const double d_rho = outer.rho - inner.rho;
  if (!(d_rho > 0.0) || !std::isfinite(d_rho)) return 0.5 * (inner.offset + outer.offset);
  return std::clamp(inner.offset + (target_rho - inner.rho) * width / d_rho, lowest, highest);
}

Eigen::VectorXd RidgeSlope(const Eigen::MatrixXd& inverse_normal_matrix, Eigen::Index j) {
  const Eigen::Index n = inverse_normal_matrix.rows();
  Eigen::VectorXd slope = Eigen::VectorXd::Zero(n);
  const double m_jj = inverse_normal_matrix(j, j);
  if (!(m_jj > 0.0) || !std::isfinite(m_jj)) return slope;
  slope = inverse_normal_matrix.col(j) / m_jj;
  slope[j] = 0.0;  // j itself is held at the profile point
  if (!slope.allFinite()) slope.setZero();
  return slope;
}

}  // namespace rockfit::fitting
