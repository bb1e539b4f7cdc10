// Phone-app and logger CSV files built from a synthetic trial (its gyroscope and accelerometer, the attitude
// withheld) with the exact header rows and units of phyphox's and Sensor Logger's exports, a microcontroller
// log whose micros() counter wraps, and a spreadsheet's fully quoted export; read back through LoadRecording and
// compared sample by sample with the x-IMU files they came from. Bad variants fail at file:line:column.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/synth_recording.hpp"
#include "rockfit/io/trial_metrics.hpp"
#include "rockfit/io/units.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::ScratchDir;

core::Block Granite() { return core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0); }

// The device samples of one synthetic trial at 256 Hz (no quantisation, so that the files' digits are the limit).
const DeviceSamples& Trial() {
  static const DeviceSamples samples = [] {
    core::ModelParameters p;
    p.alpha_rad = 0.2;
    p.lambda = 1.2;
    p.lambda_lat = -1.0;
    p.lambda_lon = 0.6;
    SynthRecordingOptions o;
    o.t0_s = 1.0;
    o.duration_s = 6.0;
    o.measurement.quantisation = false;
    return Synthesize(Granite(), p, o).device;
  }();
  return samples;
}

constexpr double kRate_hz = 256.0;
constexpr double kRadPerDegree = 3.14159265358979323846 / 180.0;

std::string Phyphox() {
  std::string text = "\"Time (s)\",\"Gyroscope x (rad/s)\",\"Gyroscope y (rad/s)\",\"Gyroscope z (rad/s)\",\"Absolute (rad/s)\"\n";
  for (std::size_t k = 0; k < Trial().size(); ++k) {
    const Eigen::Vector3d w = Trial().gyro_dps[k].cast<double>() * kRadPerDegree;
    text += fmt::format("{:.9E},{:.9E},{:.9E},{:.9E},{:.9E}\n", k / kRate_hz, w.x(), w.y(), w.z(), w.norm());
  }
  return text;
}

std::string SensorLogger() {
  std::string text = "time,seconds_elapsed,z,y,x\n";
  const std::int64_t start_ns = 1700000000000000000;
  for (std::size_t k = 0; k < Trial().size(); ++k) {
    const Eigen::Vector3d w = Trial().gyro_dps[k].cast<double>() * kRadPerDegree;
    text += fmt::format("{},{},{},{},{}\n", start_ns + static_cast<std::int64_t>(k) * 3906250, k / kRate_hz, w.z(),
                        w.y(), w.x());
  }
  return text;
}

// micros() starting 2 s before its 32-bit wrap.
std::string MicrocontrollerLog() {
  std::string text = "micros,gx [dps],gy [dps],gz [dps],ax [g],ay [g],az [g]\r\n";
  const std::uint64_t start = (std::uint64_t{1} << 32) - 2000000;
  for (std::size_t k = 0; k < Trial().size(); ++k) {
    const Eigen::Vector3f& g = Trial().gyro_dps[k];
    const Eigen::Vector3f& a = Trial().accel_g[k];
    text += fmt::format("{},{:.5f},{:.5f},{:.5f},{:.6f},{:.6f},{:.6f}\r\n", (start + k * 1000000 / 256) % (std::uint64_t{1} << 32),
                        g.x(), g.y(), g.z(), a.x(), a.y(), a.z());
  }
  return text;
}

std::string QuotedSpreadsheet() {
  std::string text =
      "\"Time (s)\";\"Gyroscope X (deg/s)\";\"Gyroscope Y (deg/s)\";\"Gyroscope Z (deg/s)\";\"Accelerometer X (g)\";"
      "\"Accelerometer Y (g)\";\"Accelerometer Z (g)\";\"Remark, \"\"free\"\"\"\n";
  for (std::size_t k = 0; k < Trial().size(); ++k) {
    const Eigen::Vector3f& g = Trial().gyro_dps[k];
    const Eigen::Vector3f& a = Trial().accel_g[k];
    std::string line = fmt::format("\"{:.8f}\";\"{:.5f}\";\"{:.5f}\";\"{:.5f}\";\"{:.6f}\";\"{:.6f}\";\"{:.6f}\";\"a; b\"\n",
                                   k / kRate_hz, g.x(), g.y(), g.z(), a.x(), a.y(), a.z());
    for (char& c : line) c = c == '.' ? ',' : c;
    text += line;
  }
  return text;
}

// The largest difference of the gyro read back from the device's gyro [rad/s].
double GyroError(const Recording& r) {
  double worst = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    worst = std::max(worst, (r.w_B[k] - Trial().gyro_dps[k].cast<double>() * kRadPerDegree).cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(AppCsv, APhyphoxExportIsRecognisedAndReadToItsDigits) {
  const ScratchDir dir("app_phyphox");
  const Recording r = LoadRecording(dir.Write("Gyroscope.csv", Phyphox()), {});
  ASSERT_EQ(r.size(), Trial().size());
  EXPECT_NEAR(r.rate_hz, kRate_hz, 1e-6);
  EXPECT_LT(GyroError(r), 1e-8);  // 10 significant digits of a rate below 10 rad/s
  EXPECT_THAT(::testing::PrintToString(r.recognised), HasSubstr("phyphox"));
  EXPECT_FALSE(r.has_accel());
}

TEST(AppCsv, ASensorLoggerGyroscopeFileIsReadWithExactNanosecondEpochTimes) {
  const ScratchDir dir("app_sensor_logger");
  const Recording r = LoadRecording(dir.Write("Gyroscope.csv", SensorLogger()), {});
  ASSERT_EQ(r.size(), Trial().size());
  EXPECT_EQ(r.rate_hz, kRate_hz);  // integer nanoseconds subtracted exactly: every step is 3906250 ns
  EXPECT_EQ(r.t_s.back(), static_cast<double>(Trial().size() - 1) * 3906250e-9);
  EXPECT_LT(GyroError(r), 1e-12);
  EXPECT_THAT(::testing::PrintToString(r.recognised), AllOf(HasSubstr("Sensor Logger"), HasSubstr("Unix epoch")));
}

TEST(AppCsv, TheSensorLoggerPresetReadsTheSameFileUnderAnotherName) {
  const ScratchDir dir("app_sensor_logger_preset");
  const auto file = dir.Write("rotation.csv", SensorLogger());
  try {
    LoadRecording(file, {});
    FAIL() << "x, y, z of an unnamed Sensor Logger file must not be guessed";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("rotation.csv:1"), HasSubstr("--columns sensor-logger")));
  }
  LoadOptions options;
  options.columns = ColumnMap::Parse("sensor-logger");
  EXPECT_EQ(LoadRecording(file, options).size(), Trial().size());
}

TEST(AppCsv, AMicrocontrollerLogWhoseCounterWrapsIsUnwrappedWithAWarning) {
  const ScratchDir dir("app_micros");
  LoadOptions options;
  options.columns = ColumnMap::Parse("time=micros@us;gyro=gx [dps],gy [dps],gz [dps];accel=ax [g],ay [g],az [g]");
  const Recording r = LoadRecording(dir.Write("log.csv", MicrocontrollerLog()), options);
  ASSERT_EQ(r.size(), Trial().size());
  EXPECT_NEAR(r.rate_hz, 1e6 / 3906.0, 1e-9);  // whole microseconds: steps of 3906 and 3907 µs, the median 3906
  EXPECT_TRUE(r.gaps.empty());
  EXPECT_LT(GyroError(r), 1e-5 * kRadPerDegree);
  EXPECT_THAT(::testing::PrintToString(r.warnings), HasSubstr("wrapped 1 time(s) at 2^32"));
}

TEST(AppCsv, AFullyQuotedSpreadsheetExportIsReadByItsHeader) {
  const ScratchDir dir("app_quoted");
  const Recording r = LoadRecording(dir.Write("trial.csv", QuotedSpreadsheet()), {});
  ASSERT_EQ(r.size(), Trial().size());
  EXPECT_LT(GyroError(r), 1e-5 * kRadPerDegree);
  EXPECT_TRUE(r.has_accel());
}

TEST(AppCsv, MetricsOfTheGyroOnlyFilesAgreeWithTheQuotedExportWithItsAccelerometer) {
  // Without an accelerometer the attitude is levelled at the first impact (a warning).
  const ScratchDir dir("app_metrics");
  const MetricsSummary with_accel =
      ComputeTrialMetrics(LoadRecording(dir.Write("trial.csv", QuotedSpreadsheet()), {}), Granite(), {});
  const MetricsSummary phyphox = ComputeTrialMetrics(LoadRecording(dir.Write("Gyroscope.csv", Phyphox()), {}), Granite(), {});
  ASSERT_TRUE(with_accel.ok()) << with_accel.message;
  ASSERT_TRUE(phyphox.ok()) << phyphox.message;
  EXPECT_THAT(::testing::PrintToString(phyphox.correction.warnings), HasSubstr("levelled at the first impact"));
  EXPECT_NEAR(phyphox.opmf.opmf, with_accel.opmf.opmf, 0.003);
  EXPECT_NEAR(phyphox.avrf.avrf / with_accel.avrf.avrf, 1.0, 0.01);
}

// ---- bad variants: where and what

std::string ReadError(const std::string& name, const std::string& text, const LoadOptions& options = {}) {
  const ScratchDir dir("app_bad");
  try {
    LoadRecording(dir.Write(name, text), options);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(AppCsvBadVariants, AMissingUnitIsReportedAtItsHeaderCell) {
  EXPECT_THAT(ReadError("g.csv", "\"Time (s)\",\"Gyroscope x\",\"Gyroscope y (rad/s)\",\"Gyroscope z (rad/s)\"\n0,1,2,3\n0.01,1,2,3\n"),
              AllOf(HasSubstr("g.csv:1:13:"), HasSubstr("no unit")));
}

TEST(AppCsvBadVariants, AChangingColumnCountIsReportedAtItsLine) {
  const std::string text = "time,seconds_elapsed,z,y,x\n1,0,0,0,0\n2,0,0,0,0,0\n";
  EXPECT_THAT(ReadError("Gyroscope.csv", text), AllOf(HasSubstr("Gyroscope.csv:3:"), HasSubstr("6 fields")));
}

TEST(AppCsvBadVariants, TimeGoingBackwardsIsReportedAtItsCell) {
  const std::string text = "\"Time (s)\",\"Gyroscope x (rad/s)\",\"Gyroscope y (rad/s)\",\"Gyroscope z (rad/s)\"\n"
                           "0.00,1,2,3\n0.01,1,2,3\n0.005,1,2,3\n";
  EXPECT_THAT(ReadError("g.csv", text), AllOf(HasSubstr("g.csv:4:1:"), HasSubstr("smaller than '0.01' on line 3")));
}

TEST(AppCsvBadVariants, ACounterThatRestartsIsNotTakenForAWrap) {
  // 4294967000 → 5000 is a wrap only if the step across it (5296 µs) is like the steps before (10 µs): it is not.
  const std::string text = "micros,gx [dps],gy [dps],gz [dps]\n4294966980,0,0,0\n4294966990,0,0,0\n4294967000,0,0,0\n5000,0,0,0\n";
  EXPECT_THAT(ReadError("log.csv", text), AllOf(HasSubstr("log.csv:5:1:"), HasSubstr("smaller than")));
}

TEST(AppCsvBadVariants, AMillisCounterWrapsAt2To32) {
  const ScratchDir dir("app_millis");
  const Recording r =
      LoadRecording(dir.Write("log.csv", "millis,gx [dps],gy [dps],gz [dps]\n4294967285,0,0,0\n4294967295,0,0,0\n9,0,0,0\n19,0,0,0\n"), {});
  ASSERT_EQ(r.size(), 4u);
  EXPECT_NEAR(r.t_s[3], 0.030, 1e-12);  // 9 + 2^32 − 4294967295 = 10 ms after the second
  EXPECT_NEAR(r.rate_hz, 100.0, 1e-9);
}

}  // namespace
}  // namespace rockfit::io
