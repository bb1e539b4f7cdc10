// A synthetic trial end to end: the simulated motion placed in the recording, the truth file, and the files read
// back by the recording readers (rate from the Registers file, no warnings, mounting undone).
#include "rockfit/io/synth_recording.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "recording/attitude.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/mounting.hpp"
#include "test_paths.hpp"

namespace rockfit::io {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;
// A printed gyro value is its single-precision value to 7 significant digits: relative error ≤ 5e-7 + 6e-8,
// the largest rate here is < 2 rad/s, plus 1e-9 rad/s for values printed near zero.
constexpr double kPrintedRateTolerance = 2.0 * 5.6e-7 + 1e-9;
// Euler angles through a single-precision quaternion (≈2.4e-7 rad) and 7 printed digits of ≤ 180° (1.6e-6 rad).
constexpr double kPrintedAngleTolerance = 2.4e-7 + 1.6e-6;

class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() / ("rockfit_synth_rec_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

core::Block GraniteBlock() { return core::Block::FromDensity(0.05000453, 0.03, 0.2, 2692.0); }

core::ModelParameters Parameters() {
  core::ModelParameters p;
  p.alpha_rad = 0.2;
  p.lambda = 1.6;
  p.lambda_lat = -1.5;
  p.lambda_lon = 0.4;
  return p;
}

SynthRecordingOptions IdealOptions() {
  SynthRecordingOptions o;
  o.t0_s = 0.9;
  o.duration_s = 4.0;
  o.measurement = MeasurementOptions::Ideal();
  return o;
}

TEST(SynthRecording, BlockRestsAtTheReleaseTiltUntilT0AndMovesAfter) {
  const SynthRecording r = Synthesize(GraniteBlock(), Parameters(), IdealOptions());
  EXPECT_EQ(r.release_sample, 231u);  // ceil(0.9 · 256)
  ASSERT_EQ(r.motion.size(), 1024u);
  for (std::size_t n = 0; n < r.release_sample; ++n) {
    ASSERT_EQ(r.motion.w_B[n], Eigen::Vector3d::Zero());
    const Eigen::Vector3d zyx = io::EulerZyxFromQuaternion(r.motion.q_WB[n]);
    ASSERT_NEAR(zyx[1], -0.2, 1e-12) << "φy = −α (docs/design.md §2)";
  }
  EXPECT_GT(r.motion.w_B[r.release_sample + 20].y(), 0.0);  // falling back: ω_y > 0
  ASSERT_FALSE(r.trajectory.impacts.empty());
  ASSERT_TRUE(r.phase4_end_s.has_value());
  EXPECT_GT(*r.phase4_end_s, 0.9 + r.trajectory.impacts.front().t_s);
}

TEST(SynthRecording, OverturningBlockIsANumericalFailure) {
  core::ModelParameters p = Parameters();
  p.alpha_rad = 0.3;  // beyond atan(b1/h) = 0.245
  EXPECT_THROW(Synthesize(GraniteBlock(), p, IdealOptions()), NumericalFailure);
}

TEST(SynthRecording, OptionsOutsideTheRecordingOrTheDeviceAreRejected) {
  SynthRecordingOptions o = IdealOptions();
  o.rate_hz = 100.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
  o = IdealOptions();
  o.t0_s = 4.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
  o = IdealOptions();
  o.R_BS = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  EXPECT_THROW(o.Validate(), InvalidArgument);
}

TEST(SynthRecording, TruthFileHoldsTheInputsAndTheImpactLog) {
  TempDir dir;
  const SynthRecordingOptions o = IdealOptions();
  const SynthRecording r = Synthesize(GraniteBlock(), Parameters(), o);
  const auto files = WriteSynthRecording((dir.path() / "t").string(), GraniteBlock(), Parameters(), o, r);
  EXPECT_EQ(files.back(), (dir.path() / "t_truth.json").string());
  std::ifstream in(dir.path() / "t_truth.json");
  const nlohmann::json truth = nlohmann::json::parse(in);
  EXPECT_EQ(truth["parameters"]["alpha_rad"].get<double>(), 0.2);
  EXPECT_EQ(truth["parameters"]["lambda_lat"].get<double>(), -1.5);
  EXPECT_EQ(truth["recording"]["samples"].get<std::size_t>(), 1024u);
  EXPECT_EQ(truth["measurement"]["quantisation"].get<bool>(), false);
  const auto& impacts = truth["impacts"];
  ASSERT_EQ(impacts.size(), r.trajectory.impacts.size());
  for (std::size_t i = 0; i < impacts.size(); ++i) {
    const auto& record = r.trajectory.impacts[i];
    EXPECT_NEAR(impacts[i][0].get<double>(), o.t0_s + record.t_s, 1e-11) << i;
    EXPECT_EQ(impacts[i][1].get<std::string>(), core::ToString(record.kind));
    EXPECT_NEAR(impacts[i][8].get<double>(), record.w_plus_B.y(), 1e-11 * (1.0 + std::abs(record.w_plus_B.y())));
  }
  EXPECT_EQ(truth["summary"]["first_impact_s"].get<double>(), o.t0_s + r.trajectory.impacts.front().t_s);
}

// Writer and readers agree: the files read back give the true motion in block axes.
void ExpectReadBackEqualsTruth(const std::string& mounting_text, double quaternion_rate_hz) {
  TempDir dir;
  SynthRecordingOptions o = IdealOptions();
  const Mounting mounting = Mounting::Parse(mounting_text);
  o.R_BS = mounting.R_BS();
  o.mounting_text = mounting_text;
  o.files.quaternion_rate_hz = quaternion_rate_hz;
  const SynthRecording r = Synthesize(GraniteBlock(), Parameters(), o);
  WriteSynthRecording((dir.path() / "t").string(), GraniteBlock(), Parameters(), o, r);
  LoadOptions load;
  load.mounting = mounting;
  const Recording rec = LoadRecording(dir.path() / "t", load);
  EXPECT_EQ(rec.format, "ximu-gui");
  EXPECT_EQ(rec.rate_source, RateSource::kRegisters);
  EXPECT_EQ(rec.rate_hz, 256.0);
  EXPECT_TRUE(rec.warnings.empty()) << rec.warnings.front();
  EXPECT_TRUE(rec.gaps.empty());
  ASSERT_EQ(rec.size(), r.motion.size());
  ASSERT_TRUE(rec.has_euler());
  for (std::size_t n = 0; n < rec.size(); ++n) {
    EXPECT_NEAR(rec.t_s[n], n / 256.0, 1e-12);
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(rec.w_B[n][i], r.motion.w_B[n][i], kPrintedRateTolerance) << n;
    if (quaternion_rate_hz == 256.0) {
      const Eigen::Vector3d zyx = io::EulerZyxFromQuaternion(r.motion.q_WB[n]);
      for (int i = 0; i < 3; ++i) {
        // Unwrapped angles may differ by whole turns (a sensor yaw of 180° lies on the wrap).
        const double d = std::remainder(rec.euler_zyx[n][i] - zyx[i], 2.0 * kPi);
        ASSERT_NEAR(d, 0.0, kPrintedAngleTolerance) << "sample " << n << " angle " << i;
      }
    }
  }
}

TEST(SynthRecording, ReadersLoadTheFilesWithTheRegisterRateAndNoWarning) { ExpectReadBackEqualsTruth("x,y,z", 256.0); }

TEST(SynthRecording, ReadersUndoTheMountingOfAnUpsideDownAndATurnedSensor) {
  ExpectReadBackEqualsTruth("x,-y,-z", 256.0);
  ExpectReadBackEqualsTruth("-x,-y,z", 256.0);
  ExpectReadBackEqualsTruth("y,-x,z", 256.0);
}

TEST(SynthRecording, ReadersAcceptAHalfRateOrientationStream) { ExpectReadBackEqualsTruth("x,y,z", 128.0); }

// The bundled campaign: every trial loads as the device's files do, rate from the registers, no repair, and its
// mounting agrees with the data.
TEST(SynthRecording, EveryBundledSampleLoadsWithoutWarningWithTheRegisterRate) {
  const fs::path recordings = rockfit::testing::SourceDir() / "data-samples" / "recordings";
  std::size_t trials = 0;
  for (const auto& entry : fs::directory_iterator(recordings)) {
    const std::string name = entry.path().filename().string();
    const std::string suffix = "_truth.json";
    if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const fs::path prefix = recordings / name.substr(0, name.size() - suffix.size());
    std::ifstream in(entry.path());
    const nlohmann::json truth = nlohmann::json::parse(in);
    LoadOptions options;  // the mounting the trial was made with, as the manifest gives it
    options.mounting = Mounting::Parse(truth["mounting"]["text"].get<std::string>());
    const Recording rec = LoadRecording(prefix, options);
    EXPECT_EQ(rec.rate_source, RateSource::kRegisters) << prefix;
    EXPECT_EQ(rec.rate_hz, 256.0) << prefix;
    EXPECT_TRUE(rec.warnings.empty()) << prefix << ": " << rec.warnings.front();
    EXPECT_TRUE(rec.gaps.empty()) << prefix;
    EXPECT_EQ(rec.size(), truth["recording"]["samples"].get<std::size_t>()) << prefix;
    ++trials;
  }
  EXPECT_EQ(trials, 16u);
}

}  // namespace
}  // namespace rockfit::io
