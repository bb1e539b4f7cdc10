// The CSV sample campaign (data-samples/csv/: phyphox, Sensor Logger, a microcontroller log and a quoted
// spreadsheet export of four synthetic trials, attitude withheld) through the program: inspect says what it
// recognised, summary agrees with the same trials read from their x-IMU files, a trial fits.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

std::string CsvManifest() { return (SourceDir() / "data-samples" / "csv" / "manifest.toml").string(); }
std::string XimuManifest() { return (SourceDir() / "data-samples" / "manifest.toml").string(); }

// The required agreement of a gyro-only campaign with the same campaign read with its attitude (io/README.md,
// "Attitude from the gyro"): met by every trial of the sample campaign since the impacts are located where the
// levelled angle comes back to zero (measured at most 0.0012 and 0.60 %; block3-A-1, the trial with the most
// out-of-plane motion, 0.0010 and 0.48 %).
constexpr double kOpmfAgreement = 0.003;
constexpr double kAvrfRelativeAgreement = 0.01;

TEST(CliCsvCampaign, SummaryOfTheGyroOnlyFilesAgreesWithTheXimuFilesOfTheSameTrials) {
  const CommandResult csv = RunRockfit({"summary", CsvManifest(), "--json"});
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const CommandResult ximu = RunRockfit({"summary", XimuManifest(), "--json"});
  ASSERT_EQ(ximu.exit_code, 0) << ximu.err;
  std::map<std::string, nlohmann::json> reference;
  const auto ximu_json = nlohmann::json::parse(ximu.out);
  for (const auto& t : ximu_json["trials"]) reference[t["trial_id"].get<std::string>()] = t;
  const auto trials = nlohmann::json::parse(csv.out)["trials"];
  ASSERT_EQ(trials.size(), 4u);
  for (const auto& t : trials) {
    SCOPED_TRACE(t["trial_id"].get<std::string>());
    ASSERT_EQ(t["status"], "ok") << t["message"];
    const auto& r = reference.at(t["trial_id"].get<std::string>());
    EXPECT_NEAR(t["opmf"].get<double>(), r["opmf"].get<double>(), kOpmfAgreement);
    EXPECT_NEAR(t["avrf"].get<double>() / r["avrf"].get<double>(), 1.0, kAvrfRelativeAgreement);
  }
}

TEST(CliCsvCampaign, InspectSaysWhatItRecognisedAndWhy) {
  const CommandResult r =
      RunRockfit({"inspect", (SourceDir() / "data-samples" / "csv" / "sensor-logger" / "Gyroscope.csv").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string recognised = nlohmann::json::parse(r.out)["recognised"].dump();
  EXPECT_NE(recognised.find("preset sensor-logger"), std::string::npos) << recognised;
  EXPECT_NE(recognised.find("Unix epoch"), std::string::npos) << recognised;
  EXPECT_NE(recognised.find("named Gyroscope.csv"), std::string::npos) << recognised;
}

TEST(CliCsvCampaign, AMicrocontrollerLogReportsItsCounterWrapAndMetricsTheIntegratedAttitude) {
  const CommandResult inspect = RunRockfit(
      {"inspect", (SourceDir() / "data-samples" / "csv" / "arduino" / "log.csv").string(), "--columns",
       "time=micros@us;gyro=gx [dps],gy [dps],gz [dps];accel=ax [g],ay [g],az [g]", "--json"});
  ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
  const auto json = nlohmann::json::parse(inspect.out);
  EXPECT_NE(json["warnings"].dump().find("wrapped 1 time(s) at 2^32"), std::string::npos) << json["warnings"];
  EXPECT_NE(json["recognised"].dump().find("log.csv:642:1"), std::string::npos) << json["recognised"];
  const CommandResult metrics = RunRockfit({"metrics", CsvManifest(), "--trial", "block3-A-1", "--json"});
  ASSERT_EQ(metrics.exit_code, 0) << metrics.err;
  EXPECT_NE(metrics.err.find("integrated from the gyro, levelled by the accelerometer"), std::string::npos)
      << metrics.err;
}

TEST(CliCsvCampaign, APhyphoxTrialFitsToItsTruth) {
  const CommandResult r = RunRockfit({"fit", CsvManifest(), "--trial", "block2-A-1", "--json", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  // The paper's Fig. 14 parameters the synthetic trial was made with (data-samples/README.md), within the bounds
  // python/tests/test_fit.py holds the x-IMU files of the same trial to.
  EXPECT_NEAR(json["parameters"]["alpha"]["value"].get<double>(), 0.197, 2e-3);
  EXPECT_NEAR(json["parameters"]["lambda_lat"]["value"].get<double>(), -2.032, 0.2032);
}

TEST(CliCsvCampaign, ASensorLoggerTrialFitsToItsTruth) {
  const CommandResult r = RunRockfit({"fit", CsvManifest(), "--trial", "block1-A-1", "--json", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  // The parameters the synthetic trial was made with (tools/make_samples.sh: α = 0.21, λ_lat = −4.2), within the
  // bounds the phyphox trial above is held to.
  EXPECT_NEAR(json["parameters"]["alpha"]["value"].get<double>(), 0.21, 2e-3);
  EXPECT_NEAR(json["parameters"]["lambda_lat"]["value"].get<double>(), -4.2, 0.42);
}

TEST(CliCsvCampaign, MetricsOfAnXimuTrialReadWithoutItsAttitudeFiles) {
  const CommandResult r = RunRockfit({"metrics", XimuManifest(), "--trial", "block2-A-1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CommandResult g = RunRockfit({"metrics", (SourceDir() / "data-samples" / "recordings" / "block2-A-1").string(),
                                      "--manifest", XimuManifest(), "--block", "block2", "--orientation", "none",
                                      "--json"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const auto a = nlohmann::json::parse(r.out);
  const auto b = nlohmann::json::parse(g.out);
  EXPECT_NEAR(b["opmf"].get<double>(), a["opmf"].get<double>(), kOpmfAgreement);
  EXPECT_NEAR(b["avrf"].get<double>() / a["avrf"].get<double>(), 1.0, kAvrfRelativeAgreement);
}

TEST(CliCsvCampaign, OrientationNoneHoldsForAManifestTrialAsForAPath) {
  const std::string prefix = (SourceDir() / "data-samples" / "recordings" / "block3-A-1").string();
  const CommandResult by_path = RunRockfit({"metrics", prefix, "--manifest", XimuManifest(), "--block", "block3",
                                            "--orientation", "none", "--json"});
  ASSERT_EQ(by_path.exit_code, 0) << by_path.err;
  const CommandResult by_trial =
      RunRockfit({"metrics", XimuManifest(), "--trial", "block3-A-1", "--orientation", "none", "--json"});
  ASSERT_EQ(by_trial.exit_code, 0) << by_trial.err;
  EXPECT_NE(by_trial.err.find("integrated from the gyro"), std::string::npos) << by_trial.err;
  EXPECT_EQ(nlohmann::json::parse(by_trial.out)["opmf"], nlohmann::json::parse(by_path.out)["opmf"]);
  const CommandResult bad = RunRockfit({"metrics", XimuManifest(), "--trial", "block3-A-1", "--orientation", "sideways"});
  EXPECT_EQ(bad.exit_code, 1) << bad.err;
  EXPECT_NE(bad.err.find("--orientation must be"), std::string::npos) << bad.err;
}

TEST(CliCsvCampaign, ASensorLoggerExportIsLevelledByTheTotalAccelerationBesideItsGyroscope) {
  const std::string gyro = (SourceDir() / "data-samples" / "csv" / "sensor-logger" / "Gyroscope.csv").string();
  const CommandResult inspect = RunRockfit({"inspect", gyro, "--json"});
  ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
  const auto json = nlohmann::json::parse(inspect.out);
  EXPECT_NE(json["recognised"].dump().find("TotalAcceleration.csv beside the gyroscope file"), std::string::npos)
      << json["recognised"];
  EXPECT_NE(json["columns"].dump().find("TotalAcceleration.csv: x"), std::string::npos) << json["columns"];
  const CommandResult metrics = RunRockfit({"metrics", CsvManifest(), "--trial", "block1-A-1", "--json"});
  ASSERT_EQ(metrics.exit_code, 0) << metrics.err;
  EXPECT_NE(metrics.err.find("levelled by the accelerometer"), std::string::npos) << metrics.err;
}

TEST(CliCsvCampaign, ASensorLoggerAccelerometerFromAnotherRecordingIsRefusedWithBothLines) {
  const ScratchDir dir("cli_sensor_logger");
  const auto samples = SourceDir() / "data-samples" / "csv" / "sensor-logger";
  std::filesystem::copy_file(samples / "Gyroscope.csv", dir.path() / "Gyroscope.csv");
  // The accelerometer's times moved on by 10 s: the same header and units, another recording.
  std::ifstream in(samples / "TotalAcceleration.csv");
  std::ofstream out(dir.path() / "TotalAcceleration.csv");
  std::string line;
  std::getline(in, line);
  out << line << "\n";
  while (std::getline(in, line)) {
    const std::size_t comma = line.find(',');
    out << std::stoll(line.substr(0, comma)) + 10'000'000'000LL << line.substr(comma) << "\n";
  }
  out.close();
  const CommandResult r = RunRockfit({"inspect", (dir.path() / "Gyroscope.csv").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("TotalAcceleration.csv:2:1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Gyroscope.csv:2:1"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rockfit::testing
