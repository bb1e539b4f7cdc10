#include "rockfit/fitting/model_error_widening.hpp"

#include <algorithm>
#include <cmath>

namespace rockfit::fitting {

double ModelErrorWideningFactor(double epsilon_over_noise_floor, double coefficient) {
  const double r = epsilon_over_noise_floor;
  if (!std::isfinite(r) || !(r > 1.0) || !(coefficient > 0.0)) return 1.0;
  return std::sqrt(1.0 + coefficient * coefficient * (r * r - 1.0));
}

double WidenedHalfWidth(double half_width, double factor, double floor) { return std::hypot(factor * half_width, floor); }

Interval WidenInterval(const Interval& interval, double value, double factor, double floor, double lower, double upper) {
  Interval out = interval;
  if (!std::isnan(out[0])) out[0] = std::max(lower, value - WidenedHalfWidth(value - out[0], factor, floor));
  if (!std::isnan(out[1])) out[1] = std::min(upper, value + WidenedHalfWidth(out[1] - value, factor, floor));
  return out;
}

}  // namespace rockfit::fitting
