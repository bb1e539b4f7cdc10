#include "rockfit/io/impact_zero_crossing.hpp"

#include <cmath>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

void ZeroCrossingOptions::Validate() const {
  if (rate_fit_samples < 2) {
    throw InvalidArgument("zero crossing rate_fit_samples must be at least 2 (a line), got " +
                          std::to_string(rate_fit_samples));
  }
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

}  // namespace rockfit::io
