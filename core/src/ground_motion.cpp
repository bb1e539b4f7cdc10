#include "rockfit/core/ground_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

// Round-off floor of a time variable t [s]: two break times closer than this are the same instant (the same
// floor as the integrator's smallest step, with a margin).
double TimeFloor(double t_s) { return 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_s)); }

// A record whose vertical samples stay below this fraction of g cannot lift the block off (interpolation between
// samples exceeds their range by round-off at most).
constexpr double kNoLiftOffFraction = 0.5;

double MaxAbsZ(const std::vector<Eigen::Vector3d>& a_W) {
  double peak = 0.0;
  for (const Eigen::Vector3d& a : a_W) peak = std::max(peak, std::abs(a.z()));
  return peak;
}

}  // namespace

GroundMotion GroundMotion::Uniform(double dt_s, std::vector<Eigen::Vector3d> a_W, double t_start_s) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw InvalidArgument("the time step of a ground motion must be a positive number of seconds, got " +
                          std::to_string(dt_s));
  }
  if (!std::isfinite(t_start_s)) throw InvalidArgument("the start time of a ground motion must be finite");
  if (a_W.size() < 2) throw InvalidArgument("a ground motion needs at least two samples");
  for (std::size_t k = 0; k < a_W.size(); ++k) {
    if (!a_W[k].allFinite()) {
      throw InvalidArgument("ground acceleration sample " + std::to_string(k) + " is not a finite number");
    }
  }
  GroundMotion g;
  g.dt_s_ = dt_s;
  g.t_start_s_ = t_start_s;
  g.stored_peak_vertical_ = MaxAbsZ(a_W);
  g.samples_W_ = std::make_shared<const std::vector<Eigen::Vector3d>>(std::move(a_W));
  return g;
}

std::vector<Eigen::Vector3d> GroundMotion::samples_W() const {
  std::vector<Eigen::Vector3d> a_W(size());
  for (std::size_t k = 0; k < a_W.size(); ++k) a_W[k] = Sample(k);
  return a_W;
}

double GroundMotion::NextBreak(double t_s) const {
  if (empty()) return std::numeric_limits<double>::infinity();
  const double floor_s = TimeFloor(t_s);
  if (t_s < t_start_s_ - floor_s) return t_start_s_;
  const double x = std::max(0.0, std::floor((t_s - t_start_s_) / dt_s_));
  for (std::size_t k = static_cast<std::size_t>(x); k < size(); ++k) {
    const double t_k = SampleTime(k);
    if (t_k > t_s + floor_s) return t_k;
  }
  return std::numeric_limits<double>::infinity();
}

double GroundMotion::PeakHorizontal() const {
  double peak = 0.0;
  for (std::size_t k = 0; k < size(); ++k) peak = std::max(peak, Sample(k).head<2>().norm());
  return peak;
}

double GroundMotion::PeakVertical() const {
  // A view scales z by its factor alone, and rounding is monotone: max |z·f| = (max |z|)·|f| bit for bit.
  return transformed_ ? stored_peak_vertical_ * std::abs(factor_) : stored_peak_vertical_;
}

GroundMotion GroundMotion::Scaled(double factor) const {
  if (!std::isfinite(factor)) throw InvalidArgument("the scale factor of a ground motion must be finite");
  std::vector<Eigen::Vector3d> a_W = samples_W();
  for (Eigen::Vector3d& a : a_W) a *= factor;
  GroundMotion g = *this;
  g.stored_peak_vertical_ = MaxAbsZ(a_W);
  g.samples_W_ = std::make_shared<const std::vector<Eigen::Vector3d>>(std::move(a_W));
  g.transformed_ = false;
  return g;
}

GroundMotion GroundMotion::Rotated(double beta_rad) const {
  if (!std::isfinite(beta_rad)) throw InvalidArgument("the incidence angle of a ground motion must be finite");
  const double c = std::cos(beta_rad);
  const double s = std::sin(beta_rad);
  std::vector<Eigen::Vector3d> a_W = samples_W();
  for (Eigen::Vector3d& a : a_W) a = Eigen::Vector3d(c * a.x() - s * a.y(), s * a.x() + c * a.y(), a.z());
  GroundMotion g = *this;
  g.stored_peak_vertical_ = MaxAbsZ(a_W);
  g.samples_W_ = std::make_shared<const std::vector<Eigen::Vector3d>>(std::move(a_W));
  g.transformed_ = false;
  return g;
}

GroundMotion GroundMotion::RotatedAndScaled(double beta_rad, double factor) const {
  if (!std::isfinite(beta_rad)) throw InvalidArgument("the incidence angle of a ground motion must be finite");
  if (!std::isfinite(factor)) throw InvalidArgument("the scale factor of a ground motion must be finite");
  if (transformed_) return Rotated(beta_rad).Scaled(factor);  // a view of a view: materialised, as before
  GroundMotion g = *this;
  g.transformed_ = true;
  g.cos_ = std::cos(beta_rad);
  g.sin_ = std::sin(beta_rad);
  g.factor_ = factor;
  return g;
}

double LiftOffTime(const GroundMotion& ground, double gravity_m_s2, double t_from_s, double t_until_s) {
  const double inf = std::numeric_limits<double>::infinity();
  const auto margin = [&](double t) { return gravity_m_s2 + ground.Acceleration_W(t).z(); };
  if (ground.empty() || !(t_until_s >= t_from_s)) return inf;
  // g + a_z, linear between samples, stays positive where no sample comes near −g (every record without a
  // vertical component): no scan of the record.
  if (ground.PeakVertical() < kNoLiftOffFraction * gravity_m_s2) return inf;
  if (margin(t_from_s) <= 0.0) return t_from_s;
  // g + a_z is linear between breaks: a root lies between two break times where it changes sign.
  double t0 = t_from_s;
  double m0 = margin(t0);
  while (t0 < t_until_s) {
    const double t1 = std::min(ground.NextBreak(t0), t_until_s);
    if (!std::isfinite(t1)) return inf;
    // The value just before the break (the record's last sample is followed by a jump to zero).
    const double m1 = gravity_m_s2 + (ground.Acceleration_W(t1).z());
    if (m1 <= 0.0) return m0 <= 0.0 ? t0 : t0 + (t1 - t0) * m0 / (m0 - m1);  // (m0 > 0 ≥ m1)
    t0 = t1;
    m0 = m1;
  }
  return inf;
}

}  // namespace rockfit::core
