#include "rockfit/fitting/lateral_motion_check.hpp"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/rest_noise.hpp"
#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

void LateralMotionCheckOptions::Validate() const {
  for (double v : {rest_margin_s, rest_min_duration_s, min_signal_to_noise_variance, max_unexplained_fraction}) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      throw InvalidArgument(fmt::format("lateral motion check options must be finite and non-negative, got {}", v));
    }
  }
}

LateralMotionCheck CheckLateralMotion(const Objective& objective, const ParameterSet& fitted,
                                      const LateralMotionCheckOptions& options) {
  options.Validate();
  LateralMotionCheck check;
  if (!options.enabled) return check;
  const MeasuredSignal& signal = objective.signal();
  const double t0 = fitted.value(ParameterId::kT0);

  // The noise at rest: ω_x and ω_z about their means before the release.
  const RestNoise rest = MeasureRestNoise(signal, t0, {options.rest_margin_s, options.rest_min_duration_s});
  if (!rest.available) return check;
  const double noise_var = 0.5 * (rest.variance_rad2_s2.x() + rest.variance_rad2_s2.z());

  // The window of (28): measured and residual out-of-plane components with the trapezoid weights.
  ErrorNodes nodes;
  ModelOutput output;
  const Evaluation e = objective.EvaluateDetailed(fitted, &nodes, &output);
  if (!e.feasible || output.w_B.size() != nodes.size() || nodes.size() < 2) return check;
  double weight = 0.0, measured_sq = 0.0, residual_sq = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Eigen::Vector3d& m = nodes.w_m_B[k];
    const Eigen::Vector3d r = m - output.w_B[k];
    weight += nodes.weight_s[k];
    measured_sq += nodes.weight_s[k] * 0.5 * (m.x() * m.x() + m.z() * m.z());
    residual_sq += nodes.weight_s[k] * 0.5 * (r.x() * r.x() + r.z() * r.z());
  }
  if (!(weight > 0.0) || !std::isfinite(measured_sq) || !std::isfinite(residual_sq) || !(noise_var >= 0.0)) return check;
  const double measured_var = measured_sq / weight, residual_var = residual_sq / weight;
  check.available = true;
  check.rest_noise_rad_s = std::sqrt(noise_var);
  check.measured_rms_rad_s = std::sqrt(measured_var);
  check.residual_rms_rad_s = std::sqrt(residual_var);
  const bool signal_present = measured_var >= options.min_signal_to_noise_variance * noise_var && measured_var > noise_var;
  check.judged = signal_present;
  if (signal_present) {
    check.unexplained_fraction = std::max(0.0, (residual_var - noise_var) / (measured_var - noise_var));
    check.unexplained = check.unexplained_fraction >= options.max_unexplained_fraction;
  }
  return check;
}

}  // namespace rockfit::fitting

namespace rockfit::fitting {

std::string LateralMotionJson(const LateralMotionCheck& c) {
  auto number = [&](double v) { return c.available ? nlohmann::json(v) : nlohmann::json(); };
  return nlohmann::json{{"available", c.available},
                        {"rest_noise_rad_s", number(c.rest_noise_rad_s)},
                        {"measured_rms_rad_s", number(c.measured_rms_rad_s)},
                        {"residual_rms_rad_s", number(c.residual_rms_rad_s)},
                        {"unexplained_fraction", number(c.unexplained_fraction)},
                        {"judged", c.judged},
                        {"unexplained", c.unexplained}}
      .dump();
}

}  // namespace rockfit::fitting
