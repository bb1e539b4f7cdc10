#include "rockfit/io/avrf.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rocking_signals.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

using testing::ChatzisAvrfAboutY;
using testing::PaperLikeBlock;
using testing::PlanarRockingSpec;
using testing::SimulatePlanarRocking;

// The targets of docs/design.md §12: r_Cha(λ) to 2e-3 without noise and 1e-2 with realistic IMU errors.
constexpr double kCleanAvrfTolerance = 2e-3;
constexpr double kNoisyAvrfTolerance = 1e-2;

AvrfResult AvrfOf(const core::Block& block, const testing::MeasuredRecording& measured, AvrfOptions options = {}) {
  const DriftCorrection c = CorrectDrift(measured.recording, {});
  return ComputeAvrf(measured.recording.t_s, c, block, options);
}

TEST(Avrf, RecoversChatzisAvrfWithoutNoiseForSeveralLambdas) {
  const core::Block block = PaperLikeBlock();
  for (double lambda : {0.2, 0.6, 1.0}) {
    PlanarRockingSpec spec;
    spec.lambda = lambda;
    spec.duration_s = 8.0;
    const auto motion = SimulatePlanarRocking(block, spec);
    const AvrfResult r = AvrfOf(block, testing::MeasurePlanar(motion, spec.rate_hz, testing::LinearDriftOnly()));
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.peaks_used, 10u);
    EXPECT_EQ(r.ratios.size(), 9u);
    EXPECT_NEAR(r.avrf, ChatzisAvrfAboutY(block, lambda), kCleanAvrfTolerance) << "λ = " << lambda;
    // The peaks are the true ones from energy conservation.
    for (std::size_t i = 0; i < r.peaks_used; ++i) EXPECT_NEAR(r.peak_angles_rad[i], motion.peak_angles_rad[i], 2e-5);
  }
}

TEST(Avrf, RecoversChatzisAvrfWithRealisticNoise) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(block, spec);
  for (std::uint32_t seed : {1u, 2u, 3u, 4u, 5u}) {
    const AvrfResult r = AvrfOf(block, testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu(seed)));
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_NEAR(r.avrf, motion.r, kNoisyAvrfTolerance) << "seed " << seed;
  }
}

TEST(Avrf, LambdaEquivalentSatisfiesEquationSix) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.lambda = 0.35;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(block, spec);
  const AvrfResult r = AvrfOf(block, testing::MeasurePlanar(motion, spec.rate_hz, {}));
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r.lambda_equivalent.has_value());
  EXPECT_NEAR(ChatzisAvrfAboutY(block, *r.lambda_equivalent), r.avrf, 1e-14);
  EXPECT_NEAR(*r.lambda_equivalent, 0.35, 1e-4);
}

TEST(Avrf, RatiosFollowFromTheUpliftOfTheCom) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(block, spec);
  const AvrfResult r = AvrfOf(block, testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu()));
  ASSERT_TRUE(r.ok());
  for (std::size_t i = 0; i < r.peaks_used; ++i) {
    const double phi = r.peak_angles_rad[i];
    EXPECT_DOUBLE_EQ(r.uplifts_m[i], block.b1() * std::sin(phi) - block.h() * (1 - std::cos(phi)));
  }
  for (std::size_t i = 0; i + 1 < r.peaks_used; ++i) {
    EXPECT_DOUBLE_EQ(r.ratios[i], std::sqrt(r.uplifts_m[i + 1] / r.uplifts_m[i]));
  }
  std::vector<double> sorted = r.ratios;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_DOUBLE_EQ(r.avrf, sorted[sorted.size() / 2]);  // nine ratios: the fifth
}

TEST(Avrf, PaperPrintedFormulaIsAvailableAndDiffers) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(block, spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, {});
  AvrfOptions paper;
  paper.uplift = UpliftFormula::kPaperPrinted;
  const AvrfResult r = AvrfOf(block, measured, paper);
  ASSERT_TRUE(r.ok());
  for (std::size_t i = 0; i < r.peaks_used; ++i) {
    const double phi = r.peak_angles_rad[i];
    EXPECT_DOUBLE_EQ(r.uplifts_m[i], block.h() * std::sin(phi) - block.b1() * (1 - std::cos(phi)));
  }
  // With h = 4·b1 the printed u ≈ h·φ is nearly proportional to φ while the true u = b1·φ − h·φ²/2 … falls
  // faster than φ: the two disagree by more than the noise tolerance.
  EXPECT_GT(std::abs(r.avrf - motion.r), kNoisyAvrfTolerance);
}

TEST(Avrf, TooFewPeaksIsAStatusWithAMessage) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.max_impacts = 3;  // three impacts: two bracketed peaks
  const auto motion = SimulatePlanarRocking(block, spec);
  const AvrfResult r = AvrfOf(block, testing::MeasurePlanar(motion, spec.rate_hz, {}));
  EXPECT_EQ(r.status, AvrfStatus::kTooFewPeaks);
  EXPECT_EQ(r.peaks_used, 2u);
  EXPECT_FALSE(r.lambda_equivalent.has_value());
  EXPECT_NE(r.message.find("only 2 peak"), std::string::npos) << r.message;
  EXPECT_STREQ(ToString(r.status), "too_few_peaks");
}

TEST(Avrf, WrongBlockGeometryGivesInvalidUplift) {
  // A block far too slender for the measured inclinations: φ ≈ 0.155 rad > 2·atan(b1/h) makes u < 0.
  const core::Block slender = core::Block::FromDensity(0.005, 0.05, 0.5, 2692.0);
  PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  const AvrfResult r = AvrfOf(slender, testing::MeasurePlanar(motion, spec.rate_hz, {}));
  EXPECT_EQ(r.status, AvrfStatus::kInvalidUplift);
  EXPECT_NE(r.message.find("b1 = 0.005"), std::string::npos) << r.message;
}

TEST(Avrf, NoImpactIsAStatus) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.release_s = 100.0;
  const auto motion = SimulatePlanarRocking(block, spec);
  const AvrfResult r = AvrfOf(block, testing::MeasurePlanar(motion, spec.rate_hz, {}));
  EXPECT_EQ(r.status, AvrfStatus::kNoImpact);
}

TEST(Avrf, OptionsAreValidated) {
  AvrfOptions bad;
  bad.min_peaks = 11;
  EXPECT_THROW(bad.Validate(), InvalidArgument);
  bad = {};
  bad.max_peaks = 1;
  EXPECT_THROW(bad.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
