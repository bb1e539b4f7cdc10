#include "rockfit/io/impact_consistency.hpp"

#include <algorithm>
#include <cmath>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

void ImpactConsistencyOptions::Validate() const {
  if (!std::isfinite(max_return_fraction) || max_return_fraction < 0.0 || max_return_fraction > 1.0) {
    throw InvalidArgument("impact consistency max_return_fraction must be in [0, 1]");
  }
  if (!std::isfinite(return_tolerance_rad) || return_tolerance_rad < 0.0) {
    throw InvalidArgument("impact consistency return_tolerance_rad must be a finite number ≥ 0 [rad]");
  }
}

namespace {

// The angle swept since t_s[0] (trapezoid rule), as a function of time by linear interpolation.
class SweptAngle {
 public:
  SweptAngle(const std::vector<double>& t, const std::vector<double>& rate) : t_(t), swept_(t.size(), 0.0) {
    for (std::size_t i = 1; i < t.size(); ++i) swept_[i] = swept_[i - 1] + 0.5 * (rate[i - 1] + rate[i]) * (t[i] - t[i - 1]);
  }
  double At(double time) const {
    if (time <= t_.front()) return swept_.front();
    if (time >= t_.back()) return swept_.back();
    const auto k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), time) - t_.begin());
    const double f = (time - t_[k - 1]) / (t_[k] - t_[k - 1]);
    return swept_[k - 1] + f * (swept_[k] - swept_[k - 1]);
  }
  // Largest |swept(t) − reference| over the samples strictly between a and b.
  double LargestSwing(double a, double b, double reference) const {
    const double lo = std::min(a, b), hi = std::max(a, b);
    auto k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), lo) - t_.begin());
    double largest = 0.0;
    for (; k < t_.size() && t_[k] < hi; ++k) largest = std::max(largest, std::abs(swept_[k] - reference));
    return largest;
  }

 private:
  const std::vector<double>& t_;
  std::vector<double> swept_;
};

}  // namespace

std::vector<std::size_t> ConsistentZeroInstants(const std::vector<double>& t_s, const std::vector<double>& rate_rad_s,
                                                const std::vector<double>& candidate_times_s,
                                                const std::vector<double>& strength,
                                                const ImpactConsistencyOptions& options) {
  options.Validate();
  if (t_s.size() != rate_rad_s.size() || candidate_times_s.size() != strength.size()) {
    throw InvalidArgument("ConsistentZeroInstants: inputs of different lengths");
  }
  const std::size_t n = candidate_times_s.size();
  if (n == 0 || t_s.size() < 2) return {};
  const SweptAngle swept(t_s, rate_rad_s);
  const std::size_t seed =
      static_cast<std::size_t>(std::max_element(strength.begin(), strength.end()) - strength.begin());
  std::vector<bool> keep(n, false);
  keep[seed] = true;
  const auto accepts = [&](std::size_t last, std::size_t candidate) {
    const double reference = swept.At(candidate_times_s[last]);
    const double back = std::abs(swept.At(candidate_times_s[candidate]) - reference);
    const double swing = swept.LargestSwing(candidate_times_s[last], candidate_times_s[candidate], reference);
    return back <= options.max_return_fraction * swing + options.return_tolerance_rad;
  };
  for (std::size_t last = seed, j = seed + 1; j < n; ++j) {
    if (accepts(last, j)) keep[j] = true, last = j;
  }
  for (std::size_t last = seed, j = seed; j-- > 0;) {
    if (accepts(last, j)) keep[j] = true, last = j;
  }
  std::vector<std::size_t> accepted;
  for (std::size_t j = 0; j < n; ++j) {
    if (keep[j]) accepted.push_back(j);
  }
  return accepted;
}

}  // namespace rockfit::io
