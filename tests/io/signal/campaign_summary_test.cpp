#include "rockfit/io/campaign_summary.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace rockfit::io {
namespace {

TrialRow Row(const std::string& trial, const std::string& block, const std::string& position, std::optional<double> opmf,
             std::optional<double> avrf) {
  TrialRow r;
  r.trial_id = trial;
  r.block_id = block;
  r.position = position;
  r.b2_m = block == "B1" ? 0.03 : 0.06;
  r.opmf = opmf;
  r.avrf = avrf;
  r.status = avrf ? MetricsStatus::kOk : MetricsStatus::kTooFewPeaks;
  return r;
}

TEST(CampaignSummary, GroupsPerBlockAndPositionWithMeanAndSampleStd) {
  const std::vector<TrialRow> rows{
      Row("a", "B1", "A", 0.10, 0.90), Row("b", "B1", "A", 0.20, 0.92), Row("c", "B1", "A", 0.30, std::nullopt),
      Row("d", "B1", "B", 0.05, 0.95), Row("e", "B2", "A", std::nullopt, std::nullopt), Row("f", "B1", "B", 0.07, 0.97)};
  const std::vector<GroupRow> groups = GroupTrials(rows);
  ASSERT_EQ(groups.size(), 3u);
  // B1/A: OPMF {0.1, 0.2, 0.3}: mean 0.2, sample std √(((−0.1)² + 0 + 0.1²)/2) = 0.1; AVRF {0.90, 0.92}.
  EXPECT_EQ(groups[0].block_id, "B1");
  EXPECT_EQ(groups[0].position, "A");
  EXPECT_EQ(groups[0].n_trials, 3u);
  EXPECT_EQ(groups[0].n_opmf, 3u);
  EXPECT_NEAR(*groups[0].opmf_mean, 0.2, 1e-15);
  EXPECT_NEAR(*groups[0].opmf_std, 0.1, 1e-15);
  EXPECT_EQ(groups[0].n_avrf, 2u);
  EXPECT_NEAR(*groups[0].avrf_mean, 0.91, 1e-15);
  EXPECT_NEAR(*groups[0].avrf_std, std::sqrt(2 * 0.01 * 0.01 / 1.0), 1e-15);
  EXPECT_DOUBLE_EQ(groups[0].b2_m, 0.03);
  // B1/B comes after B1/A (positions in order of first appearance), B2/A last.
  EXPECT_EQ(groups[1].position, "B");
  EXPECT_EQ(groups[1].n_trials, 2u);
  EXPECT_EQ(groups[2].block_id, "B2");
  // No values: no mean, no std — never NaN in the struct.
  EXPECT_EQ(groups[2].n_opmf, 0u);
  EXPECT_FALSE(groups[2].opmf_mean.has_value());
  EXPECT_FALSE(groups[2].avrf_std.has_value());
}

TEST(CampaignSummary, OneValueHasAMeanButNoStd) {
  const std::vector<GroupRow> groups = GroupTrials({Row("a", "B1", "A", 0.1, 0.9)});
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_DOUBLE_EQ(*groups[0].avrf_mean, 0.9);
  EXPECT_FALSE(groups[0].avrf_std.has_value());
}

TEST(CampaignSummary, FailedTrialKeepsItsMessage) {
  TrialSpec t;
  t.id = "T9";
  t.position = "A";
  BlockSpec b;
  b.id = "B1";
  b.b2_m = 0.03;
  const TrialRow r = MakeFailedTrialRow(t, b, "raw/T9: no such file");
  EXPECT_EQ(r.status, MetricsStatus::kLoadError);
  EXPECT_EQ(r.message, "raw/T9: no such file");
  EXPECT_FALSE(r.opmf.has_value());
}

}  // namespace
}  // namespace rockfit::io
