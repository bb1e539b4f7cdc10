// `rockfit synth`, run as the real binary: reproducibility, the ideal sensor against an independent run of the
// simulator, measured noise and drift statistics from the files, and bad arguments.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_numbers.hpp"
#include "recording/attitude.hpp"
#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::testing {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;
// Single precision stores a value to |v|·2⁻²⁴.
constexpr double kFloatRelative = 1.0 / 16777216.0;

// The block of the bundled campaign's block 2 (granite, b1/h = tan 0.245).
const std::vector<std::string> kBlock = {"--b1", "0.05000453", "--b2", "0.03", "--h", "0.2", "--density", "2692"};
constexpr double kB1 = 0.05000453;
constexpr double kB2 = 0.03;
constexpr double kH = 0.2;
constexpr double kDensity = 2692.0;

class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() / ("rockfit_cli_synth_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::vector<std::string> Args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

// Half a unit of the 7th significant digit of the printed value, plus its single-precision rounding.
double PrintedPrecision(double value) {
  if (value == 0.0) return 1e-30;
  return 0.5 * std::pow(10.0, std::floor(std::log10(std::abs(value))) - 6.0) + std::abs(value) * kFloatRelative;
}

double StandardDeviation(const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  double sum_sq = 0.0;
  for (double v : x) sum_sq += (v - mean) * (v - mean);
  return std::sqrt(sum_sq / static_cast<double>(x.size() - 1));
}

TEST(CliSynth, HelpListsTheModelRecordingAndMeasurementOptions) {
  const CommandResult r = RunRockfit({"synth", "--help"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* option : {"--alpha", "--lambda-lat", "--lambda-lon", "--t0", "--duration", "--rate", "--mounting",
                             "--seed", "--gyro-noise-dps", "--gyro-bias-dps", "--no-quantisation", "--ringing-gain",
                             "--drift-slope-dps", "--no-noise", "--output"}) {
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
  }
}

TEST(CliSynth, SameSeedGivesTheSameBytesAndAnotherSeedDifferentOnes) {
  TempDir a;
  TempDir b;
  TempDir c;
  const std::vector<std::string> common = {"--alpha", "0.2", "--lambda", "1.5", "--lambda-lat", "-1", "--lambda-lon",
                                           "0.4", "--t0", "1", "--duration", "4", "-o", "trial"};
  ASSERT_EQ(RunRockfit(Args(Args({"synth"}, kBlock), Args(common, {"--seed", "5"})), a.path()).exit_code, 0);
  ASSERT_EQ(RunRockfit(Args(Args({"synth"}, kBlock), Args(common, {"--seed", "5"})), b.path()).exit_code, 0);
  ASSERT_EQ(RunRockfit(Args(Args({"synth"}, kBlock), Args(common, {"--seed", "6"})), c.path()).exit_code, 0);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(a.path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(ReadWholeFile(entry.path()), ReadWholeFile(b.path() / name)) << name;
    ++files;
  }
  EXPECT_EQ(files, 8u);  // 7 CSV files and the truth
  EXPECT_NE(ReadWholeFile(a.path() / "trial_CalInertialAndMag.csv"), ReadWholeFile(c.path() / "trial_CalInertialAndMag.csv"));
  EXPECT_NE(ReadWholeFile(a.path() / "trial_EulerAngles.csv"), ReadWholeFile(c.path() / "trial_EulerAngles.csv"));
}

// The ideal sensor: every gyro and Euler value in the files is the simulated motion, computed here by an
// independent run of the simulator at the recording's sample times.
TEST(CliSynth, WithoutNoiseTheFilesHoldTheSimulatedAngularVelocityAndAttitude) {
  TempDir dir;
  const double t0 = 0.7;
  const double rate = 256.0;
  const double duration = 5.0;
  const CommandResult r = RunRockfit(
      Args(Args({"synth"}, kBlock), {"--alpha", "0.21", "--lambda", "1.8", "--lambda-lat", "-2", "--lambda-lon", "0.35",
                                      "--t0", "0.7", "--duration", "5", "--no-noise", "-o", (dir.path() / "t").string()}));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const core::Block block = core::Block::FromDensity(kB1, kB2, kH, kDensity);
  core::ModelParameters params;
  params.alpha_rad = 0.21;
  params.lambda = 1.8;
  params.lambda_lat = -2.0;
  params.lambda_lon = 0.35;
  const std::size_t samples = static_cast<std::size_t>(duration * rate);
  const std::size_t release = static_cast<std::size_t>(std::ceil(t0 * rate));
  core::SimulationOptions sim;
  sim.stop = core::StopCondition::kTMax;
  sim.t_max_s = static_cast<double>(samples - 1) / rate - t0;
  sim.sample_times_s.push_back(0.0);
  for (std::size_t n = release; n < samples; ++n) sim.sample_times_s.push_back(static_cast<double>(n) / rate - t0);
  const core::Trajectory truth = core::Simulate(block, params, sim);
  ASSERT_EQ(truth.t_s.size(), sim.sample_times_s.size()) << core::ToString(truth.end_reason);
  ASSERT_GT(truth.impacts.size(), 10u);

  const auto gyro = ReadCsvNumbers(dir.path() / "t_CalInertialAndMag.csv");
  const auto euler = ReadCsvNumbers(dir.path() / "t_EulerAngles.csv");
  ASSERT_EQ(gyro.size(), samples);
  ASSERT_EQ(euler.size(), samples);
  for (std::size_t n = 0; n < samples; ++n) {
    const std::size_t k = n < release ? 0 : 1 + (n - release);
    const Eigen::Vector3d w_dps = n < release ? Eigen::Vector3d::Zero() : Eigen::Vector3d(kDegPerRad * truth.w_B[k]);
    for (int i = 0; i < 3; ++i) {
      ASSERT_NEAR(gyro[n][1 + i], w_dps[i], PrintedPrecision(w_dps[i])) << "sample " << n << " axis " << i;
    }
    const Eigen::Vector3d zyx = io::EulerZyxFromQuaternion(truth.q_WB[k]);
    const Eigen::Vector3d xyz_deg = kDegPerRad * Eigen::Vector3d(zyx[2], zyx[1], zyx[0]);
    for (int i = 0; i < 3; ++i) {
      // Through a single-precision quaternion (≈4 ulps, 2.4e-7 rad) and the printed digits.
      ASSERT_NEAR(euler[n][1 + i], xyz_deg[i], 2.4e-7 * kDegPerRad + PrintedPrecision(xyz_deg[i])) << "sample " << n;
    }
  }
  // Before the release the block stands at φy = −α.
  EXPECT_NEAR(euler[0][2], -0.21 * kDegPerRad, 1e-4);
}

// Rest before a late release: white gyro noise and the drift slope measured from the files.
TEST(CliSynth, NoiseAndDriftInTheFilesMatchTheRequestWithinSamplingError) {
  TempDir dir;
  const double t0 = 20.0;
  const CommandResult r = RunRockfit(Args(
      Args({"synth"}, kBlock),
      {"--alpha", "0.2", "--t0", "20", "--duration", "20.5", "--gyro-noise-dps", "0.1", "--no-quantisation", "--no-ringing",
       "--drift-slope-dps", "0.05,-0.1,0.3", "--drift-walk-deg-per-rt-s", "0.01,0.01,0.02", "--seed", "17", "-o",
       (dir.path() / "t").string()}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto gyro = ReadCsvNumbers(dir.path() / "t_CalInertialAndMag.csv");
  const auto euler = ReadCsvNumbers(dir.path() / "t_EulerAngles.csv");
  const std::size_t rest_samples = static_cast<std::size_t>(t0 * 256.0);
  for (int i = 0; i < 3; ++i) {
    std::vector<double> x;
    for (std::size_t n = 0; n < rest_samples; ++n) x.push_back(gyro[n][1 + i]);
    // SE of a sample standard deviation: σ/√(2(N−1)).
    EXPECT_NEAR(StandardDeviation(x), 0.1, 4.0 * 0.1 / std::sqrt(2.0 * (rest_samples - 1))) << "axis " << i;
  }
  // The Euler error at rest is the drift: OLS slope, SE = σ_w √(6/(5T)) for a random walk over T.
  const double slopes[3] = {0.05, -0.1, 0.3};
  const double walks[3] = {0.01, 0.01, 0.02};
  const double truth[3] = {0.0, -0.2 * kDegPerRad, 0.0};
  for (int i = 0; i < 3; ++i) {
    double st = 0.0;
    double se = 0.0;
    for (std::size_t n = 0; n < rest_samples; ++n) {
      st += n / 256.0;
      se += euler[n][1 + i] - truth[i];
    }
    const double t_mean = st / rest_samples;
    const double e_mean = se / rest_samples;
    double sxy = 0.0;
    double sxx = 0.0;
    for (std::size_t n = 0; n < rest_samples; ++n) {
      const double t = n / 256.0;
      sxy += (t - t_mean) * (euler[n][1 + i] - truth[i] - e_mean);
      sxx += (t - t_mean) * (t - t_mean);
    }
    EXPECT_NEAR(sxy / sxx, slopes[i], 4.0 * walks[i] * std::sqrt(6.0 / (5.0 * t0))) << "axis " << i;
  }
}

TEST(CliSynth, JsonOutputListsTheFilesAndTheMotion) {
  TempDir dir;
  const CommandResult r = RunRockfit(Args(Args({"synth"}, kBlock), {"--t0", "1", "--duration", "3", "--json", "-o",
                                                                     (dir.path() / "t").string()}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["samples"].get<int>(), 768);
  EXPECT_EQ(json["rate_hz"].get<double>(), 256.0);
  EXPECT_EQ(json["files"].size(), 8u);
  for (const char* key : {"impacts", "first_impact_s", "phase4_end_s", "rest_s", "seed", "t0_s", "duration_s", "prefix"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  const auto truth = nlohmann::json::parse(ReadWholeFile(dir.path() / "t_truth.json"));
  EXPECT_EQ(truth["parameters"]["t0_s"].get<double>(), 1.0);
  EXPECT_EQ(truth["impacts"].size(), json["impacts"].get<std::size_t>());
  EXPECT_EQ(truth["impact_columns"].size(), truth["impacts"][0].size());
}

TEST(CliSynth, InspectReadsTheRateFromTheRegistersFileWithoutWarnings) {
  TempDir dir;
  const std::string prefix = (dir.path() / "t").string();
  ASSERT_EQ(RunRockfit(Args(Args({"synth"}, kBlock), {"--t0", "1", "--duration", "4", "--mounting=x,-y,-z", "-o", prefix}))
                .exit_code,
            0);
  const CommandResult r = RunRockfit({"inspect", prefix, "--mounting=x,-y,-z", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["format"], "ximu-gui");
  EXPECT_EQ(json["rate_source"], "registers");
  EXPECT_EQ(json["rate_hz"].get<double>(), 256.0);
  EXPECT_EQ(json["samples"].get<int>(), 1024);
  EXPECT_TRUE(json["warnings"].empty()) << json["warnings"];
  EXPECT_TRUE(json["gaps"].empty());
  // The upside-down sensor's readings are turned back: the block stands at φy = −α = −0.2 rad before t0.
  EXPECT_NEAR(json["ranges"]["euler_zyx_rad"]["phi_y"][0].get<double>(), -0.2, 0.01);
}

TEST(CliSynth, RateTheDeviceCannotSendIsAUsageError) {
  TempDir dir;
  const CommandResult r = RunRockfit(Args(Args({"synth"}, kBlock), {"--rate", "100", "-o", (dir.path() / "t").string()}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("512"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(CliSynth, ReleaseAfterTheEndOfTheRecordingIsAUsageError) {
  TempDir dir;
  const CommandResult r = RunRockfit(Args(Args({"synth"}, kBlock), {"--t0", "12", "--duration", "10", "-o", (dir.path() / "t").string()}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("t0"), std::string::npos) << r.err;
}

TEST(CliSynth, NoNoiseTogetherWithANoiseLevelIsAUsageError) {
  TempDir dir;
  const CommandResult r = RunRockfit(
      Args(Args({"synth"}, kBlock), {"--no-noise", "--gyro-noise-dps", "0.2", "-o", (dir.path() / "t").string()}));
  EXPECT_EQ(r.exit_code, 1);
}

TEST(CliSynth, MirroredMountingIsAUsageError) {
  TempDir dir;
  const CommandResult r = RunRockfit(Args(Args({"synth"}, kBlock), {"--mounting", "x,y,-z", "-o", (dir.path() / "t").string()}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("x,y,-z"), std::string::npos) << r.err;
}

TEST(CliSynth, UnwritableOutputIsExitCodeFour) {
  TempDir dir;
  const CommandResult r = RunRockfit(
      Args(Args({"synth"}, kBlock), {"--t0", "1", "--duration", "2", "-o", (dir.path() / "missing" / "t").string()}));
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
}

TEST(CliSynth, TiltBeyondTheOverturningAngleIsANumericalFailure) {
  // θc = atan(b1/h) = 0.245 rad: released from 0.3 rad the block falls over.
  TempDir dir;
  const CommandResult r = RunRockfit(Args(Args({"synth"}, kBlock), {"--alpha", "0.3", "-o", (dir.path() / "t").string()}));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("overturn"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace rockfit::testing
