#include "rockfit/fitting/rest_noise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "upper_median.hpp"

namespace rockfit::fitting {

void RestSegmentOptions::Validate() const {
  for (double v : {margin_s, min_duration_s, still_rate_rad_s}) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      throw InvalidArgument(fmt::format("rest segment: durations and the still rate must be non-negative, got {}", v));
    }
  }
}

namespace {

// The samples t_k < rest_end less the excluded ones: at least two, and rest_end − first time ≥ min_duration.
bool LongEnough(const MeasuredSignal& signal, double rest_end, double min_duration_s) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < signal.size() && signal.t_s[k] < rest_end && n < 2; ++k) {
    if (!signal.is_excluded(k)) ++n;
  }
  return n >= 2 && rest_end - signal.t_s.front() >= min_duration_s;
}

// The end of the rest before t_release: t_release − margin, or margin before the onset of a motion that runs into
// t_release from the last still stretch of min_duration (rest_noise.hpp), where that leaves a rest long enough.
double RestEnd(const MeasuredSignal& signal, double t_release_s, const RestSegmentOptions& options) {
  const double planned_end = t_release_s - options.margin_s;
  if (!(options.still_rate_rad_s > 0.0) || !LongEnough(signal, planned_end, options.min_duration_s)) return planned_end;
  // The reference of stillness: the median per axis over the planned rest (robust to the motion's start in it).
  std::array<std::vector<double>, 3> axes;
  for (std::size_t k = 0; k < signal.size() && signal.t_s[k] < planned_end; ++k) {
    if (signal.is_excluded(k)) continue;
    for (int i = 0; i < 3; ++i) axes[static_cast<std::size_t>(i)].push_back(signal.w_B[k][i]);
  }
  Eigen::Vector3d median;
  for (int i = 0; i < 3; ++i) median[i] = UpperMedian(std::move(axes[static_cast<std::size_t>(i)]));
  const auto moving = [&](std::size_t k) {
    return signal.is_excluded(k) || (signal.w_B[k] - median).norm() >= options.still_rate_rad_s;
  };
  // Back from the last sample before t_release to the latest still stretch that lasts min_duration (a rest, not
  // a short stop at the top of a lift or a dip of |ω| in a wobble): the motion after it runs into the release.
  const std::size_t before_release = static_cast<std::size_t>(
      std::lower_bound(signal.t_s.begin(), signal.t_s.end(), t_release_s) - signal.t_s.begin());
  std::size_t run_end = before_release;  // one past the last sample of the still stretch being walked over
  bool found = false;
  for (std::size_t k = before_release; k-- > 0;) {
    if (moving(k)) {
      run_end = k;
    } else if (signal.t_s[run_end - 1] - signal.t_s[k] >= options.min_duration_s) {
      found = true;
      break;
    }
  }
  if (!found || run_end == before_release) return planned_end;  // no rest at all, or still up to the release
  const double cut_end = signal.t_s[run_end] - options.margin_s;
  if (!(cut_end < planned_end) || !LongEnough(signal, cut_end, options.min_duration_s)) return planned_end;
  return cut_end;
}

}  // namespace

RestNoise MeasureRestNoise(const MeasuredSignal& signal, double t_release_s, const RestSegmentOptions& options) {
  options.Validate();
  RestNoise rest;
  if (signal.size() == 0) return rest;
  const double rest_end = RestEnd(signal, t_release_s, options);
  rest.cut_before_release_s = (t_release_s - options.margin_s) - rest_end;
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
