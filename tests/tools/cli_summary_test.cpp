// `rockfit summary` on a synthetic campaign: per-trial and per-(block, position) tables, HDF5 and CSV outputs.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "python_h5py.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_transaction.hpp"
#include "synthetic_campaign.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

class CliSummary : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("cli_summary");
    trials_ = new std::vector<SyntheticTrial>(WriteSyntheticCampaign(dir_->path()));
  }
  static void TearDownTestSuite() {
    delete trials_;
    delete dir_;
  }
  static std::string Manifest() { return (dir_->path() / "campaign.toml").string(); }
  static ScratchDir* dir_;
  static std::vector<SyntheticTrial>* trials_;
};
ScratchDir* CliSummary::dir_ = nullptr;
std::vector<SyntheticTrial>* CliSummary::trials_ = nullptr;

TEST_F(CliSummary, GroupsHaveTheMeanAndSampleStdOfTheirTrials) {
  const CommandResult r = RunRockfit({"summary", Manifest(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  ASSERT_EQ(json["trials"].size(), trials_->size());
  ASSERT_EQ(json["groups"].size(), 6u);  // 3 blocks × positions A, B
  for (const auto& g : json["groups"]) {
    std::vector<double> avrf, opmf;
    double expected_r = 0.0;
    for (std::size_t i = 0; i < trials_->size(); ++i) {
      const auto& t = json["trials"][i];
      if (t["block_id"] != g["block_id"] || t["position"] != g["position"]) continue;
      ASSERT_EQ(t["status"], "ok") << t["message"];
      avrf.push_back(t["avrf"].get<double>());
      opmf.push_back(t["opmf"].get<double>());
      EXPECT_NEAR(t["avrf"].get<double>(), (*trials_)[i].r, 1e-2) << t["trial_id"];
      expected_r += (*trials_)[i].r / 3.0;
    }
    ASSERT_EQ(avrf.size(), 3u);
    EXPECT_EQ(g["n_trials"], 3);
    const double mean = (avrf[0] + avrf[1] + avrf[2]) / 3.0;
    double ss = 0.0;
    for (double v : avrf) ss += (v - mean) * (v - mean);
    EXPECT_NEAR(g["avrf_mean"].get<double>(), mean, 1e-12);
    EXPECT_NEAR(g["avrf_std"].get<double>(), std::sqrt(ss / 2.0), 1e-12);
    EXPECT_NEAR(g["avrf_mean"].get<double>(), expected_r, 1e-2);
    const double opmf_mean = (opmf[0] + opmf[1] + opmf[2]) / 3.0;
    EXPECT_NEAR(g["opmf_mean"].get<double>(), opmf_mean, 1e-12);
  }
}

TEST_F(CliSummary, PrintsBothTables) {
  const CommandResult r = RunRockfit({"summary", Manifest()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("B2-B-3"), std::string::npos);
  EXPECT_NE(r.out.find("OPMF mean ± std (n)"), std::string::npos);
  EXPECT_NE(r.out.find("AVRF mean ± std (n)"), std::string::npos);
}

TEST_F(CliSummary, Hdf5OutputHasTheDocumentedTablesAndARerunKeepsFits) {
  const ScratchDir out_dir("cli_summary_out");
  const auto out = out_dir / "campaign.h5";
  ASSERT_EQ(RunRockfit({"summary", Manifest(), "-o", out.string()}).exit_code, 0);
  {  // the fitting engineer's later step
    io::hdf5::Transaction tx(out, {"/fits/B1-A-1"});
    tx.Root().CreateGroup("fits/B1-A-1").SetDouble("epsilon_rad_s", 0.02);
    tx.Commit();
  }
  const CommandResult again = RunRockfit({"summary", Manifest(), "-o", out.string()});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const io::hdf5::File file = io::hdf5::File::Open(out);
  EXPECT_EQ(file.Root().OpenGroup("fits/B1-A-1").GetDouble("epsilon_rad_s"), 0.02);
  EXPECT_EQ(io::ReadSummaryHdf5(out).groups.size(), 6u);
  ROCKFIT_REQUIRE_H5PY();
  const auto check = RunH5pyScript(R"(
import sys, h5py
f = h5py.File(sys.argv[1], 'r')
assert f.attrs['rockfit_schema_version'] == 1
t, g = f['summary/trials'], f['summary/groups']
n = t['trial_id'].shape[0]
assert n == 18
for name, units in [('b2_m', 'm'), ('opmf', '1'), ('avrf', '1'), ('lambda_equivalent', '1')]:
    assert t[name].shape == (n,) and t[name].attrs['units'] == units, name
for name in ['block_id', 'position', 'status', 'message']:
    assert t[name].shape == (n,), name
for name, units in [('b2_m', 'm'), ('n_trials', '1'), ('opmf_mean', '1'), ('opmf_std', '1'), ('avrf_mean', '1'), ('avrf_std', '1')]:
    assert g[name].shape == (6,) and g[name].attrs['units'] == units, name
assert sorted(f['trials'].keys())[0] == 'B1-A-1' and len(f['trials']) == 18
assert len(f['blocks']) == 3 and abs(f['blocks/B2'].attrs['b2_m'] - 0.05) < 1e-15
assert 'fits' in f
print('ok')
)", out);
  EXPECT_EQ(check.out, "ok\n");
}

TEST_F(CliSummary, CsvOutputWritesGroupsAndTrials) {
  const ScratchDir out_dir("cli_summary_out");
  const CommandResult r = RunRockfit({"summary", Manifest(), "-o", (out_dir / "s.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream groups(out_dir / "s.csv"), trials(out_dir / "s_trials.csv");
  std::string line;
  std::size_t n = 0;
  while (std::getline(groups, line)) ++n;
  EXPECT_EQ(n, 7u);
  n = 0;
  while (std::getline(trials, line)) ++n;
  EXPECT_EQ(n, 19u);
}

TEST_F(CliSummary, UnreadableTrialIsReportedAndTheRestSummarised) {
  std::ifstream in(Manifest());
  std::stringstream text;
  text << in.rdbuf();
  std::string manifest = text.str();
  const std::string from = "recordings/B1-A-2.h5";
  manifest.replace(manifest.find(from), from.size(), "recordings/missing.h5");
  std::ofstream(dir_->path() / "one-missing.toml") << manifest;  // beside the recordings: relative paths resolve
  const CommandResult r = RunRockfit({"summary", (dir_->path() / "one-missing.toml").string(), "--json"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("trial B1-A-2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("missing.h5"), std::string::npos) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["load_errors"], 1);
  EXPECT_EQ(json["trials"][1]["status"], "load_error");
  EXPECT_EQ(json["groups"][0]["n_trials"], 3);
  EXPECT_EQ(json["groups"][0]["n_avrf"], 2);
}

TEST_F(CliSummary, BadManifestIsExitTwoWithPosition) {
  const ScratchDir out_dir("cli_summary_out");
  std::ofstream(out_dir / "bad.toml") << "[[blocks]]\nid = \"B1\"\nb1 = 0.05\nb2 = 0.03\nh = 0.2\ndensty = 2692\n";
  const CommandResult r = RunRockfit({"summary", (out_dir / "bad.toml").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.toml:6:1: unknown key 'densty'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'density'"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rockfit::testing

namespace rockfit::testing {
namespace {

// The bundled sample campaign (data-samples/, made by `rockfit synth` with an independent measurement model:
// strong gyro ringing, gyro bias, drift and random walk of the attitude) against the truth files written with it.
// Where the lateral motion stands out of the noise (Φ ≥ 0.015: max|φx| ≥ 3e-3 rad) the OPMF is within 10 %: the
// attitude files integrate the gyro's ringing as the device does, a step of ~1e-3 rad in φx after an impact that
// the drift correction spreads to the next anchor; measured ≤ 8.2 % (block1-B-1, the narrowest block).
constexpr double kOpmfRelativeTolerance = 0.10;
constexpr double kOpmfSignificant = 0.015;
// Below it, 0.005 absolute (the angle random walk between anchors, opmf_test).
constexpr double kOpmfAbsoluteTolerance = 0.005;

TEST(CliSummaryOfTheSampleCampaign, OpmfMatchesTheSimulatedAnglesOfEveryTrial) {
  const auto samples = SourceDir() / "data-samples";
  if (!std::filesystem::exists(samples / "manifest.toml")) GTEST_SKIP() << "no data-samples/manifest.toml";
  const CommandResult r = RunRockfit({"summary", (samples / "manifest.toml").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  ASSERT_EQ(json["trials"].size(), 16u);
  EXPECT_EQ(json["groups"].size(), 8u);
  for (const auto& t : json["trials"]) {
    const std::string id = t["trial_id"];
    ASSERT_EQ(t["status"], "ok") << id << ": " << t["message"];
    const auto truth = nlohmann::json::parse(ReadWholeFile(samples / "recordings" / (id + "_truth.json")));
    const double expected = truth["summary"]["opmf"].get<double>();
    const double measured = t["opmf"].get<double>();
    if (expected >= kOpmfSignificant) {
      EXPECT_NEAR(measured / expected, 1.0, kOpmfRelativeTolerance) << id;
    } else {
      EXPECT_NEAR(measured, expected, kOpmfAbsoluteTolerance) << id;
    }
  }
}

}  // namespace
}  // namespace rockfit::testing
