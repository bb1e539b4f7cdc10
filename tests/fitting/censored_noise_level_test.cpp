// The noise level of a fit with clipped gyro samples (censored_noise_level.hpp): the maximum-likelihood σ of a
// censored normal model, checked against a brute-force maximisation of the same likelihood written
// independently (log Φ by std::erfc, a dense grid and a golden-section refinement in σ), against the truth of
// simulated censored normals (fixed seeds), and in the limit without censoring, where it must be today's
// S/dof to the last digit.
#include "rockfit/fitting/censored_noise_level.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace rockfit::fitting {
namespace {

// Relative tolerance of the brute-force maximiser: its golden section stops at 1e-10 of σ, and the likelihood
// is flat at the top, so the two maximisers agree to about that.
constexpr double kBruteForceRelTol = 1e-7;

double LogNormalCdf(double z) { return std::log(0.5 * std::erfc(-z / std::sqrt(2.0))); }

// The log-likelihood in σ with ν in place of the count of the plain residuals (the header's L, in σ).
double LogLikelihood(double sigma, double sum_sq, double dof, const std::vector<double>& margins) {
  double l = -dof * std::log(sigma) - 0.5 * sum_sq / (sigma * sigma);
  for (double m : margins) l += LogNormalCdf(m / sigma);
  return l;
}

// σ² maximising LogLikelihood: the best of a log-spaced grid over [σ_lo, σ_hi], then golden section about it.
double BruteForceVariance(double sum_sq, double dof, const std::vector<double>& margins, double sigma_lo, double sigma_hi) {
  const int n = 4000;
  double best = sigma_lo, best_l = -INFINITY;
  for (int i = 0; i <= n; ++i) {
    const double s = sigma_lo * std::pow(sigma_hi / sigma_lo, static_cast<double>(i) / n);
    const double l = LogLikelihood(s, sum_sq, dof, margins);
    if (l > best_l) {
      best_l = l;
      best = s;
    }
  }
  const double step = std::pow(sigma_hi / sigma_lo, 1.0 / n);
  double a = best / step, b = best * step;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  while (b - a > 1e-10 * best) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (LogLikelihood(c, sum_sq, dof, margins) > LogLikelihood(d, sum_sq, dof, margins)) {
      b = d;
    } else {
      a = c;
    }
  }
  const double s = 0.5 * (a + b);
  return s * s;
}

struct CensoredSample {
  double sum_sq = 0.0;
  double observed = 0.0;
  std::vector<double> margins;
};

// n draws y = μ + e, e ~ N(0, σ²), μ uniform in [−μ_max, μ_max]; y ≥ rail is censored (only "y ≥ rail" is known, with
// the margin μ − rail), the rest observed with residual y − μ.
CensoredSample DrawCensored(std::uint64_t seed, int n, double sigma, double rail, double mu_max = 1.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mean(-mu_max, mu_max);
  std::normal_distribution<double> noise(0.0, sigma);
  CensoredSample c;
  for (int i = 0; i < n; ++i) {
    const double mu = mean(rng), y = mu + noise(rng);
    if (y >= rail) {
      c.margins.push_back(mu - rail);
    } else {
      c.sum_sq += (y - mu) * (y - mu);
      c.observed += 1.0;
    }
  }
  return c;
}

TEST(CensoredNoiseLevel, WithoutCensoredComponentsItIsTheSumOfSquaresOverTheDegreesOfFreedomExactly) {
  for (double sum_sq : {0.0, 1e-9, 0.37, 1234.5}) {
    for (double dof : {1.0, 17.0, 4893.0}) {
      EXPECT_EQ(CensoredNoiseVariance(sum_sq, dof, {}), sum_sq / dof);
    }
  }
  EXPECT_TRUE(std::isnan(CensoredNoiseVariance(1.0, 0.0, {})));
}

TEST(CensoredNoiseLevel, MaximisesTheCensoredLikelihoodAsABruteForceSearchDoes) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    for (double rail : {0.2, 0.8}) {
      const CensoredSample c = DrawCensored(seed, 600, 0.3, rail);
      ASSERT_FALSE(c.margins.empty());
      for (double p : {0.0, 5.0}) {
        const double dof = c.observed - p;
        const double fast = CensoredNoiseVariance(c.sum_sq, dof, c.margins);
        const double brute = BruteForceVariance(c.sum_sq, dof, c.margins, 0.01, 10.0);
        EXPECT_NEAR(fast, brute, kBruteForceRelTol * brute) << seed << " " << rail << " " << p;
      }
    }
  }
}

TEST(CensoredNoiseLevel, RecoversTheNoiseOfCensoredNormalsWhereTheUncensoredCountIsBiasedLow) {
  // Every mean half a σ below the rail: the draws above it (the largest positive errors, 31 %) are censored, and
  // the rest's RMS is √(1 − aφ(a)/Φ(a))·σ ≈ 0.86 σ (a = 0.5); the censored likelihood recovers σ.
  const double sigma = 0.5;
  const CensoredSample c = DrawCensored(26, 20000, sigma, 0.5 * sigma, 0.0);
  const double censored = std::sqrt(CensoredNoiseVariance(c.sum_sq, c.observed, c.margins));
  const double uncensored = std::sqrt(c.sum_sq / c.observed);
  // 20 000 draws: the standard error of σ is below 1 %; 3 % is far outside the scatter, 0.9 σ far above 0.86 σ's.
  EXPECT_NEAR(censored, sigma, 0.03 * sigma);
  EXPECT_LT(uncensored, 0.9 * sigma);
}

TEST(CensoredNoiseLevel, AComponentFarBeyondTheRailCountsNowhereAndOneFarShortCountsItsMargin) {
  const double sum_sq = 50.0, dof = 5000.0;
  // Far beyond the rail (z ≈ 10⁴ at σ ≈ 0.1): no information, σ² as without it.
  EXPECT_NEAR(CensoredNoiseVariance(sum_sq, dof, {1e3, 2e3}), sum_sq / dof, 1e-15);
  // Far short (z ≈ −69): log Φ(z) = −z²/2 − log|z| − log√(2π) + O(z⁻²), so the stationary point has
  // (S + m²)/σ² = ν − 1: the margin counts as a residual and takes a degree of freedom away (a plain residual of
  // that size would add one).
  const double m = -30.0;
  const double v = CensoredNoiseVariance(sum_sq, dof, {m});
  EXPECT_NEAR(v, (sum_sq + m * m) / (dof - 1.0), 1e-4 * v);
  EXPECT_GT(v, (sum_sq + m * m) / (dof + 1.0));
}

TEST(CensoredNoiseLevel, TheInverseMillsRatioIsContinuousAndHasItsKnownValues) {
  EXPECT_NEAR(InverseMillsRatio(0.0), 2.0 / std::sqrt(2.0 * M_PI), 1e-15);
  EXPECT_NEAR(InverseMillsRatio(8.0), 0.0, 1e-14);
  // Either side of the switch to the continued fraction, against the direct ratio where erfc is still exact.
  for (double z : {-19.999, -20.0, -20.001, -25.0, -30.0}) {
    const double direct = std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI) / (0.5 * std::erfc(-z / std::sqrt(2.0)));
    EXPECT_NEAR(InverseMillsRatio(z), direct, 1e-12 * direct) << z;
  }
  // Far out: λ(z) = |z| + 1/|z| − 2/|z|³ + …
  EXPECT_NEAR(InverseMillsRatio(-1e4), 1e4 + 1e-4, 1e-9);
}

ErrorNodes NodesWithRail(int n, double rail, const std::vector<Eigen::Vector3d>& w_m) {
  ErrorNodes nodes;
  for (int k = 0; k < n; ++k) {
    nodes.t_s.push_back(0.004 * k);
    nodes.t_after_release_s.push_back(0.004 * k);
    nodes.w_m_B.push_back(w_m[static_cast<std::size_t>(k)]);
    nodes.weight_s.push_back(k == 0 || k == n - 1 ? 0.002 : 0.004);
    std::uint8_t axes = 0;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(w_m[static_cast<std::size_t>(k)][a]) >= rail) axes = static_cast<std::uint8_t>(axes | (1u << a));
    }
    nodes.censored_axes.push_back(axes);
    if (axes != 0) ++nodes.num_censored;
  }
  return nodes;
}

TEST(CensoredNoiseLevel, TheFactorIsExactlyOneWithoutClippedNodesAndFollowsTheLikelihoodWithThem) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  const int n = 400;
  std::vector<Eigen::Vector3d> model(n), measured(n);
  for (int k = 0; k < n; ++k) {
    model[static_cast<std::size_t>(k)] = Eigen::Vector3d(0.1 * std::sin(0.05 * k), 1.2 * std::sin(0.03 * k), 0.0);
    measured[static_cast<std::size_t>(k)] = model[static_cast<std::size_t>(k)] + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  }
  const ErrorNodes plain = NodesWithRail(n, 10.0, measured);
  ASSERT_EQ(plain.num_censored, 0u);
  EXPECT_EQ(CensoredNoiseFactor(plain, model, 5), 1.0);

  // Clip ω_y at 1.0: the clipped nodes' measured value is the rail, the model is beyond it or short of it.
  std::vector<Eigen::Vector3d> clipped = measured;
  for (Eigen::Vector3d& w : clipped) w.y() = std::clamp(w.y(), -1.0, 1.0);
  const ErrorNodes railed = NodesWithRail(n, 1.0, clipped);
  ASSERT_GT(railed.num_censored, 20u);
  const CensoredResiduals c = CollectCensoredResiduals(railed, model);
  EXPECT_EQ(c.censored_margins.size(), railed.num_censored);
  EXPECT_EQ(c.observed_components, 3u * n - railed.num_censored);
  const double p = 5.0;
  const double expected = CensoredNoiseVariance(c.observed_sum_sq, c.observed_components - p, c.censored_margins) /
                          (c.misfit_sum_sq / (static_cast<double>(c.misfit_components) - p));
  EXPECT_DOUBLE_EQ(CensoredNoiseFactor(railed, model, 5), expected);
  // The brute force on the same split.
  const double brute = BruteForceVariance(c.observed_sum_sq, c.observed_components - p, c.censored_margins, 1e-5, 1.0);
  EXPECT_NEAR(CensoredNoiseVariance(c.observed_sum_sq, c.observed_components - p, c.censored_margins), brute,
              kBruteForceRelTol * brute);
}

}  // namespace
}  // namespace rockfit::fitting
