// `rockfit metrics` on recordings made from known motion (tests/support/rocking_signals.hpp).
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "rocking_signals.hpp"
#include "synthetic_campaign.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

class CliMetrics : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("cli_metrics");
    trials_ = new std::vector<SyntheticTrial>(WriteSyntheticCampaign(dir_->path(), {0.03, 0.08}, 1));
  }
  static void TearDownTestSuite() {
    delete trials_;
    delete dir_;
  }
  static ScratchDir* dir_;
  static std::vector<SyntheticTrial>* trials_;
};
ScratchDir* CliMetrics::dir_ = nullptr;
std::vector<SyntheticTrial>* CliMetrics::trials_ = nullptr;

TEST_F(CliMetrics, JsonHasTheDocumentedKeysAndRecoversTheAvrf) {
  const SyntheticTrial& t = trials_->front();
  const CommandResult r = RunRockfit({"metrics", t.file.string(), "--b1", "0.05", "--b2", std::to_string(t.b2_m), "--h",
                                      "0.2", "--density", "2692", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  for (const char* key : {"opmf", "avrf", "avrf_ratios", "avrf_peaks_used", "lambda_equivalent", "impact_times", "status"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["avrf_peaks_used"], 10);
  EXPECT_EQ(json["avrf_ratios"].size(), 9u);
  EXPECT_NEAR(json["avrf"].get<double>(), t.r, 1e-2);  // realistic IMU errors: the 1e-2 of docs/design.md §12
  EXPECT_NEAR(json["lambda_equivalent"].get<double>(), t.lambda, 0.15);
  EXPECT_GT(json["impact_times"].size(), 15u);
  EXPECT_GT(json["opmf"].get<double>(), 0.05);
}

TEST_F(CliMetrics, BlockFromTheManifestAndTrialFromTheManifest) {
  const SyntheticTrial& t = trials_->back();
  const auto manifest = (dir_->path() / "campaign.toml").string();
  const CommandResult by_block = RunRockfit({"metrics", t.file.string(), "--manifest", manifest, "--block", t.block_id, "--json"});
  const CommandResult by_trial = RunRockfit({"metrics", manifest, "--trial", t.id, "--json"});
  ASSERT_EQ(by_block.exit_code, 0) << by_block.err;
  ASSERT_EQ(by_trial.exit_code, 0) << by_trial.err;
  EXPECT_EQ(nlohmann::json::parse(by_block.out)["avrf"], nlohmann::json::parse(by_trial.out)["avrf"]);
}

TEST_F(CliMetrics, TableNamesTheMetrics) {
  const auto manifest = (dir_->path() / "campaign.toml").string();
  const CommandResult r = RunRockfit({"metrics", manifest, "--trial", trials_->front().id});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("OPMF"), std::string::npos);
  EXPECT_NE(r.out.find("AVRF"), std::string::npos);
  EXPECT_NE(r.out.find("status     ok"), std::string::npos) << r.out;
}

TEST_F(CliMetrics, PaperUpliftFormulaGivesADifferentAvrf) {
  const auto manifest = (dir_->path() / "campaign.toml").string();
  const auto com = nlohmann::json::parse(RunRockfit({"metrics", manifest, "--trial", trials_->front().id, "--json"}).out);
  const auto paper = nlohmann::json::parse(
      RunRockfit({"metrics", manifest, "--trial", trials_->front().id, "--uplift", "paper", "--json"}).out);
  EXPECT_EQ(paper["uplift_formula"], "paper");
  EXPECT_GT(std::abs(paper["avrf"].get<double>() - com["avrf"].get<double>()), 1e-3);
}

TEST_F(CliMetrics, WithoutABlockItIsAUsageError) {
  const CommandResult r = RunRockfit({"metrics", trials_->front().file.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--b1"), std::string::npos) << r.err;
}

TEST_F(CliMetrics, TooFewPeaksIsExitCodeThreeWithAStatus) {
  const auto manifest = (dir_->path() / "campaign.toml").string();
  const CommandResult r = RunRockfit({"metrics", manifest, "--trial", trials_->front().id, "--min-peaks", "10", "--peaks",
                                      "10", "--min-prominence", "1.0", "--json"});
  // With a 1 rad/s prominence only the first few impacts count: fewer than ten peaks lie between them.
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["status"], "too_few_peaks");
  EXPECT_TRUE(json["avrf"].is_null());
  EXPECT_FALSE(r.err.empty());
}

TEST_F(CliMetrics, MissingFileOrTrialIsBadInput) {
  const CommandResult missing = RunRockfit({"metrics", (dir_->path() / "nope.h5").string(), "--b1", "0.05", "--b2", "0.05",
                                            "--h", "0.2", "--mass", "10"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope.h5"), std::string::npos) << missing.err;
  const auto manifest = (dir_->path() / "campaign.toml").string();
  const CommandResult unknown = RunRockfit({"metrics", manifest, "--trial", "B9-A-1"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("no trial 'B9-A-1'"), std::string::npos) << unknown.err;
  const CommandResult bad_block = RunRockfit({"metrics", trials_->front().file.string(), "--manifest", manifest, "--block", "B7"});
  EXPECT_EQ(bad_block.exit_code, 2);
  EXPECT_NE(bad_block.err.find("no block 'B7'; known blocks: B1, B2"), std::string::npos) << bad_block.err;
}

}  // namespace
}  // namespace rockfit::testing
