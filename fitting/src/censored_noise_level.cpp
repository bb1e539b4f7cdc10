#include "rockfit/fitting/censored_noise_level.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockfit::fitting {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// 1/√(2π): the normal density at 0.
constexpr double kInvSqrt2Pi = 0.398942280401432677939946;
// Below this z, Φ(z) = erfc(−z/√2)/2 (about 3·10⁻¹⁰⁰ at −21) loses relative accuracy towards its underflow
// near −37; the continued fraction of the Mills ratio converges there in a few terms.
constexpr double kMillsContinuedFractionBelow = -20.0;
// Terms of that continued fraction: at |z| ≥ 20 its error after 40 terms is below round-off.
constexpr int kMillsTerms = 40;
// The root in θ = 1/σ is taken as found when its bracket is narrower than this fraction of θ: σ² to ~10⁻¹³,
// far below the statistical scatter of any noise level.
constexpr double kRelativeBracket = 5e-14;
// Newton/bisection steps and bracket doublings at most (the bracket halves at least every other step).
constexpr int kMaxIterations = 400;
constexpr int kMaxDoublings = 200;

// L′(θ) and L″(θ) of the header.
struct Slope {
  double first = 0.0, second = 0.0;
};

Slope LikelihoodSlope(double theta, double sum_sq, double dof, const std::vector<double>& margins) {
  Slope s;
  s.first = dof / theta - theta * sum_sq;
  s.second = -dof / (theta * theta) - sum_sq;
  for (double m : margins) {
    const double z = theta * m;
    const double lambda = InverseMillsRatio(z);
    s.first += m * lambda;
    s.second -= m * m * lambda * (z + lambda);  // λ′(z) = −λ(z)·(z + λ(z)) ≤ 0
  }
  return s;
}

}  // namespace

double InverseMillsRatio(double z) {
  if (z >= kMillsContinuedFractionBelow) {
    const double density = kInvSqrt2Pi * std::exp(-0.5 * z * z);
    return density / (0.5 * std::erfc(-z / std::sqrt(2.0)));
  }
  // Φ(z)/φ(z) = R(x), x = −z, the Mills ratio: R(x) = 1/(x + 1/(x + 2/(x + 3/(x + …)))), evaluated backwards.
  const double x = -z;
  double tail = x;
  for (int k = kMillsTerms; k >= 1; --k) tail = x + static_cast<double>(k) / tail;
  return tail;  // 1/R(x)
}

CensoredResiduals CollectCensoredResiduals(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B) {
  CensoredResiduals c;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const double w = nodes.weight_s[k];
    if (w == 0.0) continue;
    const std::uint8_t censored = nodes.censored_axes.empty() ? 0 : nodes.censored_axes[k];
    const std::uint8_t satisfied = SatisfiedCensoredAxes(nodes, k, w_s_B[k]);
    const Eigen::Vector3d misfit = NodeMisfit(nodes, k, w_s_B[k]);
    for (int a = 0; a < 3; ++a) {
      const double r2 = w * misfit[a] * misfit[a];
      if ((satisfied & (1u << a)) == 0) {
        c.misfit_sum_sq += r2;
        ++c.misfit_components;
      }
      if ((censored & (1u << a)) != 0) {
        const double sense = nodes.w_m_B[k][a] >= 0.0 ? 1.0 : -1.0;
        c.censored_margins.push_back(std::sqrt(w) * sense * (w_s_B[k][a] - nodes.w_m_B[k][a]));
      } else {
        c.observed_sum_sq += r2;
        ++c.observed_components;
      }
    }
  }
  return c;
}

double CensoredNoiseVariance(double observed_sum_sq, double degrees_of_freedom, const std::vector<double>& margins) {
  if (!(degrees_of_freedom > 0.0)) return kNaN;
  const double uncensored = observed_sum_sq / degrees_of_freedom;
  if (margins.empty()) return uncensored;
  // Start at the uncensored answer (or, without plain residuals, at the scale of the margins) and double or
  // halve θ until L′ changes sign; L′ decreases in θ, from +∞ at 0 (ν > 0) to below 0 for large θ.
  double scale = 0.0;
  for (double m : margins) scale = std::max(scale, std::abs(m));
  const double theta0 = uncensored > 0.0 ? 1.0 / std::sqrt(uncensored) : (scale > 0.0 ? 1.0 / scale : 0.0);
  if (!(theta0 > 0.0) || !std::isfinite(theta0)) return uncensored;
  double lo = theta0, hi = theta0;
  double slope0 = LikelihoodSlope(theta0, observed_sum_sq, degrees_of_freedom, margins).first;
  if (slope0 == 0.0) return 1.0 / (theta0 * theta0);
  int doublings = 0;
  if (slope0 > 0.0) {
    while (LikelihoodSlope(hi, observed_sum_sq, degrees_of_freedom, margins).first > 0.0) {
      lo = hi;
      hi *= 2.0;
      if (++doublings > kMaxDoublings) return kNaN;  // no maximum: every residual 0 and every margin ≥ 0
    }
  } else {
    while (LikelihoodSlope(lo, observed_sum_sq, degrees_of_freedom, margins).first < 0.0) {
      hi = lo;
      lo *= 0.5;
      if (++doublings > kMaxDoublings) return kNaN;
    }
  }
  double theta = 0.5 * (lo + hi);
  for (int i = 0; i < kMaxIterations && hi - lo > kRelativeBracket * hi; ++i) {
    const Slope s = LikelihoodSlope(theta, observed_sum_sq, degrees_of_freedom, margins);
    if (s.first == 0.0) break;
    (s.first > 0.0 ? lo : hi) = theta;
    const double newton = s.second < 0.0 ? theta - s.first / s.second : kNaN;
    theta = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
  }
  return 1.0 / (theta * theta);
}

double CensoredNoiseFactor(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                           std::size_t free_parameters) {
  if (nodes.num_censored == 0 || w_s_B.size() != nodes.size()) return 1.0;
  const CensoredResiduals c = CollectCensoredResiduals(nodes, w_s_B);
  if (c.censored_margins.empty()) return 1.0;
  const double p = static_cast<double>(free_parameters);
  const double before_dof = static_cast<double>(c.misfit_components) - p;
  const double dof = static_cast<double>(c.observed_components) - p;
  if (!(before_dof > 0.0) || !(dof > 0.0) || !(c.misfit_sum_sq > 0.0)) return 1.0;
  const double censored = CensoredNoiseVariance(c.observed_sum_sq, dof, c.censored_margins);
  const double factor = censored / (c.misfit_sum_sq / before_dof);
  return std::isfinite(factor) && factor > 0.0 ? factor : 1.0;
}

double CensoredNoiseFactorAt(const Objective& objective, const ParameterSet& at, std::size_t free_parameters) {
  const std::vector<std::uint8_t>& axes = objective.signal().censored_axes;
  if (std::none_of(axes.begin(), axes.end(), [](std::uint8_t a) { return a != 0; })) return 1.0;
  ErrorNodes nodes;
  ModelOutput output;
  const Evaluation e = objective.EvaluateDetailed(at, &nodes, &output);
  if (!e.feasible || output.w_B.size() != nodes.size()) return 1.0;
  return CensoredNoiseFactor(nodes, output.w_B, free_parameters);
}

}  // namespace rockfit::fitting
