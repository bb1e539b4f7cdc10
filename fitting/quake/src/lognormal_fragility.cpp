#include "rockfit/quake/lognormal_fragility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sf_erf.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::quake {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kZ95 = 1.959963984540054;  // two-sided 95 % quantile of the normal distribution
// Newton stops when a step changes (a, b·|ln x|) by less than this: far below any standard error of a study,
// above the round-off of the gradient (a sum over all samples).
constexpr double kStepTolerance = 1e-8;
constexpr int kMaxIterations = 200;
// Smallest fraction of a Newton step tried before giving up (the log-likelihood is concave: never needed in
// exact arithmetic, only against round-off at the optimum).
constexpr double kMinStep = 1e-10;
// A Newton step this small that no longer increases the log-likelihood is at its optimum within round-off.
constexpr double kRoundOffStep = 1e-7;

// ln Φ(z), accurate in both tails.
double LogPhi(double z) { return gsl_sf_log_erfc(-z / M_SQRT2) - M_LN2; }

struct Data {
  std::vector<double> log_x;
  std::vector<double> n, k;
};

double LogLikelihood(const Data& d, double mu, double beta) {
  double sum = 0.0;
  for (std::size_t i = 0; i < d.log_x.size(); ++i) {
    const double z = (d.log_x[i] - mu) / beta;
    if (d.k[i] > 0.0) sum += d.k[i] * LogPhi(z);
    if (d.n[i] > d.k[i]) sum += (d.n[i] - d.k[i]) * LogPhi(-z);
  }
  return sum;
}


}  // namespace

const char* ToString(LognormalFitStatus status) {
  switch (status) {
    case LognormalFitStatus::kOk: return "ok";
    case LognormalFitStatus::kNoExceedance: return "no_exceedance";
    case LognormalFitStatus::kAllExceeded: return "all_exceeded";
    case LognormalFitStatus::kSeparated: return "separated";
    case LognormalFitStatus::kTooFewLevels: return "too_few_levels";
    case LognormalFitStatus::kNotConverged: return "not_converged";
  }
  return "?";
}

double LognormalFragility(double intensity, double median, double beta) {
  if (!(intensity > 0.0)) return 0.0;
  if (beta == 0.0) return intensity >= median ? 1.0 : 0.0;
  return gsl_cdf_ugaussian_P(std::log(intensity / median) / beta);
}

LognormalFragilityFit FitLognormalFragility(const std::vector<LevelCount>& levels) {
  LognormalFragilityFit fit;
  fit.median = fit.beta = fit.median_std_error = fit.beta_std_error = fit.correlation = fit.log_likelihood = kNaN;
  fit.median_interval_95 = {kNaN, kNaN};
  std::vector<LevelCount> used;
  for (const LevelCount& l : levels) {
    if (!(l.intensity > 0.0) || !std::isfinite(l.intensity)) {
      throw InvalidArgument(fmt::format("a fragility level needs a positive finite intensity, got {}", l.intensity));
    }
    if (l.trials < 0 || l.exceeded < 0 || l.exceeded > l.trials) {
      throw InvalidArgument(fmt::format("a fragility level needs 0 ≤ exceeded ≤ trials, got {} of {}", l.exceeded, l.trials));
    }
    if (l.trials > 0) used.push_back(l);
  }
  std::sort(used.begin(), used.end(), [](const LevelCount& a, const LevelCount& b) { return a.intensity < b.intensity; });
  if (used.size() < 2) {
    fit.status = LognormalFitStatus::kTooFewLevels;
    fit.message = fmt::format("{} level(s) with samples; a curve needs at least two", used.size());
    return fit;
  }
  std::int64_t total_exceeded = 0, total = 0;
  for (const LevelCount& l : used) total_exceeded += l.exceeded, total += l.trials;
  if (total_exceeded == 0) {
    fit.status = LognormalFitStatus::kNoExceedance;
    fit.message = fmt::format("no sample reached the limit state up to {:.4g}: the median is beyond the highest level",
                              used.back().intensity);
    return fit;
  }
  if (total_exceeded == total) {
    fit.status = LognormalFitStatus::kAllExceeded;
    fit.message = fmt::format("every sample reached the limit state from {:.4g} on: the median is below the lowest level",
                              used.front().intensity);
    return fit;
  }
  // (Quasi-)separation: levels with none exceeded, at most one mixed level, then levels with all exceeded. The
  // likelihood then grows without bound as β → 0: no dispersion can be estimated.
  std::size_t mixed = 0, mixed_at = 0;
  bool monotone = true;
  int phase = 0;  // 0: none exceeded so far, 1: after the mixed level, 2: all exceeded
  for (std::size_t i = 0; i < used.size(); ++i) {
    const bool none = used[i].exceeded == 0, all = used[i].exceeded == used[i].trials;
    if (none) {
      monotone = monotone && phase == 0;
    } else if (all) {
      phase = 2;
    } else {
      ++mixed;
      mixed_at = i;
      monotone = monotone && phase == 0;
      phase = 1;
    }
  }
  if (monotone && mixed <= 1) {
    std::size_t first_exceeded = 0;
    while (used[first_exceeded].exceeded == 0) ++first_exceeded;
    fit.status = LognormalFitStatus::kSeparated;
    fit.beta = 0.0;
    fit.log_likelihood = 0.0;
    if (mixed == 0) {
      const double below = used[first_exceeded - 1].intensity, above = used[first_exceeded].intensity;
      fit.median = std::sqrt(below * above);
      fit.median_interval_95 = {below, above};
      fit.message = fmt::format("no sample reached the limit state at {:.4g} and all did at {:.4g}: a step (β = 0) "
                                "between them; add levels in between for a dispersion",
                                below, above);
    } else {
      const LevelCount& m = used[mixed_at];
      const double p = static_cast<double>(m.exceeded) / static_cast<double>(m.trials);
      fit.median = m.intensity;
      fit.median_interval_95 = {mixed_at > 0 ? used[mixed_at - 1].intensity : m.intensity,
                                mixed_at + 1 < used.size() ? used[mixed_at + 1].intensity : m.intensity};
      fit.log_likelihood = static_cast<double>(m.exceeded) * std::log(p) +
                           static_cast<double>(m.trials - m.exceeded) * std::log1p(-p);
      fit.message = fmt::format("only the level {:.4g} has both outcomes ({} of {}), all below none, all above every "
                                "sample: the curve is a step there (β → 0); add levels around it for a dispersion",
                                m.intensity, m.exceeded, m.trials);
    }
    return fit;
  }

  Data d;
  double mean_log_x = 0.0;
  for (const LevelCount& l : used) {
    d.log_x.push_back(std::log(l.intensity));
    d.n.push_back(static_cast<double>(l.trials));
    d.k.push_back(static_cast<double>(l.exceeded));
    mean_log_x += std::log(l.intensity) / static_cast<double>(used.size());
  }
  // Probit regression P = Φ(a + b·ln x), whose log-likelihood is concave in (a, b): Newton's method with the exact
  // Hessian, halving steps that do not increase it. Then ln θ = −a/b, β = 1/b.
  const double spread = std::max(d.log_x.back() - d.log_x.front(), 1e-3);
  double b = 2.0 / spread, a = -b * mean_log_x;
  const auto loglik = [&](double a_, double b_) { return b_ > 0.0 ? LogLikelihood(d, -a_ / b_, 1.0 / b_) : -HUGE_VAL; };
  double current = loglik(a, b);
  double h_aa = 0.0, h_ab = 0.0, h_bb = 0.0;
  bool converged = false;
  int iteration = 0;
  for (; iteration < kMaxIterations && !converged; ++iteration) {
    double g_a = 0.0, g_b = 0.0;
    h_aa = h_ab = h_bb = 0.0;
    for (std::size_t i = 0; i < d.log_x.size(); ++i) {
      const double eta = a + b * d.log_x[i];
      const double up = gsl_sf_hazard(-eta), down = gsl_sf_hazard(eta);  // φ/Φ(η), φ/Φ(−η)
      const double first = d.k[i] * up - (d.n[i] - d.k[i]) * down;
      const double second = -d.k[i] * up * (eta + up) - (d.n[i] - d.k[i]) * down * (down - eta);
      g_a += first;
      g_b += first * d.log_x[i];
      h_aa += second;
      h_ab += second * d.log_x[i];
      h_bb += second * d.log_x[i] * d.log_x[i];
    }
    const double det = h_aa * h_bb - h_ab * h_ab;
    if (!(det > 0.0) || !std::isfinite(det)) break;
    const double da = -(h_bb * g_a - h_ab * g_b) / det, db = -(-h_ab * g_a + h_aa * g_b) / det;
    const double size = std::abs(da) + std::abs(db) * std::max(1.0, std::abs(mean_log_x));
    if (size < kStepTolerance) {
      converged = true;
      break;
    }
    double step = 1.0, next = loglik(a + da, b + db);
    while (!(next >= current) && step > kMinStep) {
      step *= 0.5;
      next = loglik(a + step * da, b + step * db);
    }
    if (!(next > current)) {
      converged = size < kRoundOffStep;  // at the optimum up to the round-off of the sum
      break;
    }
    a += step * da;
    b += step * db;
    current = next;
  }
  fit.iterations = iteration;
  const double det = h_aa * h_bb - h_ab * h_ab;
  if (!converged || !(b > 0.0) || !std::isfinite(a) || !(det > 0.0)) {
    fit.status = LognormalFitStatus::kNotConverged;
    fit.message = fmt::format("the likelihood maximisation did not converge in {} Newton steps", iteration);
    return fit;
  }
  // Observed information −H in (a, b), carried to (ln θ, β) by the Jacobian of (−a/b, 1/b).
  const double var_a = -h_bb / det, var_b = -h_aa / det, cov_ab = h_ab / det;
  const double j11 = -1.0 / b, j12 = a / (b * b), j22 = -1.0 / (b * b);
  const double var_mu = j11 * j11 * var_a + 2.0 * j11 * j12 * cov_ab + j12 * j12 * var_b;
  const double var_beta = j22 * j22 * var_b;
  const double cov = j11 * j22 * cov_ab + j12 * j22 * var_b;
  const double mu = -a / b;
  const double se_mu = std::sqrt(var_mu);
  fit.median = std::exp(mu);
  fit.beta = 1.0 / b;
  fit.log_likelihood = current;
  fit.status = LognormalFitStatus::kOk;
  fit.median_std_error = fit.median * se_mu;  // delta method through ln θ
  fit.beta_std_error = std::sqrt(var_beta);
  fit.correlation = cov / (se_mu * fit.beta_std_error);
  fit.median_interval_95 = {std::exp(mu - kZ95 * se_mu), std::exp(mu + kZ95 * se_mu)};
  fit.message = "maximum likelihood; standard errors from the observed information";
  return fit;
}

}  // namespace rockfit::quake
