// FitCampaign (fit_campaign.hpp) over a few small synthetic trials: one callback per trial, every trial committed
// to the file with the campaign tables, a resumed campaign skipping what the file holds with the same settings,
// failures isolated with their exception, options and outputs checked before any work.
#include "rockfit/fitting/fit_campaign.hpp"

#include <map>
#include <mutex>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "campaign_trials.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "scratch_dir.hpp"

namespace rockfit::fitting {
namespace {

using testing::QuickCampaignTrial;
using testing::ScratchDir;

std::vector<CampaignTrial> ThreeTrials(const std::string& settings,
                                       std::map<std::string, std::shared_ptr<std::atomic<int>>>* prepared = nullptr) {
  std::vector<CampaignTrial> trials;
  const std::pair<const char*, const char*> ids[] = {{"T1", "A"}, {"T2", "A"}, {"T3", "B"}};
  std::uint64_t seed = 11;
  for (const auto& [id, position] : ids) {
    auto count = std::make_shared<std::atomic<int>>(0);
    if (prepared) (*prepared)[id] = count;
    trials.push_back(QuickCampaignTrial(id, position, seed++, settings, count));
  }
  return trials;
}

CampaignOptions TwoThreads(bool resume = false) {
  CampaignOptions options;
  options.num_threads = 2;
  options.resume = resume;
  options.rockfit_version = "test";
  return options;
}

TEST(FitCampaign, CallbackRunsOncePerTrialAndEveryTrialIsCommitted) {
  const ScratchDir dir("fit_campaign_callback");
  std::mutex mutex;
  std::multiset<std::string> called;
  const CampaignSummary s = FitCampaign(ThreeTrials("quick"), dir / "fits.h5", TwoThreads(),
                                        [&](const TrialOutcome& o, double elapsed_s) {
                                          std::lock_guard<std::mutex> lock(mutex);
                                          called.insert(o.trial);
                                          EXPECT_GE(elapsed_s, 0.0);
                                          EXPECT_NE(o.status, TrialStatus::kSkipped);
                                        });
  EXPECT_EQ(called, (std::multiset<std::string>{"T1", "T2", "T3"}));
  ASSERT_EQ(s.trials.size(), 3u);
  EXPECT_EQ(s.trials[0].trial, "T1") << "outcomes in the order given";
  EXPECT_EQ(s.trials[2].trial, "T3");
  EXPECT_EQ(s.fitted + s.failed, 3u);
  EXPECT_EQ(s.skipped, 0u);
  ASSERT_EQ(s.groups.size(), 2u) << "the group tables of the last commit hold every trial";
  EXPECT_EQ(s.groups[0].n + s.groups[1].n, 3);
  const io::hdf5::File file = io::hdf5::File::Open(dir / "fits.h5");
  EXPECT_EQ(StoredFitTrials(file.Root()), (std::vector<std::string>{"T1", "T2", "T3"}));
  EXPECT_EQ(file.Root().ReadStrings("summary/fits/per_trial/trial").size(), 3u);
  EXPECT_EQ(file.Root().GetString("rockfit_version"), "test");
}

TEST(FitCampaign, ResumeSkipsAStoredTrialWithTheSameSettingsHashAndRefitsOneWithAnother) {
  const ScratchDir dir("fit_campaign_resume");
  const std::filesystem::path path = dir / "fits.h5";
  FitCampaign(ThreeTrials("quick"), path, TwoThreads());
  const std::map<std::string, std::string> before = StoredSettingsHashes(path);

  std::map<std::string, std::shared_ptr<std::atomic<int>>> prepared;
  std::vector<CampaignTrial> trials = ThreeTrials("quick", &prepared);
  trials[1].settings = [] { return std::string("quick; other bounds"); };
  const CampaignSummary s = FitCampaign(trials, path, TwoThreads(/*resume=*/true));
  EXPECT_EQ(s.trials[0].status, TrialStatus::kSkipped);
  EXPECT_EQ(s.trials[2].status, TrialStatus::kSkipped);
  EXPECT_NE(s.trials[1].status, TrialStatus::kSkipped);
  EXPECT_EQ(s.skipped, 2u);
  EXPECT_EQ(prepared.at("T1")->load(), 0) << "a skipped trial is not even loaded";
  EXPECT_EQ(prepared.at("T2")->load(), 1);
  const std::map<std::string, std::string> after = StoredSettingsHashes(path);
  EXPECT_EQ(after.at("T1"), before.at("T1"));
  EXPECT_EQ(after.at("T2"), SettingsHash("quick; other bounds"));

  // Without resume every trial is fitted again.
  const CampaignSummary again = FitCampaign(ThreeTrials("quick", &prepared), path, TwoThreads(/*resume=*/false));
  EXPECT_EQ(again.skipped, 0u);
  EXPECT_EQ(prepared.at("T1")->load(), 1);
}

TEST(FitCampaign, FailingTrialKeepsItsExceptionAndLeavesTheOthersCommitted) {
  const ScratchDir dir("fit_campaign_failure");
  std::vector<CampaignTrial> trials = ThreeTrials("quick");
  trials[1].prepare = []() -> PreparedTrial { throw BadInput("T2.txt: no samples"); };
  const CampaignSummary s = FitCampaign(trials, dir / "fits.h5", TwoThreads());
  EXPECT_EQ(s.trials[1].status, TrialStatus::kFailed);
  EXPECT_FALSE(s.trials[1].ok());
  EXPECT_EQ(s.trials[1].message, "T2.txt: no samples");
  EXPECT_THROW(std::rethrow_exception(s.trials[1].error), BadInput);
  EXPECT_GE(s.failed, 1u);
  const io::hdf5::File file = io::hdf5::File::Open(dir / "fits.h5");
  EXPECT_EQ(StoredFitTrials(file.Root()), (std::vector<std::string>{"T1", "T3"}));
}

TEST(FitCampaign, BadOptionsAndAnUnwritableOutputFailBeforeAnyTrialIsPrepared) {
  const ScratchDir dir("fit_campaign_checks");
  CampaignOptions negative;
  negative.num_threads = -1;
  EXPECT_THROW(negative.Validate(), InvalidArgument);
  std::map<std::string, std::shared_ptr<std::atomic<int>>> prepared_bad_options, prepared_bad_output;
  EXPECT_THROW(FitCampaign(ThreeTrials("quick", &prepared_bad_options), dir / "fits.h5", negative), InvalidArgument);
  dir.Write("notes.h5", "not an HDF5 file\n");
  EXPECT_THROW(FitCampaign(ThreeTrials("quick", &prepared_bad_output), dir / "notes.h5", TwoThreads()), OutputError);
  for (const auto* prepared : {&prepared_bad_options, &prepared_bad_output}) {
    for (const auto& [id, count] : *prepared) EXPECT_EQ(count->load(), 0) << id;
  }
}

}  // namespace
}  // namespace rockfit::fitting
