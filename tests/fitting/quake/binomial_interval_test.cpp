// Binomial intervals (binomial_interval.hpp) against closed forms, and the exact coverage of Clopper–Pearson.
#include <cmath>

#include <gsl/gsl_randist.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/quake/binomial_interval.hpp"

namespace rockfit::quake {
namespace {

using fitting::Interval;

constexpr double kZ95 = 1.959963984540054;

TEST(BinomialInterval, NoSuccessesGiveTheClosedFormUpperEnds) {
  // Wilson at k = 0: [0, z²/(n + z²)]; Clopper–Pearson: [0, 1 − (α/2)^(1/n)].
  const Interval w = WilsonInterval(0, 10);
  EXPECT_EQ(w[0], 0.0);
  EXPECT_NEAR(w[1], kZ95 * kZ95 / (10.0 + kZ95 * kZ95), 1e-12);
  const Interval cp = ClopperPearsonInterval(0, 10);
  EXPECT_EQ(cp[0], 0.0);
  EXPECT_NEAR(cp[1], 1.0 - std::pow(0.025, 0.1), 1e-10);
  // All successes mirror them, with an upper end of exactly 1.
  const Interval all = ClopperPearsonInterval(10, 10);
  EXPECT_EQ(all[1], 1.0);
  EXPECT_NEAR(all[0], std::pow(0.025, 0.1), 1e-10);
  EXPECT_EQ(WilsonInterval(10, 10)[1], 1.0);
}

TEST(BinomialInterval, HalfSuccessesAreSymmetricAndMatchPublishedValues) {
  // k = 5 of 10: Wilson [0.2366, 0.7634], Clopper–Pearson [0.1871, 0.8129] (standard tables).
  const Interval w = WilsonInterval(5, 10), cp = ClopperPearsonInterval(5, 10);
  EXPECT_NEAR(w[0], 0.23659, 5e-5);
  EXPECT_NEAR(w[0] + w[1], 1.0, 1e-12);
  EXPECT_NEAR(cp[0], 0.18709, 5e-5);
  EXPECT_NEAR(cp[0] + cp[1], 1.0, 1e-12);
}

TEST(BinomialInterval, ClopperPearsonCoversAtLeastTheConfidenceForEveryP) {
  // Exact coverage: Σ_k P(k | n, p) [p ∈ interval(k)], over a grid of p.
  const int n = 30;
  for (double p = 0.01; p < 1.0; p += 0.01) {
    double coverage = 0.0;
    for (int k = 0; k <= n; ++k) {
      const Interval cp = ClopperPearsonInterval(k, n);
      if (cp[0] <= p && p <= cp[1]) coverage += gsl_ran_binomial_pdf(static_cast<unsigned>(k), p, n);
    }
    EXPECT_GE(coverage, 0.95 - 1e-12) << "p = " << p;
  }
}

TEST(BinomialInterval, NoTrialsIsTheWholeRangeAndBadCountsAreRefused) {
  EXPECT_EQ(WilsonInterval(0, 0), (Interval{0.0, 1.0}));
  EXPECT_EQ(ClopperPearsonInterval(0, 0), (Interval{0.0, 1.0}));
  EXPECT_THROW(WilsonInterval(3, 2), InvalidArgument);
  EXPECT_THROW(ClopperPearsonInterval(-1, 2), InvalidArgument);
  EXPECT_THROW(WilsonInterval(1, 2, 1.0), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::quake
