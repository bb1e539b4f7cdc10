#include "load/format_detection.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;

std::string DetectError(const std::filesystem::path& path) {
  try {
    DetectRecordingSource(path);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(DetectRecordingSource, FindsAnXimuGuiSetFromItsPrefixAnyOfItsFilesOrItsDirectory) {
  const ScratchDir dir("detect_gui");
  dir.Write("my_trial_1_CalInertialAndMag.csv", "x");
  dir.Write("my_trial_1_EulerAngles.csv", "x");
  for (const auto& path : {dir / "my_trial_1", dir / "my_trial_1_EulerAngles.csv", dir.path()}) {
    const DetectedSource source = DetectRecordingSource(path);
    EXPECT_EQ(source.format, RecordingFormat::kXimuGui) << path;
    EXPECT_EQ(source.path, dir / "my_trial_1") << path;
  }
}

TEST(DetectRecordingSource, ADirectoryWithSeveralGuiSetsNeedsAPrefix) {
  const ScratchDir dir("detect_two");
  dir.Write("00000_CalInertialAndMag.csv", "x");
  dir.Write("00001_CalInertialAndMag.csv", "x");
  EXPECT_THAT(DetectError(dir.path()), AllOf(HasSubstr("several x-IMU recordings: '00000', '00001'"),
                                             HasSubstr("00000.")));
}

TEST(DetectRecordingSource, FindsAnXimu3DirectoryFromItselfItsFilesOrItsParent) {
  const ScratchDir dir("detect_x3");
  const auto device = dir / "x-IMU3 673B204B (UDP)";
  dir.Write("x-IMU3 673B204B (UDP)/Inertial.csv", "x");
  dir.Write("x-IMU3 673B204B (UDP)/EulerAngles.csv", "x");
  for (const auto& path : {device, device / "EulerAngles.csv", dir.path()}) {
    const DetectedSource source = DetectRecordingSource(path);
    EXPECT_EQ(source.format, RecordingFormat::kXimu3) << path;
    EXPECT_EQ(source.path, device) << path;
  }
  dir.Write("other device/Inertial.csv", "x");
  EXPECT_THAT(DetectError(dir.path()), HasSubstr("x-IMU3 logs of several devices"));
}

TEST(DetectRecordingSource, OtherFilesAreGenericCsvOrHdf5AndBinariesAreRefused) {
  const ScratchDir dir("detect_other");
  dir.Write("walk.csv", "x");
  dir.Write("EulerAngles.csv", "x");  // no Inertial.csv beside it: just a CSV file
  dir.Write("trial.H5", "x");
  dir.Write("00000.BIN", "x");
  dir.Write("log.ximu3", "x");
  EXPECT_EQ(DetectRecordingSource(dir / "walk.csv").format, RecordingFormat::kGenericCsv);
  EXPECT_EQ(DetectRecordingSource(dir / "EulerAngles.csv").format, RecordingFormat::kGenericCsv);
  EXPECT_EQ(DetectRecordingSource(dir / "trial.H5").format, RecordingFormat::kRockfitHdf5);
  EXPECT_THAT(DetectError(dir / "00000.BIN"), HasSubstr("SD Card tab"));
  EXPECT_THAT(DetectError(dir / "log.ximu3"), HasSubstr("file converter"));
  EXPECT_THAT(DetectError(dir / "missing"), HasSubstr("no such file, directory or x-IMU prefix"));
  std::filesystem::create_directories(dir / "empty");
  EXPECT_THAT(DetectError(dir / "empty"), HasSubstr("found a directory without a recording"));
}

TEST(DetectRecordingSource, AForcedFormatStillResolvesThePath) {
  const ScratchDir dir("detect_forced");
  dir.Write("S_CalInertialAndMag.csv", "x");
  EXPECT_EQ(DetectRecordingSource(dir / "S_CalInertialAndMag.csv", RecordingFormat::kGenericCsv).path,
            dir / "S_CalInertialAndMag.csv");
  EXPECT_EQ(DetectRecordingSource(dir / "S_CalInertialAndMag.csv", RecordingFormat::kXimuGui).path, dir / "S");
  EXPECT_EQ(DetectRecordingSource(dir / "Inertial.csv", RecordingFormat::kXimu3).path, dir.path());
}

}  // namespace
}  // namespace rockfit::io
