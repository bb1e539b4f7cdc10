// Seeded random streams of the synthetic recordings: standard-defined engine, Box–Muller by definition,
// independent streams, and the moments of the normal variates.
#include "rockfit/io/synth_random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rockfit::io {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

TEST(SynthRandom, SplitMix64MatchesTheReferenceGeneratorSeededWithZero) {
  // First output of Vigna's reference splitmix64.c with state 0.
  EXPECT_EQ(SplitMix64(0), 0xe220a8397b1dcdafULL);
}

TEST(SynthRandom, EngineIsTheStandardMt19937_64) {
  // [rand.predef]: the 10000th output of a default-constructed mt19937_64 is 9981545732273789042.
  std::mt19937_64 engine;
  engine.discard(9999);
  EXPECT_EQ(engine(), 9981545732273789042ULL);
}

TEST(SynthRandom, NormalIsTheBoxMullerTransformOfTwoUniforms) {
  const std::uint64_t seed = 42;
  SynthRandom random(seed, SynthStream::kGyroNoise);
  std::mt19937_64 engine(SplitMix64(seed + static_cast<std::uint64_t>(SynthStream::kGyroNoise)));
  const auto uniform = [&engine] { return static_cast<double>((engine() >> 11) + 1) / 9007199254740992.0; };
  for (int pair = 0; pair < 100; ++pair) {
    const double u1 = uniform();
    const double u2 = uniform();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    EXPECT_EQ(random.Normal(), radius * std::cos(kTwoPi * u2));
    EXPECT_EQ(random.Normal(), radius * std::sin(kTwoPi * u2));
  }
}

TEST(SynthRandom, SameSeedAndStreamRepeatsDifferentStreamsDiffer) {
  SynthRandom a(7, SynthStream::kDriftWalk);
  SynthRandom b(7, SynthStream::kDriftWalk);
  SynthRandom c(7, SynthStream::kAccelNoise);
  SynthRandom d(8, SynthStream::kDriftWalk);
  int equal_c = 0;
  int equal_d = 0;
  for (int i = 0; i < 1000; ++i) {
    const double x = a.Normal();
    EXPECT_EQ(x, b.Normal());
    equal_c += x == c.Normal();
    equal_d += x == d.Normal();
  }
  EXPECT_EQ(equal_c, 0);
  EXPECT_EQ(equal_d, 0);
}

TEST(SynthRandom, UniformNeverReturnsZero) {
  SynthRandom random(3, SynthStream::kHousekeeping);
  for (int i = 0; i < 100000; ++i) {
    const double u = random.Uniform();
    ASSERT_GT(u, 0.0);
    ASSERT_LE(u, 1.0);
  }
}

TEST(SynthRandom, NormalHasZeroMeanAndUnitVarianceWithinSamplingError) {
  constexpr int kCount = 200000;
  SynthRandom random(11, SynthStream::kMagNoise);
  double sum = 0.0;
  double sum_sq = 0.0;
  for (int i = 0; i < kCount; ++i) {
    const double x = random.Normal();
    sum += x;
    sum_sq += x * x;
  }
  const double mean = sum / kCount;
  const double variance = sum_sq / kCount - mean * mean;
  // 4 standard errors: SE(mean) = 1/√N, SE(variance) = √(2/N) for a unit normal.
  EXPECT_NEAR(mean, 0.0, 4.0 / std::sqrt(kCount));
  EXPECT_NEAR(variance, 1.0, 4.0 * std::sqrt(2.0 / kCount));
}

}  // namespace
}  // namespace rockfit::io
