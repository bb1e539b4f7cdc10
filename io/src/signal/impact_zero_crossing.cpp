#include "rockfit/io/impact_zero_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

namespace {

// Bisection steps: the bracket of one sample interval shrinks to 2^-60 of it, far below any time resolution.
constexpr int kBisectionSteps = 60;

}  // namespace

void ZeroCrossingOptions::Validate() const {
  if (rate_fit_samples < 2) {
    throw InvalidArgument("zero crossing rate_fit_samples must be at least 2 (a line), got " +
                          std::to_string(rate_fit_samples));
  }
  if (!std::isfinite(drift_half_window_s) || drift_half_window_s <= 0.0) {
    throw InvalidArgument("zero crossing drift_half_window_s must be a positive number of seconds");
  }
  if (!std::isfinite(reading_scatter_rad) || reading_scatter_rad <= 0.0) {
    throw InvalidArgument("zero crossing reading_scatter_rad must be a positive number of radians");
  }
}

double SmoothDriftAt(const std::vector<DriftPoint>& points, double t_s, double half_window_s) {
  if (points.empty()) return 0.0;
  double weights = 0.0, sum = 0.0;
  for (const DriftPoint& p : points) {
    if (std::abs(p.t_s - t_s) > half_window_s) continue;
    weights += p.weight;
    sum += p.weight * p.value_rad;
  }
  if (weights > 0.0) return sum / weights;
  const auto nearest = std::min_element(points.begin(), points.end(), [&](const DriftPoint& a, const DriftPoint& b) {
    return std::abs(a.t_s - t_s) < std::abs(b.t_s - t_s);
  });
  return nearest->value_rad;
}

DriftPoint BeforeImpact::MiddleReading(double reading_scatter_rad) const {
  const double t_mid = 0.5 * (t0_s + t1_s);
  const double dt = t1_s - t0_s;
  const double variance = rate_rad_s * rate_rad_s * dt * dt / 12.0 + reading_scatter_rad * reading_scatter_rad;
  return {t_mid, At(t_mid), 1.0 / variance};
}

std::optional<BeforeImpact> AngleBeforeImpact(const std::vector<double>& t_s, const std::vector<double>& angle_rad,
                                              const std::vector<double>& rate_rad_s, std::size_t m,
                                              const ZeroCrossingOptions& options) {
  options.Validate();
  const std::size_t n = t_s.size();
  if (angle_rad.size() != n || rate_rad_s.size() != n) {
    throw InvalidArgument("AngleBeforeImpact: time, angle and rate must have the same length");
  }
  if (m + 1 >= n || m + 1 < options.rate_fit_samples) return std::nullopt;
  // The rate line a + b·(t − t_m) through the samples m − K + 1 … m.
  const std::size_t first = m + 1 - options.rate_fit_samples;
  double count = 0.0, sum_x = 0.0, sum_y = 0.0, sum_xx = 0.0, sum_xy = 0.0;
  for (std::size_t j = first; j <= m; ++j) {
    const double x = t_s[j] - t_s[m];
    count += 1.0, sum_x += x, sum_y += rate_rad_s[j], sum_xx += x * x, sum_xy += x * rate_rad_s[j];
  }
  const double spread = count * sum_xx - sum_x * sum_x;
  if (!(spread > 0.0)) return std::nullopt;
  BeforeImpact before;
  before.t0_s = t_s[m];
  before.t1_s = t_s[m + 1];
  before.angle_rad = angle_rad[m];
  before.rate_rad_s = (sum_xx * sum_y - sum_x * sum_xy) / spread;
  before.rate_slope_rad_s2 = (count * sum_xy - sum_x * sum_y) / spread;
  return before;
}

std::optional<double> ZeroCrossingTime(const BeforeImpact& before, double drift_rad) {
  const auto f = [&](double s) { return before.At(before.t0_s + s) - drift_rad; };
  double lo = 0.0, hi = before.t1_s - before.t0_s;
  double f_lo = f(lo);
  if (f_lo == 0.0) return before.t0_s;
  if (f_lo * f(hi) > 0.0) return std::nullopt;
  for (int step = 0; step < kBisectionSteps; ++step) {
    const double mid = 0.5 * (lo + hi);
    const double f_mid = f(mid);
    if (f_mid * f_lo > 0.0) {
      lo = mid, f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  return before.t0_s + 0.5 * (lo + hi);
}

}  // namespace rockfit::io
