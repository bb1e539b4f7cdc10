#include "rockfit/io/impact_consistency.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

// An angle φ(t) = A·sin(2πt) sampled finely, and its rate.
struct Wave {
  std::vector<double> t, rate;
};
Wave SineWave(double amplitude) {
  Wave w;
  for (int k = 0; k <= 4000; ++k) {
    w.t.push_back(k * 1e-3);
    w.rate.push_back(amplitude * 2 * M_PI * std::cos(2 * M_PI * w.t.back()));
  }
  return w;
}

TEST(ImpactConsistency, KeepsTheZerosOfTheAngleAndDropsATiltedInstant) {
  const Wave w = SineWave(0.1);
  // Zeros of 0.1·sin(2πt) at t = 0.5, 1, 1.5, 2, …; t = 1.25 is a crest (φ = 0.1), t = 2.3 a flank.
  const std::vector<double> times{0.5, 1.0, 1.25, 1.5, 2.0, 2.3, 2.5};
  const std::vector<double> strength{1.0, 3.0, 0.5, 1.0, 1.0, 0.5, 1.0};
  EXPECT_EQ(ConsistentZeroInstants(w.t, w.rate, times, strength, {}), (std::vector<std::size_t>{0, 1, 3, 4, 6}));
}

TEST(ImpactConsistency, StartsFromTheStrongestCandidate) {
  const Wave w = SineWave(0.1);
  // The strongest candidate is the crest at 1.25: the zeros are then judged against it and all fail, as the
  // swing from a crest back to zero is the whole amplitude.
  const std::vector<double> times{1.0, 1.25, 1.5};
  EXPECT_EQ(ConsistentZeroInstants(w.t, w.rate, times, {1.0, 9.0, 1.0}, {}), (std::vector<std::size_t>{1}));
}

TEST(ImpactConsistency, GyroBiasWithinTheToleranceIsAccepted) {
  Wave w = SineWave(0.1);
  for (double& r : w.rate) r += 0.005;  // 0.005 rad/s bias: 2.5e-3 rad over 0.5 s, inside 3e-3 rad
  EXPECT_EQ(ConsistentZeroInstants(w.t, w.rate, {0.5, 1.0}, {1.0, 1.0}, {}).size(), 2u);
}

TEST(ImpactConsistency, OptionsAreValidated) {
  ImpactConsistencyOptions bad;
  bad.max_return_fraction = 1.5;
  EXPECT_THROW(bad.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
