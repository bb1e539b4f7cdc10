#include "recording/orientation_resampling.hpp"

#include <algorithm>

#include "recording/time_base.hpp"

namespace rockfit::io {
namespace {

double MedianStep(const std::vector<double>& t) {
  if (t.size() < 2) return 0.0;
  std::vector<double> steps(t.size() - 1);
  for (std::size_t k = 0; k + 1 < t.size(); ++k) steps[k] = t[k + 1] - t[k];
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

}  // namespace

ResampledOrientation ResampleOrientation(const std::vector<double>& target_t_s, const OrientationSeries& series) {
  ResampledOrientation result;
  if (series.empty() || target_t_s.empty()) return result;
  const double start = series.t_s.front() - kSameInstant_s;
  const double stop = series.t_s.back() + kSameInstant_s;
  result.first = static_cast<std::size_t>(std::lower_bound(target_t_s.begin(), target_t_s.end(), start) - target_t_s.begin());
  result.median_step_s = MedianStep(series.t_s);
  const double hole_step = kGapStepFactor * result.median_step_s;

  std::size_t j = 0;  // series.t_s[j] ≤ t < series.t_s[j + 1] (up to kSameInstant_s)
  std::size_t hole_interval = series.t_s.size();  // the interval a hole was last recorded for
  for (std::size_t k = result.first; k < target_t_s.size() && target_t_s[k] <= stop; ++k) {
    const double t = target_t_s[k];
    while (j + 1 < series.t_s.size() && series.t_s[j + 1] <= t + kSameInstant_s) ++j;
    if (std::abs(t - series.t_s[j]) <= kSameInstant_s || j + 1 == series.t_s.size()) {
      result.q_WS.push_back(series.q_WS[j]);
      continue;
    }
    const double t0 = series.t_s[j];
    const double t1 = series.t_s[j + 1];
    result.q_WS.push_back(series.q_WS[j].slerp((t - t0) / (t1 - t0), series.q_WS[j + 1]));
    if (result.median_step_s > 0.0 && t1 - t0 > hole_step) {
      if (hole_interval != j) result.holes.push_back({t0, t1 - t0, 0});
      hole_interval = j;
      ++result.holes.back().samples;
    }
  }
  return result;
}

}  // namespace rockfit::io
