#include "rockfit/fitting/motion_before_release.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::fitting {

void MotionBeforeReleaseOptions::Validate() const {
  if (!(std::isfinite(lookback_s) && lookback_s > 0.0)) {
    throw InvalidArgument(fmt::format("motion before the release: lookback_s must be a positive number of seconds, got {}",
                                      lookback_s));
  }
  if (!(std::isfinite(warn_turn_deg) && warn_turn_deg >= 0.0)) {
    throw InvalidArgument(fmt::format("motion before the release: warn_turn_deg must be a non-negative angle, got {}",
                                      warn_turn_deg));
  }
}

MotionBeforeRelease MeasureMotionBeforeRelease(const MeasuredSignal& signal, double t0_s,
                                               const MotionBeforeReleaseOptions& options) {
  options.Validate();
  if (!std::isfinite(t0_s)) throw InvalidArgument(fmt::format("motion before the release: t0 must be finite, got {}", t0_s));
  MotionBeforeRelease m;
  m.t0_s = t0_s;
  if (!options.enabled || signal.size() < 2 || !(t0_s > signal.t_s.front())) return m;
  const double t_begin_s = std::max(signal.t_s.front(), t0_s - options.lookback_s);
  m.available = true;
  m.lookback_s = t0_s - t_begin_s;

  // ∫_t^t0 ω_m dt backwards from t0 by trapezoids of the linear interpolant, exact for a piecewise-linear ω_m.
  double t_after_s = t0_s;
  Eigen::Vector3d w_after_B = signal.Interpolate(t0_s);
  m.rate_at_release_rad_s = w_after_B.norm();
  Eigen::Vector3d turn_rad = Eigen::Vector3d::Zero();
  double farthest_rad = 0.0;
  const auto back_to = [&](double t_s, const Eigen::Vector3d& w_B) {
    turn_rad += 0.5 * (w_B + w_after_B) * (t_after_s - t_s);
    farthest_rad = std::max(farthest_rad, turn_rad.norm());
    t_after_s = t_s;
    w_after_B = w_B;
  };
  // The samples strictly inside (t_begin, t0), latest first, then the start of the stretch.
  std::size_t k = static_cast<std::size_t>(std::lower_bound(signal.t_s.begin(), signal.t_s.end(), t0_s) - signal.t_s.begin());
  while (k > 0 && signal.t_s[k - 1] > t_begin_s) {
    --k;
    back_to(signal.t_s[k], signal.w_B[k]);
  }
  back_to(t_begin_s, signal.Interpolate(t_begin_s));
  m.turn_deg = farthest_rad / io::kRadPerDeg;
  m.moving = m.turn_deg > options.warn_turn_deg;
  return m;
}

std::string MotionBeforeReleaseJson(const MotionBeforeRelease& m) {
  auto number = [&](double v) { return m.available && std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  return nlohmann::json{{"available", m.available},
                        {"t0_s", m.t0_s},
                        {"lookback_s", number(m.lookback_s)},
                        {"turn_deg", number(m.turn_deg)},
                        {"rate_at_release_rad_s", number(m.rate_at_release_rad_s)},
                        {"moving", m.available ? nlohmann::json(m.moving) : nlohmann::json()}}
      .dump();
}

std::string MotionBeforeReleaseText(const MotionBeforeRelease& m) {
  if (!m.available) return fmt::format("not measured: the recording has no samples before t0 = {:.4f} s", m.t0_s);
  return fmt::format("turned {:.3f}° ({:.2f} mrad) in the {:.2f} s before t0 = {:.4f} s, {:.3g} rad/s at t0{}",
                     m.turn_deg, 1e3 * io::kRadPerDeg * m.turn_deg, m.lookback_s, m.t0_s, m.rate_at_release_rad_s,
                     m.moving ? ": moving at the release" : "");
}

std::string MotionBeforeReleaseWarning(const MotionBeforeRelease& m) {
  return fmt::format("the recording turned by {:.2f}° ({:.1f} mrad) in the {:.2f} s before the fitted release at "
                     "t0 = {:.4f} s, where the model is at rest, and moved at {:.3g} rad/s at t0: the block was "
                     "already moving when the fit releases it (pushed, or let go while moving); t0 and α are those of "
                     "the release from rest that best matches the later motion, not of the real release",
                     m.turn_deg, 1e3 * io::kRadPerDeg * m.turn_deg, m.lookback_s, m.t0_s, m.rate_at_release_rad_s);
}

}  // namespace rockfit::fitting
