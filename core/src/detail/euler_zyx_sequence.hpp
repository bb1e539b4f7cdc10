// Euler angles (φz, φy, φx) of consecutive output samples without two arctangents a sample. Between samples a
// fraction of a second apart the yaw φz and the roll φx change by little: each is the previous sample's angle
// plus the angle between the two samples' direction vectors (cos, sin), whose tangent is a cross product over a
// dot product, and whose arctangent a short odd series gives exactly to round-off when that tangent is small.
// The angles are evaluated exactly (EulerZyxFromUnitQuaternion) at the first sample, every kExactEvery samples,
// after a gap in the samples, and wherever an increment is not small or an angle is near ±π or the gimbal lock,
// so that round-off cannot accumulate. Internal to the simulator's sampler.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/attitude.hpp"

namespace rockfit::core::detail {

class EulerZyxSequence {
 public:
  // At most this many increments follow an exact evaluation, so that their round-off (a few units in the last
  // place each) stays below ~1e-14 rad.
  static constexpr int kExactEvery = 16;
  // Increments whose tangent exceeds this are evaluated exactly: below it the arctangent's series through x¹³ is
  // exact to round-off (the first term left out, x¹⁵/15, is below 2⁻⁵³·|x| for |x| ≤ 0.06).
  static constexpr double kMaxIncrementTangent = 0.06;
  // Angles within this of ±π [rad] are evaluated exactly (atan2's convention at the cut, (−π, π]).
  static constexpr double kCutMargin_rad = 0.1;
  // |φy| above this [rad] (cos φy below ~1e-3) is evaluated exactly: near the gimbal lock the yaw and roll
  // vectors shrink and EulerZyxFromUnitQuaternion's own rule applies.
  static constexpr double kMaxPitch_rad = 1.57;

  // The Euler angles of the unit quaternion q_WB of output sample `index` (samples are numbered in order).
  Eigen::Vector3d Next(const Eigen::Quaterniond& q_WB, std::size_t index) {
    const double tx = 2.0 * q_WB.x();
    const double ty = 2.0 * q_WB.y();
    const double tz = 2.0 * q_WB.z();
    // The entries of R_WB as EulerZyxFromUnitQuaternion forms them.
    const double r00 = 1.0 - (ty * q_WB.y() + tz * q_WB.z());
    const double r10 = ty * q_WB.x() + tz * q_WB.w();
    const double r20 = tz * q_WB.x() - ty * q_WB.w();
    const double r21 = tz * q_WB.y() + tx * q_WB.w();
    const double r22 = 1.0 - (tx * q_WB.x() + ty * q_WB.y());
    const bool follows = valid_ && index == index_ + 1 && since_exact_ < kExactEvery;
    index_ = index;
    if (follows) {
      const double phi_y = std::asin(std::clamp(-r20, -1.0, 1.0));
      double phi_z = 0.0;
      double phi_x = 0.0;
      if (std::abs(phi_y) <= kMaxPitch_rad && Increment(yaw_cos_, yaw_sin_, r00, r10, euler_[0], &phi_z) &&
          Increment(roll_cos_, roll_sin_, r22, r21, euler_[2], &phi_x)) {
        Keep({phi_z, phi_y, phi_x}, r00, r10, r22, r21);
        ++since_exact_;
        return euler_;
      }
    }
    Keep(EulerZyxFromUnitQuaternion(q_WB), r00, r10, r22, r21);
    since_exact_ = 0;
    valid_ = std::abs(euler_[1]) <= kMaxPitch_rad;
    return euler_;
  }

 private:
  // φ_before plus the angle from (c0, s0) to (c1, s1) in *phi, when that angle's tangent is small and the result
  // is away from the cut at ±π.
  static bool Increment(double c0, double s0, double c1, double s1, double phi_before, double* phi) {
    const double dot = c0 * c1 + s0 * s1;
    if (!(dot > 0.0)) return false;
    const double x = (c0 * s1 - s0 * c1) / dot;  // tan of the increment
    if (!(std::abs(x) <= kMaxIncrementTangent)) return false;
    const double x2 = x * x;
    // atan x = x − x³/3 + x⁵/5 − … − x¹³/13.
    const double series =
        x * (1.0 + x2 * (-1.0 / 3.0 +
                         x2 * (1.0 / 5.0 +
                               x2 * (-1.0 / 7.0 + x2 * (1.0 / 9.0 + x2 * (-1.0 / 11.0 + x2 * (1.0 / 13.0)))))));
    *phi = phi_before + series;
    return std::abs(*phi) < kPi - kCutMargin_rad;
  }
  void Keep(const Eigen::Vector3d& euler, double r00, double r10, double r22, double r21) {
    euler_ = euler;
    yaw_cos_ = r00;
    yaw_sin_ = r10;
    roll_cos_ = r22;
    roll_sin_ = r21;
  }

  static constexpr double kPi = 3.14159265358979323846;
  bool valid_ = false;
  std::size_t index_ = 0;
  int since_exact_ = 0;
  Eigen::Vector3d euler_ = Eigen::Vector3d::Zero();
  double yaw_cos_ = 1.0;  // R(0,0) and R(1,0) of the previous sample: cos φz, sin φz times cos φy
  double yaw_sin_ = 0.0;
  double roll_cos_ = 1.0;  // R(2,2) and R(2,1): cos φx, sin φx times cos φy
  double roll_sin_ = 0.0;
};

}  // namespace rockfit::core::detail
