// Prescribed motion of the rigid table: the ground acceleration a_g(t) in the world frame W, piecewise
// linear between the samples of a record (uniform step), zero before the first and after the last sample.
// The simulator integrates in the ground frame with the inertial force −m·a_g at the centre of mass and
// stops its integrator steps at the record's sample times, so that the right-hand side is smooth within a
// step and event times stay exact (core/README.md, "Ground motion").
//
//   const GroundMotion quake = GroundMotion::Uniform(0.01, a_W);   // a_W[k] at t = k·0.01 s [m/s²]
//   const Eigen::Vector3d a = quake.Acceleration_W(2.345);
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace rockfit::core {

// Standard gravity of records given in units of g [m/s²] (the simulation's g is a separate option).
inline constexpr double kRecordGravity = 9.80665;

class GroundMotion {
 public:
  // Relative round-off of t/dt within which t is a sample time.
  static constexpr double kSampleTimeRoundOff = 4.0 * std::numeric_limits<double>::epsilon();

  GroundMotion() = default;
  // Samples a_W[k] [m/s²] at t = t_start_s + k·dt_s. Throws InvalidArgument for dt ≤ 0, fewer than two
  // samples or a non-finite value.
  static GroundMotion Uniform(double dt_s, std::vector<Eigen::Vector3d> a_W, double t_start_s = 0.0);

  bool empty() const { return size() == 0; }
  std::size_t size() const { return samples_W_ ? samples_W_->size() : 0; }
  double dt_s() const { return dt_s_; }
  double t_start_s() const { return t_start_s_; }
  double t_end_s() const { return t_start_s_ + static_cast<double>(size() - 1) * dt_s_; }
  double SampleTime(std::size_t k) const { return t_start_s_ + static_cast<double>(k) * dt_s_; }
  Eigen::Vector3d Sample(std::size_t k) const {
    const Eigen::Vector3d& a = (*samples_W_)[k];
    if (!transformed_) return a;
    return Eigen::Vector3d(cos_ * a.x() - sin_ * a.y(), sin_ * a.x() + cos_ * a.y(), a.z()) * factor_;
  }
  // Every sample, as Sample(k) gives it (a copy).
  std::vector<Eigen::Vector3d> samples_W() const;

  // a_g(t): linear between samples, exactly the sample at a sample time, zero outside the record. Inline: the
  // right-hand side of every mode under ground motion calls it at each integrator stage.
  Eigen::Vector3d Acceleration_W(double t_s) const {
    const std::size_t n = size();
    if (n == 0 || t_s < t_start_s_) return Eigen::Vector3d::Zero();
    const double x = (t_s - t_start_s_) / dt_s_;  // ≥ 0
    const double last = static_cast<double>(n - 1);
    if (x > last) return t_s <= t_end_s() ? Sample(n - 1) : Eigen::Vector3d::Zero();
    // At a sample time (to the round-off of t/dt) the sample itself, so that breaks are exact. (The nearest
    // integer by truncation of x + 1/2, x ≥ 0: it differs from rounding only next to a half, where x is far from
    // any integer anyway.)
    const auto nearest = static_cast<std::size_t>(x + 0.5);
    if (std::abs(x - static_cast<double>(nearest)) <= kSampleTimeRoundOff * std::max(1.0, x)) return Sample(nearest);
    const std::size_t k = std::min(static_cast<std::size_t>(x), n - 2);
    const double u = (t_s - SampleTime(k)) / dt_s_;
    return (1.0 - u) * Sample(k) + u * Sample(k + 1);
  }
  // The first sample time after t_s by more than the round-off of t (+∞ after the last sample): where the
  // slope of a_g changes.
  double NextBreak(double t_s) const;

  // Largest |a_x, a_y| (horizontal resultant) and |a_z| over the samples [m/s²].
  double PeakHorizontal() const;
  double PeakVertical() const;
  // The same motion with every sample multiplied by `factor`.
  GroundMotion Scaled(double factor) const;
  // Horizontal components rotated about the vertical by β (a record along x acts along (cos β, sin β, 0)).
  GroundMotion Rotated(double beta_rad) const;
  // Rotated(β).Scaled(factor), bit for bit, as a view that shares this motion's samples instead of copying them:
  // the many samples of a fragility study run on one copy of each record whatever the number of threads.
  GroundMotion RotatedAndScaled(double beta_rad, double factor) const;

 private:
  double dt_s_ = 1.0;
  double t_start_s_ = 0.0;
  // The samples as given to Uniform, shared by the copies and views of one record (never changed).
  std::shared_ptr<const std::vector<Eigen::Vector3d>> samples_W_;
  // A view's rotation about the vertical (cos β, sin β) and scale factor, applied in Sample().
  bool transformed_ = false;
  double cos_ = 1.0;
  double sin_ = 0.0;
  double factor_ = 1.0;
  // max |a_z| over the stored samples (before a view's scale factor), so that PeakVertical() costs nothing.
  double stored_peak_vertical_ = 0.0;
};

// The first time in [t_from, t_until] at which the table accelerates downward at least as fast as g
// (g + a_z ≤ 0): from then on the block would leave the ground (end status `lift_off`). +∞ if never.
double LiftOffTime(const GroundMotion& ground, double gravity_m_s2, double t_from_s, double t_until_s);

}  // namespace rockfit::core
