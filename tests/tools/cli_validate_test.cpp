// `rockfit validate` (tools/src/cmd_validate.cpp) on campaigns made by `rockfit synth`: three releases of one block
// with the same λ, λ_lat, λ_lon predict each other (every ε_pred/ε_own ≤ 1.5); with the third release's λ_lon 50 %
// off, that trial's ratio is at least 2. Releases rolled off the rocking plane (`synth --release-roll`) with the same
// λ's predict each other with each one's roll fitted again; with the roll left out of every fit
// (--release-roll-mode off) the model error shows in every ratio. The table, --json, /validation in HDF5 (own fits
// read from a batch file) and the figure.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "png_header.hpp"
#include "python_h5py.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

// Linearised intervals keep the own fits cheap (the check does not depend on the interval method's cost).
const std::vector<std::string> kFast = {"--intervals", "fast", "-j", "2"};

// Three releases of the paper's Fig. 14 block (λ = 2.185, λ_lat = −2.032, λ_lon = 0.197) at different tilts and
// times; the third with λ_lon = `third_lambda_lon`. Returns the manifest.
std::string WriteCampaign(const ScratchDir& dir, double third_lambda_lon) {
  struct Release {
    double alpha, t0, lambda_lon;
    int seed;
  };
  const Release releases[] = {{0.19, 1.3, 0.197, 11}, {0.197, 1.5, 0.197, 12}, {0.205, 1.7, third_lambda_lon, 13}};
  std::string manifest = "[[blocks]]\nid = \"b\"\nb1 = 0.05000453\nb2 = 0.035\nh = 0.2\ndensity = 2692\n";
  for (int i = 0; i < 3; ++i) {
    const Release& r = releases[i];
    const std::string prefix = (dir / fmt::format("t{}", i + 1)).string();
    const CommandResult s = RunRockfit({"synth", "--b1", "0.05000453", "--b2", "0.035", "--h", "0.2", "--density",
                                        "2692", "--alpha", fmt::format("{}", r.alpha), "--lambda", "2.185",
                                        "--lambda-lat", "-2.032", "--lambda-lon", fmt::format("{}", r.lambda_lon),
                                        "--t0", fmt::format("{}", r.t0), "--duration", "3.5", "--seed",
                                        std::to_string(r.seed), "-o", prefix});
    EXPECT_EQ(s.exit_code, 0) << s.err;
    manifest += fmt::format("\n[[trials]]\nid = \"t{0}\"\nblock = \"b\"\nposition = \"A\"\nfiles = \"{1}\"\n", i + 1, prefix);
  }
  return dir.Write("campaign.toml", manifest).string();
}

nlohmann::json Validate(const std::string& manifest, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"validate", manifest, "--json"};
  args.insert(args.end(), kFast.begin(), kFast.end());
  args.insert(args.end(), extra.begin(), extra.end());
  const CommandResult r = RunRockfit(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(CliValidate, ReleasesSharingTheirImpactParametersHaveEveryRatioAtMostOnePointFive) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();  // whole fits with the global stage
  const ScratchDir dir("cli_validate_shared");
  const nlohmann::json j = Validate(WriteCampaign(dir, 0.197));
  ASSERT_EQ(j["trials"].size(), 3u);
  for (const auto& t : j["trials"]) {
    ASSERT_TRUE(t["predicted"].get<bool>()) << t.dump();
    EXPECT_LE(t["ratio"].get<double>(), 1.5) << t.dump();
    EXPECT_TRUE(t["transfers"].get<bool>());
    EXPECT_EQ(t["n_others"], 2);
  }
  ASSERT_EQ(j["groups"].size(), 1u);
  EXPECT_EQ(j["groups"][0]["n_transfer"], 3);
  EXPECT_LE(j["groups"][0]["max_ratio"].get<double>(), 1.5);
}

TEST(CliValidate, AReleaseWhoseLambdaLonIsFiftyPercentOffHasARatioOfAtLeastTwo) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();  // whole fits with the global stage
  const ScratchDir dir("cli_validate_off");
  const nlohmann::json j = Validate(WriteCampaign(dir, 1.5 * 0.197));
  const auto& off = j["trials"][2];
  ASSERT_TRUE(off["predicted"].get<bool>()) << off.dump();
  EXPECT_GE(off["ratio"].get<double>(), 2.0) << off.dump();
  EXPECT_FALSE(off["transfers"].get<bool>());
  EXPECT_FALSE(off["parameters"]["lambda_lon"]["overlaps"].get<bool>());
  EXPECT_FALSE(off["overlaps_all"].get<bool>());
}

TEST(CliValidate, ReadsOwnFitsFromABatchFileAndWritesValidationHdf5TableAndFigure) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();  // whole fits with the global stage
  if (!HaveH5py()) GTEST_SKIP() << "/usr/bin/python3 with h5py is missing";
  const ScratchDir dir("cli_validate_files");
  const std::string manifest = WriteCampaign(dir, 0.197);
  const std::string fits = (dir / "fits.h5").string(), png = (dir / "validation.png").string();
  std::vector<std::string> batch = {"batch", manifest, "-o", fits};
  batch.insert(batch.end(), kFast.begin(), kFast.end());
  const CommandResult b = RunRockfit(batch);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  std::vector<std::string> args = {"validate", manifest, "--fits", fits, "-o", fits, "--plot", png};
  args.insert(args.end(), kFast.begin(), kFast.end());
  const CommandResult r = RunRockfit(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("median ratio"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("written  " + fits), std::string::npos) << r.out;
  EXPECT_TRUE(ReadPngHeader(png).valid);
  const CommandResult check = RunH5pyScript(R"(
import sys, h5py, math
f = h5py.File(sys.argv[1], 'r')
t = f['validation/per_trial']
assert [x.decode() for x in t['trial'][()]] == ['t1', 't2', 't3'], t['trial'][()]
assert all(0 < r <= 1.5 for r in t['ratio'][()]), t['ratio'][()]
assert list(t['predicted'][()]) == [1, 1, 1]
assert list(t['release_roll_fitted'][()]) == [0, 0, 0], 'released on the edge: no roll fitted'
assert list(t['release_roll_rad'][()]) == [0, 0, 0]
assert all(1.3 < e < 3.5 for e in t['t_end_s'][()]), t['t_end_s'][()]
assert t['lambda_lon_held'].attrs['units'].startswith('1')
g = f['validation/per_group']
assert list(g['n'][()]) == [3] and list(g['n_transfer'][()]) == [3]
assert f['validation'].attrs['ratio_warning'] == 1.5
assert 'fits' in f and len(f['fits']) == 3, 'the batch fits are kept'
print('ok')
)", fits);
  EXPECT_EQ(check.exit_code, 0) << check.out;
  const CommandResult plot = RunRockfit({"plot", "validation", fits, "-o", (dir / "again.png").string()});
  EXPECT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_TRUE(ReadPngHeader(dir / "again.png").valid);
}

// Three releases of a 5 × 4 × 20 cm block with λ = 0.9, λ_lat = 0.5, λ_lon = 0.8, each rolled off the rocking
// plane by its own roll (as a hand lets a block go: either sense, a few mrad). Returns the manifest.
struct RolledRelease {
  double alpha, t0, roll_rad;
  int seed;
};
constexpr RolledRelease kRolledReleases[] = {{0.15, 1.3, 0.002, 11}, {0.18, 1.5, -0.003, 12}, {0.21, 1.7, -0.003, 13}};

std::string WriteRolledCampaign(const ScratchDir& dir) {
  std::string manifest = "[[blocks]]\nid = \"b\"\nb1 = 0.05\nb2 = 0.04\nh = 0.2\ndensity = 2692\n";
  for (int i = 0; i < 3; ++i) {
    const RolledRelease& r = kRolledReleases[i];
    const std::string prefix = (dir / fmt::format("r{}", i + 1)).string();
    const CommandResult s = RunRockfit({"synth", "--b1", "0.05", "--b2", "0.04", "--h", "0.2", "--density", "2692",
                                        "--alpha", fmt::format("{}", r.alpha), "--lambda", "0.9", "--lambda-lat", "0.5",
                                        "--lambda-lon", "0.8", "--t0", fmt::format("{}", r.t0), "--release-roll",
                                        fmt::format("{}", r.roll_rad), "--duration", "3.5", "--seed",
                                        std::to_string(r.seed), "-o", prefix});
    EXPECT_EQ(s.exit_code, 0) << s.err;
    manifest += fmt::format("\n[[trials]]\nid = \"r{0}\"\nblock = \"b\"\nposition = \"A\"\nfiles = \"{1}\"\n", i + 1, prefix);
  }
  return dir.Write("campaign.toml", manifest).string();
}

// The roll of the prediction against the truth: 0.1 mrad, 5 % of the smallest roll (measured: within 1 µrad).
constexpr double kRollTolerance_rad = 1e-4;

TEST(CliValidate, RolledReleasesSharingTheirImpactParametersHaveEveryRatioAtMostOnePointFiveAndTheirRollsRefitted) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();  // whole fits with the global stage
  const ScratchDir dir("cli_validate_rolled");
  const std::string manifest = WriteRolledCampaign(dir), fits = (dir / "fits.h5").string();
  std::vector<std::string> batch = {"batch", manifest, "-o", fits};
  batch.insert(batch.end(), kFast.begin(), kFast.end());
  const CommandResult b = RunRockfit(batch);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const nlohmann::json j = Validate(manifest, {"--fits", fits});
  ASSERT_EQ(j["trials"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& t = j["trials"][i];
    ASSERT_TRUE(t["predicted"].get<bool>()) << t.dump();
    EXPECT_LE(t["ratio"].get<double>(), 1.5) << t.dump();
    EXPECT_TRUE(t["release_roll_fitted"].get<bool>()) << t.dump();
    EXPECT_NEAR(t["release_roll"].get<double>(), kRolledReleases[i].roll_rad, kRollTolerance_rad) << t.dump();
  }
  // The table gets the roll's column (mrad) where a roll is fitted.
  std::vector<std::string> table = {"validate", manifest, "--fits", fits};
  table.insert(table.end(), kFast.begin(), kFast.end());
  const CommandResult r = RunRockfit(table);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("β [mrad]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("-3.000"), std::string::npos) << r.out;
}

TEST(CliValidate, WithTheRollLeftOutOfEveryFitTheRolledReleasesShowTheModelErrorInEveryRatio) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();  // whole fits with the global stage
  // Expected before it was run: each own fit explains its rolled release with a planar one (β held at 0), its λ_lat
  // and λ_lon absorb its own roll, which differs from the others' in sense and size, and the prediction, with the
  // others' λ's held, can move only t0 and α: ε_pred well above ε_own. Measured: ratios 1.9–2.5 over the
  // problems' windows (the own fits extend theirs; ε_own there 0.045–0.052 rad/s, several times that of the fits
  // with the roll).
  const ScratchDir dir("cli_validate_rolled_off");
  const nlohmann::json j = Validate(WriteRolledCampaign(dir), {"--release-roll-mode", "off"});
  ASSERT_EQ(j["trials"].size(), 3u);
  for (const auto& t : j["trials"]) {
    ASSERT_TRUE(t["predicted"].get<bool>()) << t.dump();
    EXPECT_FALSE(t["release_roll_fitted"].get<bool>()) << t.dump();
    EXPECT_EQ(t["release_roll"].get<double>(), 0.0);
    EXPECT_GT(t["ratio"].get<double>(), 1.5) << t.dump();
    EXPECT_FALSE(t["transfers"].get<bool>());
  }
  EXPECT_EQ(j["groups"][0]["n_transfer"], 0);
}

TEST(CliValidate, AFitsFileWithoutATrialOfTheManifestIsBadInput) {
  const ScratchDir dir("cli_validate_missing");
  const std::string manifest = WriteCampaign(dir, 0.197);
  const std::string fits = (dir / "fits.h5").string();
  const CommandResult b = RunRockfit({"fit", manifest, "--trial", "t1", "-o", fits, "--intervals", "fast",
                                      "--threads", "1", "--no-global", "--max-evaluations", "15"});
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const CommandResult r = RunRockfit({"validate", manifest, "--fits", fits});
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("no /fits/t2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rockfit batch"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rockfit::testing
