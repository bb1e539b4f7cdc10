#include "rockfit/io/trial_metrics.hpp"

#include <gtest/gtest.h>

#include "rocking_signals.hpp"

namespace rockfit::io {
namespace {

TEST(TrialMetrics, PlanarTrialGivesBothMetrics) {
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  spec.duration_s = 8.0;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, testing::RealisticImu());
  const MetricsSummary s = ComputeTrialMetrics(measured.recording, block, {});
  EXPECT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(s.status, "ok");
  EXPECT_TRUE(s.opmf.ok());
  EXPECT_TRUE(s.avrf.ok());
  EXPECT_NEAR(s.avrf.avrf, motion.r, 1e-2);
}

TEST(TrialMetrics, WithoutABlockOnlyTheOpmfIsComputed) {
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  const auto measured = testing::MeasurePlanar(motion, spec.rate_hz, {});
  const MetricsSummary s = ComputeTrialMetrics(measured.recording, std::nullopt, {});
  EXPECT_TRUE(s.opmf.ok());
  EXPECT_EQ(s.avrf.status, AvrfStatus::kNoBlock);
  EXPECT_EQ(s.status, "no_block");
  EXPECT_NE(s.message.find("--b1"), std::string::npos);
}

TEST(TrialMetrics, TheFirstFailingMetricNamesTheStatus) {
  const core::Block block = testing::PaperLikeBlock();
  testing::PlanarRockingSpec spec;
  spec.release_s = 100.0;
  const auto motion = testing::SimulatePlanarRocking(block, spec);
  const MetricsSummary s = ComputeTrialMetrics(testing::MeasurePlanar(motion, spec.rate_hz, {}).recording, block, {});
  EXPECT_EQ(s.status, "no_impact");
  EXPECT_FALSE(s.message.empty());
}

}  // namespace
}  // namespace rockfit::io
