#include "rockfit/io/peak_finding.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

std::vector<std::size_t> Indices(const std::vector<Peak>& peaks) {
  std::vector<std::size_t> out;
  for (const Peak& p : peaks) out.push_back(p.index);
  return out;
}

TEST(PeakFinding, ProminenceIsHeightAboveTheHigherOfTheTwoBases) {
  //                          0  1  2  3  4  5  6  7  8
  const std::vector<double> x{0, 5, 1, 3, 2, 7, 0, 4, 0};
  const std::vector<Peak> peaks = FindPeaks(x, {});
  ASSERT_EQ(Indices(peaks), (std::vector<std::size_t>{1, 3, 5, 7}));
  // Peak 1 (5): left base 0, right base min(1,3,2) = 1 up to the higher 7 → 5 − 1.
  EXPECT_DOUBLE_EQ(peaks[0].prominence, 4.0);
  // Peak 3 (3): bases 1 (left, up to 5) and 2 (right, up to 7) → 3 − 2.
  EXPECT_DOUBLE_EQ(peaks[1].prominence, 1.0);
  // Peak 5 (7): the highest; bases are the minima of each whole side (0 and 0) → 7.
  EXPECT_DOUBLE_EQ(peaks[2].prominence, 7.0);
  // Peak 7 (4): left base 0 (down to the higher 7), right base 0 → 4.
  EXPECT_DOUBLE_EQ(peaks[3].prominence, 4.0);
}

TEST(PeakFinding, ProminenceThresholdDropsSmallBumps) {
  const std::vector<double> x{0, 5, 1, 3, 2, 7, 0, 4, 0};
  PeakOptions options;
  options.min_prominence = 2.0;
  EXPECT_EQ(Indices(FindPeaks(x, options)), (std::vector<std::size_t>{1, 5, 7}));
}

TEST(PeakFinding, MinimumSeparationKeepsTheHigherPeak) {
  const std::vector<double> x{0, 5, 1, 3, 2, 7, 0, 4, 0};
  PeakOptions options;
  options.min_separation_samples = 3;
  // 7 at 5 removes 3 at 3 and 4 at 7 (distance 2 < 3); 5 at 1 is 4 samples from 5 and stays.
  EXPECT_EQ(Indices(FindPeaks(x, options)), (std::vector<std::size_t>{1, 5}));
}

TEST(PeakFinding, FlatTopCountsOnceAtItsMiddleAndEndsAreNeverPeaks) {
  const std::vector<double> x{9, 1, 4, 4, 4, 1, 2, 8};
  EXPECT_EQ(Indices(FindPeaks(x, {})), (std::vector<std::size_t>{3}));
}

TEST(PeakFinding, NonFiniteSamplesAreRejected) {
  EXPECT_THROW(FindPeaks({0.0, NAN, 1.0}, {}), InvalidArgument);
  PeakOptions bad;
  bad.min_prominence = -1.0;
  EXPECT_THROW(FindPeaks({0.0, 1.0, 0.0}, bad), InvalidArgument);
}

TEST(PeakFinding, ParabolicRefinementIsExactForAParabola) {
  // y = 3 − 2 (k − 4.3)²: vertex at 4.3 with value 3.
  std::vector<double> y;
  for (int k = 0; k < 9; ++k) y.push_back(3.0 - 2.0 * (k - 4.3) * (k - 4.3));
  const RefinedPeak refined = RefinePeakParabolic(y, 4);
  EXPECT_NEAR(refined.offset_samples, 0.3, 1e-12);
  EXPECT_NEAR(refined.value, 3.0, 1e-12);
}

TEST(PeakFinding, ParabolicRefinementRemovesTheSamplingBiasOfACosinePeak) {
  // cos sampled 16 times per period with the maximum 0.37 samples off the grid: the sample misses the peak
  // by 1 − cos(2π·0.37/16) ≈ 1e-2, the refined vertex by the O(h⁴) rest.
  const double phase = 0.37;
  std::vector<double> y;
  for (int k = 0; k < 16; ++k) y.push_back(std::cos(2 * M_PI * (k - 8 - phase) / 16.0));
  const RefinedPeak refined = RefinePeakParabolic(y, 8);
  EXPECT_GT(1.0 - y[8], 1e-2);
  EXPECT_LT(std::abs(1.0 - refined.value), 1e-3);
  EXPECT_NEAR(refined.offset_samples, phase, 0.02);
}

}  // namespace
}  // namespace rockfit::io
