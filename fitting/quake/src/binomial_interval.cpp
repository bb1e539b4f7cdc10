#include "rockfit/quake/binomial_interval.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <gsl/gsl_cdf.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::quake {
namespace {

void Check(std::int64_t k, std::int64_t n, double confidence) {
  if (n < 0 || k < 0 || k > n) {
    throw InvalidArgument("a binomial interval needs 0 ≤ successes ≤ trials, got " + std::to_string(k) + " of " +
                          std::to_string(n));
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw InvalidArgument("a confidence level must be between 0 and 1, got " + std::to_string(confidence));
  }
}

}  // namespace

fitting::Interval WilsonInterval(std::int64_t successes, std::int64_t trials, double confidence) {
  Check(successes, trials, confidence);
  if (trials == 0) return {0.0, 1.0};
  const double z = gsl_cdf_ugaussian_Qinv(0.5 * (1.0 - confidence));
  const double n = static_cast<double>(trials), k = static_cast<double>(successes);
  const double z2 = z * z;
  const double centre = (k + 0.5 * z2) / (n + z2);
  const double half = z / (n + z2) * std::sqrt(k * (n - k) / n + 0.25 * z2);
  // At k = 0 and k = n the formula gives 0 and 1 up to round-off: exactly, so that a certain outcome reads as one.
  const double lower = successes == 0 ? 0.0 : std::max(0.0, centre - half);
  const double upper = successes == trials ? 1.0 : std::min(1.0, centre + half);
  return {lower, upper};
}

fitting::Interval ClopperPearsonInterval(std::int64_t successes, std::int64_t trials, double confidence) {
  Check(successes, trials, confidence);
  if (trials == 0) return {0.0, 1.0};
  const double alpha = 1.0 - confidence;
  const double n = static_cast<double>(trials), k = static_cast<double>(successes);
  const double lower = successes == 0 ? 0.0 : gsl_cdf_beta_Pinv(0.5 * alpha, k, n - k + 1.0);
  const double upper = successes == trials ? 1.0 : gsl_cdf_beta_Qinv(0.5 * alpha, k + 1.0, n - k);
  return {lower, upper};
}

}  // namespace rockfit::quake
