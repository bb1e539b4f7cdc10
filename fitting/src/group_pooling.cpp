#include "rockfit/fitting/group_pooling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gsl/gsl_cdf.h>

namespace rockfit::fitting {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kZ95 = 1.959963984540054;  // two-sided 95 % quantile of the normal distribution

}  // namespace

PooledEstimate PoolTrials(const std::vector<TrialEstimate>& trials) {
  PooledEstimate p;
  p.pooled = p.spread = p.chi2_per_dof = p.consistency_p = kNaN;
  p.interval_95 = {kNaN, kNaN};
  std::vector<double> values, x, w;
  for (const TrialEstimate& t : trials) {
    if (!std::isfinite(t.value)) continue;
    values.push_back(t.value);
    const double half_width = 0.5 * (t.interval_95[1] - t.interval_95[0]);
    if (t.determined && std::isfinite(half_width) && half_width > 0.0) {
      const double sigma = half_width / kZ95;
      x.push_back(t.value);
      w.push_back(1.0 / (sigma * sigma));
    }
  }
  p.n_trials = static_cast<int>(values.size());
  p.n_pooled = static_cast<int>(x.size());
  if (values.size() >= 2) {
    double mean = 0.0;
    for (double v : values) mean += v / static_cast<double>(values.size());
    double ss = 0.0;
    for (double v : values) ss += (v - mean) * (v - mean);
    p.spread = std::sqrt(ss / static_cast<double>(values.size() - 1));
  }
  if (x.empty()) return p;
  double sw = 0.0, swx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sw += w[i];
    swx += w[i] * x[i];
  }
  p.pooled = swx / sw;
  double sigma_pooled = 1.0 / std::sqrt(sw);
  if (x.size() >= 2) {
    double chi2 = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) chi2 += w[i] * (x[i] - p.pooled) * (x[i] - p.pooled);
    const double dof = static_cast<double>(x.size() - 1);
    p.chi2_per_dof = chi2 / dof;
    p.consistency_p = gsl_cdf_chisq_Q(chi2, dof);
    sigma_pooled *= std::max(1.0, std::sqrt(p.chi2_per_dof));
  }
  p.interval_95 = {p.pooled - kZ95 * sigma_pooled, p.pooled + kZ95 * sigma_pooled};
  return p;
}

}  // namespace rockfit::fitting
