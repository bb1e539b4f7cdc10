// The intervals of `rockfit fit` and `rockfit batch` as a user sees them (fitting/README.md, "Intervals"): the
// JSON keys, the text, the HDF5 columns and the group ranges, `--intervals` parsing, and a small version of
// the coverage study (tools/coverage_study.py) on random synthetic trials. Fits with profile intervals run
// the simulator thousands of times: optimised builds only; the parsing test runs everywhere.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "python_h5py.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

const char* const kFree[] = {"t0", "alpha", "lambda", "lambda_lat", "lambda_lon"};
// The keys of the same parameters in a synth truth file.
const char* const kTruthKey[] = {"t0_s", "alpha_rad", "lambda", "lambda_lat", "lambda_lon"};

std::string SampleManifest() { return (SourceDir() / "data-samples" / "manifest.toml").string(); }

nlohmann::json Truth(const std::string& trial) {
  std::ifstream in(SourceDir() / "data-samples" / "recordings" / (trial + "_truth.json"));
  return nlohmann::json::parse(in);
}

TEST(CliFitIntervals, UnknownIntervalMethodIsAUsageError) {
  const CommandResult r = RunRockfit({"fit", SampleManifest(), "--trial", "block2-A-1", "--intervals", "exact"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("none, fast or thorough"), std::string::npos) << r.err;
}

TEST(CliFitIntervals, JsonTextAndHdf5CarryIntervalsThatHoldTheTruth) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("cli_fit_intervals");
  const std::string out = (dir / "fits.h5").string();
  const CommandResult r =
      RunRockfit({"fit", SampleManifest(), "--trial", "block2-A-1", "--threads", "1", "--json", "-o", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["uncertainty_method"], "thorough");  // the default
  const nlohmann::json truth = Truth("block2-A-1")["parameters"];
  for (int i = 0; i < 5; ++i) {
    const char* name = kFree[i];
    const nlohmann::json& p = j["parameters"][name];
    ASSERT_EQ(p["interval_68"].size(), 2u) << name;
    ASSERT_EQ(p["interval_95"].size(), 2u) << name;
    EXPECT_EQ(p["determined"], "yes") << name << "\n" << j.dump(1);
    const double lo68 = p["interval_68"][0], hi68 = p["interval_68"][1];
    const double lo95 = p["interval_95"][0], hi95 = p["interval_95"][1];
    EXPECT_LE(lo95, lo68);
    EXPECT_LE(hi68, hi95);
    const double v = p["value"];
    EXPECT_TRUE(lo68 <= v && v <= hi68) << name;
    // block2-A-1 is the paper's Fig. 14 trial. One trial cannot test a coverage (tools/coverage_study.py does);
    // the truth lies within twice the 95 % half-width on its side (λ_lat misses the interval itself by 1.3
    // half-widths: fitting/README.md, "Intervals").
    const double t = truth[kTruthKey[i]];
    const double half = t > v ? hi95 - v : v - lo95;
    EXPECT_LE(std::abs(t - v), 2.0 * half) << name << " truth " << t << ", 95 % [" << lo95 << ", " << hi95 << "]";
  }
  EXPECT_TRUE(j["parameters"]["tau_edge"]["interval_95"].is_null());
  EXPECT_TRUE(j["parameters"]["tau_edge"]["determined"].is_null());
  ASSERT_EQ(j["correlation"]["parameters"].size(), 5u);
  ASSERT_EQ(j["correlation"]["matrix"].size(), 5u);
  EXPECT_DOUBLE_EQ(j["correlation"]["matrix"][0][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["correlation"]["matrix"][0][1].get<double>(), j["correlation"]["matrix"][1][0].get<double>());
  EXPECT_GE(j["uncertainty"]["correlation_factor"].get<double>(), 1.0);
  EXPECT_GE(j["uncertainty"]["noise_inflation_68"].get<double>(), 1.0);  // the lag-1 factor (1 + ρ₁)/(1 − ρ₁)
  EXPECT_GT(j["uncertainty"]["simulations"].get<int>(), 0);

  if (HaveH5py()) {
    const CommandResult check = RunH5pyScript(R"(
import sys, h5py, math
f = h5py.File(sys.argv[1], 'r')
p = f['fits/block2-A-1/parameters']
for name in ['interval_68_lower', 'interval_68_upper', 'interval_95_lower', 'interval_95_upper']:
    assert p[name].shape == (6,), (name, p[name].shape)
assert p['correlation'].shape == (6, 6)
assert [d.decode() for d in p['determined'][()]] == ['yes'] * 5 + ['fixed'], p['determined'][()]
assert math.isnan(p['interval_95_lower'][5])
assert f['fits/block2-A-1'].attrs['uncertainty_method'] == 'thorough'
assert f['fits/block2-A-1'].attrs['noise_inflation_68'] >= 1.0
print('ok')
)",
                                              out);
    EXPECT_EQ(check.exit_code, 0) << check.out;
  }
}

TEST(CliFitIntervals, NearTheCriticalTiltTheT0IntervalFollowsTheRidge) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  // block4-A-1: α = 0.24 rad, 5 mrad below θ_c. The data fix the first impact t0 + T(α) much better than t0:
  // the linearised standard error of t0 understates its uncertainty (fitting/README.md, "Known limits"), the
  // profile follows the ridge and holds the truth.
  const CommandResult r = RunRockfit({"fit", SampleManifest(), "--trial", "block4-A-1", "--threads", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& t0 = j["parameters"]["t0"];
  const double lo = t0["interval_95"][0], hi = t0["interval_95"][1];
  const double truth = Truth("block4-A-1")["parameters"]["t0_s"];
  EXPECT_TRUE(lo <= truth && truth <= hi) << truth << " outside [" << lo << ", " << hi << "]";
  EXPECT_GT(hi - lo, 10.0 * 2.0 * 1.96 * t0["std_error"].get<double>()) << j.dump(1);
}

// Runs tools/coverage_study.py (profile intervals) with `arguments` (trials, seed, checks) into a scratch
// directory and expects its exit status 0 (every check passed); the study's output on failure.
void ExpectCoverageStudyPasses(const std::string& tag, const std::string& arguments) {
  const ScratchDir dir(tag);
  const std::string command = std::string(kPython) + " " + ShellQuote((SourceDir() / "tools" / "coverage_study.py").string()) +
                              " --rockfit " + ShellQuote(RockfitBinary().string()) + " --methods thorough --out " +
                              ShellQuote(dir.path().string()) + " " + arguments + " >" +
                              ShellQuote((dir / "log").string()) + " 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << ReadWholeFile(dir / "log");
}

// The coverage study in small: four random trials (one seed), profile intervals; every 95 % interval of a
// determined parameter holds the truth in at least 3 of 4 trials, every "sign only" sign is right, and ε is
// within 1.02 × ε(truth) in at least 3 of 4 (the full study: tools/coverage_study.py, fitting/README.md).
TEST(CliFitIntervals, SmallCoverageStudyHoldsTheTruth) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  ExpectCoverageStudyPasses("cli_fit_coverage", "--trials 4 --seed 5 --check-coverage-95 0.75 --check-epsilon-fraction 0.75");
}

// The 68 % intervals, pooled over every determined parameter value of 16 random trials (about 80 values), hold
// the truth in about two thirds of them: between 50 and 85 % (about ±3.5 binomial standard deviations around
// 68 %; this seed gives 58 %). A bound against gross errors (intervals of zero width, or as wide as the 95 %
// ones), not a calibration: 16 trials cannot tell the bulk level from the old one (61 % on this seed), which
// only the 100-trial studies separate (fitting/README.md, "Coverage study").
TEST(CliFitIntervals, SixtyEightPercentIntervalsHoldTheTruthInAboutTwoThirds) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  ExpectCoverageStudyPasses("cli_fit_coverage_68", "--trials 16 --seed 7 --check-coverage-95 0.75 --check-coverage-68 0.5,0.85");
}

// Recordings with sensor errors that synth's measurement model does not make (tools/coverage_study.py
// --sensor-family; the full study: fitting/README.md, "Intervals under model error"), in small: three trials of
// a ringing of another form and three of a clock off by 100 ppm with jitter; with the default widening for
// model error every determined parameter's 95 % interval holds the truth in at least 2 of 3 trials.
TEST(CliFitIntervals, SmallSensorFamilyStudiesHoldTheTruth) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  ExpectCoverageStudyPasses("cli_fit_coverage_hammer", "--trials 3 --seed 5 --sensor-family ringing-hammer --check-coverage-95 0.66");
  ExpectCoverageStudyPasses("cli_fit_coverage_clock", "--trials 3 --seed 5 --sensor-family clock --check-coverage-95 0.66");
}

}  // namespace
}  // namespace rockfit::testing
