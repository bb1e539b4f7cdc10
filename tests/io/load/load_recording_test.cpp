#include "rockfit/io/load_recording.hpp"

#include <fstream>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bad_recordings.hpp"
#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

// Data lines of a CSV file (all lines but the header and blank ones), counted here, not by the reader.
std::size_t CountDataLines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::size_t lines = 0;
  while (std::getline(in, line)) {
    if (!line.empty()) ++lines;
  }
  return lines - 1;
}

LoadOptions OptionsFromArgs(const std::vector<std::string>& args) {
  LoadOptions options;
  for (std::size_t k = 0; k + 1 < args.size(); k += 2) {
    if (args[k] == "--rate") options.rate_hz = std::stod(args[k + 1]);
    else if (args[k] == "--columns") options.columns = ColumnMap::Parse(args[k + 1]);
    else if (args[k] == "--orientation") options.orientation = *ParseOrientationChoice(args[k + 1]);
    else if (args[k] == "--mounting") options.mounting = Mounting::Parse(args[k + 1]);
    else ADD_FAILURE() << "unknown option " << args[k];
  }
  return options;
}

TEST(LoadRecording, EveryRealRecordingLoadsWithItsSampleCountRateAndDuration) {
  ROCKFIT_REQUIRE_REAL_IMU();
  const auto real = testing::RealImuDir();
  LoadOptions at_256;
  at_256.rate_hz = 256.0;  // the x-IMU GUI sets have no _Registers.csv (see their READMEs)

  const auto oscillatory = real / "Oscillatory-Motion-Tracking-With-x-IMU/LoggedData";
  const std::size_t n_oscillatory = CountDataLines(oscillatory / "LoggedData_CalInertialAndMag.csv");
  EXPECT_EQ(n_oscillatory, 11617u);  // README: 11 617 rows, 45.4 s
  for (const auto& path : {oscillatory / "LoggedData", oscillatory / "LoggedData_EulerAngles.csv", oscillatory}) {
    const Recording r = LoadRecording(path, at_256);
    EXPECT_EQ(r.format, "ximu-gui") << path;
    EXPECT_EQ(r.size(), n_oscillatory);
    EXPECT_EQ(r.euler_zyx.size(), n_oscillatory);
    EXPECT_EQ(r.accel_B.size(), n_oscillatory);
    EXPECT_DOUBLE_EQ(r.rate_hz, 256.0);
    EXPECT_DOUBLE_EQ(r.duration_s(), static_cast<double>(n_oscillatory - 1) / 256.0);
    EXPECT_TRUE(r.gaps.empty());
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  }

  const auto gait = real / "Gait-Tracking-With-x-IMU/Datasets/straightLine_CalInertialAndMag.csv";
  const std::size_t n_gait = CountDataLines(gait);
  EXPECT_EQ(n_gait, 9963u);  // README: 9 963 rows, 38.9 s
  const Recording walk = LoadRecording(gait, at_256);
  EXPECT_EQ(walk.format, "ximu-gui");
  EXPECT_EQ(walk.size(), n_gait);
  EXPECT_DOUBLE_EQ(walk.duration_s(), static_cast<double>(n_gait - 1) / 256.0);
  EXPECT_FALSE(walk.has_euler());  // only the inertial CSV was published

  const auto ximu3 = real / "x-IMU3-CSV/Logged Data/x-IMU3 673B204B (UDP)";
  const std::size_t n_ximu3 = CountDataLines(ximu3 / "Inertial.csv");
  EXPECT_EQ(n_ximu3, 362u);  // README: 362 rows, 7.3 s, 50 Hz
  for (const auto& path : {ximu3, ximu3 / "Inertial.csv", ximu3.parent_path()}) {
    const Recording r = LoadRecording(path);
    EXPECT_EQ(r.format, "ximu3") << path;
    EXPECT_EQ(r.size(), n_ximu3);
    EXPECT_NEAR(r.rate_hz, 50.0, 0.05);
    EXPECT_NEAR(r.duration_s(), 7.2965, 1e-4);
    EXPECT_EQ(r.gaps.size(), 4u);
  }
}

TEST(LoadRecording, RealXimuGuiSetsWithoutRegistersAskForTheRate) {
  ROCKFIT_REQUIRE_REAL_IMU();
  for (const char* path : {"Oscillatory-Motion-Tracking-With-x-IMU/LoggedData/LoggedData",
                           "Gait-Tracking-With-x-IMU/Datasets/straightLine_CalInertialAndMag.csv"}) {
    try {
      LoadRecording(testing::RealImuDir() / path);
      ADD_FAILURE() << path << " loaded without a rate";
    } catch (const BadInput& e) {
      EXPECT_THAT(e.what(), AllOf(HasSubstr("_Registers.csv"), HasSubstr("Pass --rate HZ")));
    }
  }
}

TEST(LoadRecording, EveryCraftedBadFileGivesItsMessageOrItsDocumentedRepair) {
  for (const testing::BadRecordingCase& c : testing::BadRecordingCorpus()) {
    SCOPED_TRACE(c.name);
    const testing::ScratchDir dir("bad_" + c.name);
    for (const auto& [name, bytes] : c.files) dir.Write(name, bytes);
    const LoadOptions options = OptionsFromArgs(c.args);
    if (c.repaired) {
      const Recording r = LoadRecording(dir / c.load, options);
      EXPECT_GT(r.size(), 0u);
      std::string warnings;
      for (const std::string& warning : r.warnings) warnings += warning + "\n";
      for (const std::string& fragment : c.fragments) EXPECT_THAT(warnings, HasSubstr(fragment));
      continue;
    }
    try {
      LoadRecording(dir / c.load, options);
      ADD_FAILURE() << "loaded without complaint";
    } catch (const BadInput& e) {
      for (const std::string& fragment : c.fragments) EXPECT_THAT(e.what(), HasSubstr(fragment));
    }
  }
}

TEST(LoadRecording, TruncatedAndCrlfFilesGiveTheSameSamplesAsTheCleanFile) {
  const testing::ScratchDir dir("load_same");
  const testing::GuiSpin spin = testing::MakeGuiSpin(40, 256.0, 20.0);
  std::string crlf;
  for (char c : spin.inertial) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  dir.Write("a/S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("b/S_CalInertialAndMag.csv", crlf + "40,0.1,0.");
  LoadOptions options;
  options.rate_hz = 256.0;
  const Recording clean = LoadRecording(dir / "a/S", options);
  const Recording repaired = LoadRecording(dir / "b/S", options);
  ASSERT_EQ(repaired.size(), clean.size());
  for (std::size_t k = 0; k < clean.size(); ++k) EXPECT_EQ(repaired.w_B[k], clean.w_B[k]);
  EXPECT_EQ(repaired.warnings.size(), 1u);
}

TEST(LoadRecording, RandomlyDamagedFilesLoadOrThrowBadInputButNeverAnythingElse) {
  // Byte-level damage (deleted, replaced, inserted bytes) to a small set of each format, with a fixed
  // seed: every outcome must be a Recording or a BadInput, never a crash or another exception.
  const testing::ScratchDir dir("load_damage");
  const testing::GuiSpin spin = testing::MakeGuiSpin(12, 256.0, 20.0, 2);
  const std::vector<std::pair<std::string, std::string>> originals = {
      {"S_CalInertialAndMag.csv", spin.inertial}, {"S_EulerAngles.csv", spin.euler},
      {"x3/Inertial.csv", testing::MakeXimu3Inertial({19990, 19990, 39980, 19990})}};
  std::mt19937 random(20240601u);
  std::string alphabet = "0123456789,.;-+eENa \r\n\t\xef";
  alphabet.push_back('\0');
  std::size_t loaded = 0;
  std::size_t refused = 0;
  for (const auto& [name, text] : originals) dir.Write(name, text);
  for (int trial = 0; trial < 150; ++trial) {
    const auto& [name, text] = originals[static_cast<std::size_t>(trial) % originals.size()];
    std::string damaged = text;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits && !damaged.empty(); ++e) {
      const std::size_t at = random() % damaged.size();
      const char byte = alphabet[random() % alphabet.size()];
      switch (random() % 3) {
        case 0: damaged.erase(at, 1 + random() % 8); break;
        case 1: damaged[at] = byte; break;
        default: damaged.insert(at, 1, byte); break;
      }
    }
    dir.Write(name, damaged);
    LoadOptions options;
    if (name.rfind("x3/", 0) != 0) options.rate_hz = 256.0;
    try {
      const Recording r = LoadRecording(dir / (name.rfind("x3/", 0) == 0 ? "x3" : "S"), options);
      EXPECT_EQ(r.w_B.size(), r.t_s.size());
      for (const auto& w : r.w_B) EXPECT_TRUE(w.allFinite());
      ++loaded;
    } catch (const BadInput&) {
      ++refused;
    }
    dir.Write(name, text);
  }
  EXPECT_GT(loaded, 0u);
  EXPECT_GT(refused, 0u);
}

TEST(LoadRecording, HdfFilesAreSentToTheHdf5StoreAndColumnMapsOnlyFitCsvFiles) {
  const testing::ScratchDir dir("load_hdf5");
  dir.Write("trial.h5", "not really");
  EXPECT_THROW(LoadRecording(dir / "trial.h5"), BadInput);
  const testing::GuiSpin spin = testing::MakeGuiSpin(10, 256.0, 20.0);
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  LoadOptions options;
  options.rate_hz = 256.0;
  options.columns = ColumnMap::Parse("gyro=Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)");
  EXPECT_THROW(LoadRecording(dir / "S", options), InvalidArgument);
  options.format = RecordingFormat::kGenericCsv;
  const Recording generic = LoadRecording(dir / "S_CalInertialAndMag.csv", options);
  EXPECT_EQ(generic.format, "generic-csv");
  EXPECT_EQ(generic.size(), 10u);
}

}  // namespace
}  // namespace rockfit::io
