// The lognormal fragility fit (lognormal_fragility.hpp): recovery of known (θ, β), standard errors against the
// spread of repeated studies, and the statuses of data that give no curve.
#include <cmath>
#include <random>
#include <vector>

#include <gsl/gsl_cdf.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/quake/lognormal_fragility.hpp"

namespace rockfit::quake {
namespace {

const std::vector<double> kLevels{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8};

TEST(LognormalFragility, ExpectedCountsGiveBackTheMedianAndDispersion) {
  const double theta = 0.35, beta = 0.4;
  const std::int64_t n = 1000000;
  std::vector<LevelCount> levels;
  for (double x : kLevels) {
    levels.push_back({x, n, std::llround(static_cast<double>(n) * gsl_cdf_ugaussian_P(std::log(x / theta) / beta))});
  }
  const LognormalFragilityFit fit = FitLognormalFragility(levels);
  ASSERT_EQ(fit.status, LognormalFitStatus::kOk) << fit.message;
  EXPECT_NEAR(fit.median, theta, 1e-5);
  EXPECT_NEAR(fit.beta, beta, 1e-5);
  EXPECT_LT(fit.median_std_error, 1e-3);
  EXPECT_LT(fit.median_interval_95[0], fit.median);
  EXPECT_GT(fit.median_interval_95[1], fit.median);
  EXPECT_NEAR(LognormalFragility(theta, fit.median, fit.beta), 0.5, 1e-4);
}

TEST(LognormalFragility, StandardErrorsMatchTheSpreadOfRepeatedStudies) {
  const double theta = 0.35, beta = 0.4;
  const std::int64_t n = 40;
  std::mt19937_64 engine(20261125);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> medians, betas, se_median, se_beta;
  for (int rep = 0; rep < 400; ++rep) {
    std::vector<LevelCount> levels;
    for (double x : kLevels) {
      const double p = gsl_cdf_ugaussian_P(std::log(x / theta) / beta);
      std::int64_t k = 0;
      for (std::int64_t i = 0; i < n; ++i) k += uniform(engine) < p ? 1 : 0;
      levels.push_back({x, n, k});
    }
    const LognormalFragilityFit fit = FitLognormalFragility(levels);
    if (fit.status != LognormalFitStatus::kOk) continue;
    medians.push_back(fit.median);
    betas.push_back(fit.beta);
    se_median.push_back(fit.median_std_error);
    se_beta.push_back(fit.beta_std_error);
  }
  ASSERT_GT(medians.size(), 390u);
  const auto mean = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s / static_cast<double>(v.size());
  };
  const auto sd = [&](const std::vector<double>& v) {
    const double m = mean(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
  };
  EXPECT_NEAR(mean(medians), theta, 0.01);
  EXPECT_NEAR(mean(betas), beta, 0.03);  // the MLE of β is biased low by O(1/n)
  EXPECT_NEAR(mean(se_median) / sd(medians), 1.0, 0.2);
  EXPECT_NEAR(mean(se_beta) / sd(betas), 1.0, 0.25);
}

TEST(LognormalFragility, DataWithoutACurveSayWhy) {
  EXPECT_EQ(FitLognormalFragility({{0.1, 10, 0}, {0.2, 10, 0}}).status, LognormalFitStatus::kNoExceedance);
  EXPECT_EQ(FitLognormalFragility({{0.1, 10, 10}, {0.2, 10, 10}}).status, LognormalFitStatus::kAllExceeded);
  EXPECT_EQ(FitLognormalFragility({{0.1, 10, 3}, {0.2, 0, 0}}).status, LognormalFitStatus::kTooFewLevels);
  const LognormalFragilityFit step = FitLognormalFragility({{0.1, 10, 0}, {0.2, 10, 0}, {0.4, 10, 10}, {0.8, 10, 10}});
  EXPECT_EQ(step.status, LognormalFitStatus::kSeparated);
  EXPECT_DOUBLE_EQ(step.median, std::sqrt(0.2 * 0.4));
  EXPECT_EQ(step.beta, 0.0);
  EXPECT_EQ(step.median_interval_95[0], 0.2);
  EXPECT_EQ(step.median_interval_95[1], 0.4);
  EXPECT_FALSE(step.message.empty());
  EXPECT_THROW(FitLognormalFragility({{0.0, 10, 1}, {0.2, 10, 3}}), InvalidArgument);
  EXPECT_THROW(FitLognormalFragility({{0.1, 10, 11}, {0.2, 10, 3}}), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::quake
