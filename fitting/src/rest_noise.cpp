#include "rockfit/fitting/rest_noise.hpp"

#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {

void RestSegmentOptions::Validate() const {
  for (double v : {margin_s, min_duration_s}) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      throw InvalidArgument(fmt::format("rest segment: durations must be non-negative seconds, got {}", v));
    }
  }
}

RestNoise MeasureRestNoise(const MeasuredSignal& signal, double t_release_s, const RestSegmentOptions& options) {
  options.Validate();
  RestNoise rest;
  const double rest_end = t_release_s - options.margin_s;
  if (signal.size() == 0) return rest;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  // Samples before the end of the rest, less the excluded ones (a clipped gyro, gyro_clipping.hpp).
  std::size_t end = 0, n = 0;
  for (; end < signal.size() && signal.t_s[end] < rest_end; ++end) {
    if (signal.is_excluded(end)) continue;
    sum += signal.w_B[end];
    sum_sq += signal.w_B[end].cwiseAbs2();
    ++n;
  }
  rest.samples = n;
  rest.duration_s = rest_end - signal.t_s.front();
  if (n < 2 || rest.duration_s < options.min_duration_s) return rest;
  rest.available = true;
  rest.mean_rad_s = sum / static_cast<double>(n);
  rest.variance_rad2_s2 = sum_sq / static_cast<double>(n) - rest.mean_rad_s.cwiseAbs2();
  double norm_sum = 0.0;
  for (std::size_t k = 0; k < end; ++k) {
    if (!signal.is_excluded(k)) norm_sum += (signal.w_B[k] - rest.mean_rad_s).norm();
  }
  rest.epsilon_floor_rad_s = norm_sum / static_cast<double>(n);
  return rest;
}

}  // namespace rockfit::fitting
