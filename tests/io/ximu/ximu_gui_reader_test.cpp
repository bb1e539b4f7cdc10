#include "ximu/ximu_gui_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "csv_numbers.hpp"
#include "imu_test_files.hpp"
#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "rockfit/io/units.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;
using testing::GuiSpin;
using testing::MakeGuiSpin;
using testing::ScratchDir;

// Angles printed with 7 significant digits of degrees (≤ 360°): rounding below 4e-5° ≈ 1e-6 rad.
constexpr double kPrintedAngle_rad = 2e-6;
// The quaternion printed with 7 digits: each element ±5e-8, an angle error of ~2e-7 rad.
constexpr double kPrintedQuaternion_rad = 1e-6;
// docs/design.md §12: angles from the Euler file and from the quaternion file agree to this.
constexpr double kEulerVsQuaternion_rad = 1e-4;

double Wrapped(double angle) { return std::remainder(angle, 2.0 * kPi); }

LoadOptions WithRate(double rate_hz) {
  LoadOptions options;
  options.rate_hz = rate_hz;
  return options;
}

std::string LoadError(const XimuGuiFileSet& files, const LoadOptions& options) {
  try {
    ReadXimuGuiRecording(files, options);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(ReadXimuGuiRecording, TimeIsRowOverRateAndAttitudeIsTheSpinThatWasWritten) {
  const ScratchDir dir("gui_spin");
  const GuiSpin spin = MakeGuiSpin(600, 256.0, 90.0);  // passes yaw ±180° at t = 2 s
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_EulerAngles.csv", spin.euler);
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0));
  ASSERT_EQ(r.size(), 600u);
  EXPECT_EQ(r.rate_source, RateSource::kOption);
  EXPECT_DOUBLE_EQ(r.t_s[599], 599.0 / 256.0);
  EXPECT_DOUBLE_EQ(r.orientation_rate_hz, 256.0);
  for (std::size_t k = 0; k < r.size(); k += 37) {
    EXPECT_NEAR(r.euler_zyx[k][0], spin.yaw_deg[k] * kRadPerDeg, kPrintedAngle_rad) << k;  // unwrapped past 180°
    EXPECT_NEAR(r.euler_zyx[k][1], -3.0 * kRadPerDeg, kPrintedAngle_rad);
    EXPECT_NEAR(r.euler_zyx[k][2], 5.0 * kRadPerDeg, kPrintedAngle_rad);
    EXPECT_NEAR(r.w_B[k].norm(), 90.0 * kRadPerDeg, 1e-6);
    EXPECT_NEAR(r.accel_B[k].z(), kMetresPerSecond2PerG, 1e-12);
  }
  EXPECT_TRUE(r.warnings.empty());
}

TEST(ReadXimuGuiRecording, AnInertialRowMissingBetweenTwoAttitudePacketsIsAGapInTheTimeBase) {
  const ScratchDir dir("gui_dropped_row");
  const GuiSpin spin = MakeGuiSpin(300, 256.0, 40.0);
  std::istringstream lines(spin.inertial);
  std::string line, inertial;
  for (int row = -1; std::getline(lines, line); ++row) {  // row −1: the header
    if (row != 100) inertial += line + "\n";
  }
  dir.Write("S_CalInertialAndMag.csv", inertial);
  dir.Write("S_Quaternion.csv", spin.quaternion);
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0));
  ASSERT_EQ(r.size(), 299u);
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].index, 99u);
  EXPECT_EQ(r.gaps[0].missing, 1u);
  EXPECT_DOUBLE_EQ(r.t_s[100], 101.0 / 256.0);  // the row after the gap at its own time
  EXPECT_DOUBLE_EQ(r.t_s[298], 299.0 / 256.0);
  EXPECT_THAT(r.warnings.front(), HasSubstr("1 inertial row(s) missing"));
}

TEST(ReadXimuGuiRecording, TheQuaternionFileIsTheConjugateOfTheAttitude) {
  const ScratchDir dir("gui_quaternion");
  const GuiSpin spin = MakeGuiSpin(300, 256.0, 40.0);
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_Quaternion.csv", spin.quaternion);
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0));
  EXPECT_EQ(r.orientation_source, "S_Quaternion.csv");
  for (std::size_t k = 0; k < r.size(); k += 29) {
    EXPECT_NEAR(r.euler_zyx[k][0], spin.yaw_deg[k] * kRadPerDeg, kPrintedQuaternion_rad);
    EXPECT_NEAR(r.euler_zyx[k][2], 5.0 * kRadPerDeg, kPrintedQuaternion_rad);  // +5°, not −5°
  }
}

TEST(ReadXimuGuiRecording, SlowerAttitudeIsPairedByPacketNumberAndInterpolated) {
  const ScratchDir dir("gui_slow_attitude");
  const GuiSpin spin = MakeGuiSpin(257, 256.0, 60.0, 2);  // attitude at 128 Hz after rows 0, 2, 4, …
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_EulerAngles.csv", spin.euler);
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0));
  ASSERT_EQ(r.size(), 257u);
  EXPECT_DOUBLE_EQ(r.orientation_rate_hz, 128.0);
  // Rows between attitude samples get the slerp of their neighbours: exact for a steady spin.
  for (std::size_t k = 1; k < r.size(); k += 2) {
    EXPECT_NEAR(r.euler_zyx[k][0], spin.yaw_deg[k] * kRadPerDeg, kPrintedAngle_rad) << k;
  }
}

TEST(ReadXimuGuiRecording, AttitudeEndingBeforeTheGyroTrimsTheRecordingWithAWarning) {
  const ScratchDir dir("gui_trim");
  const GuiSpin spin = MakeGuiSpin(100, 256.0, 60.0, 2);  // the last inertial row (99) has no attitude after it
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_EulerAngles.csv", spin.euler);
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0));
  EXPECT_EQ(r.size(), 99u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], HasSubstr("1 after it were dropped"));
  LoadOptions gyro_only = WithRate(256.0);
  gyro_only.orientation = OrientationChoice::kNone;
  EXPECT_EQ(ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), gyro_only).size(), 100u);
}

TEST(ReadXimuGuiRecording, RatesComeFromTheRegistersAndMustAgreeWithWhatIsGiven) {
  const ScratchDir dir("gui_registers");
  const GuiSpin spin = MakeGuiSpin(64, 128.0, 30.0);
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_Registers.csv", testing::kGuiRegistersHeader + "\n900,69,8,NaN,InertialAndMagneticDataRate\n"
                                                              "901,70,8,NaN,QuaternionDataRate\n");
  dir.Write("S_EulerAngles.csv", spin.euler);
  const XimuGuiFileSet files = XimuGuiFileSet::Find(dir / "S");
  const Recording r = ReadXimuGuiRecording(files, {});
  EXPECT_DOUBLE_EQ(r.rate_hz, 128.0);
  EXPECT_EQ(r.rate_source, RateSource::kRegisters);
  EXPECT_DOUBLE_EQ(r.orientation_rate_hz, 128.0);
  EXPECT_NO_THROW(ReadXimuGuiRecording(files, WithRate(128.0)));
  EXPECT_THAT(LoadError(files, WithRate(256.0)),
              AllOf(HasSubstr("S_Registers.csv:2:8: InertialAndMagneticDataRate (register 69): found 8 (128 Hz), "
                              "expected the rate given with --rate (256 Hz)")));
}

TEST(ReadXimuGuiRecording, WarnsAboutGyroscopeSamplesAtTheFullScaleOfRegister8) {
  const ScratchDir dir("gui_rail");
  dir.Write("S_CalInertialAndMag.csv", testing::kGuiInertialHeader +
                                           "\n0,0,0,0,0,0,1,0,0,0\n2,249.9375,0,0,0,0,1,0,0,0\n4,0,-250,0,0,0,1,0,0,0\n");
  dir.Write("S_Registers.csv", testing::kGuiRegistersHeader + "\n1,8,0,NaN,GyroscopeFullScale\n");
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], AllOf(HasSubstr("2 gyroscope sample(s) at the ±250 °/s full scale"), HasSubstr("line 3")));
}

TEST(ReadXimuGuiRecording, RefusesAttitudeRowsThatDisagreeWithTheQuaternionRateRegister) {
  const ScratchDir dir("gui_register70");
  const GuiSpin spin = MakeGuiSpin(64, 256.0, 30.0, 2);  // attitude at 128 Hz
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_EulerAngles.csv", spin.euler);
  dir.Write("S_Registers.csv", testing::kGuiRegistersHeader + "\n1,69,9,NaN,InertialAndMagneticDataRate\n"
                                                              "1,70,9,NaN,QuaternionDataRate\n");
  EXPECT_THAT(LoadError(XimuGuiFileSet::Find(dir / "S"), {}),
              AllOf(HasSubstr("S_Registers.csv:3:6: QuaternionDataRate (register 70): found 9 (256 Hz)"),
                    HasSubstr("the rate of the attitude rows in S_EulerAngles.csv")));
}

TEST(ReadXimuGuiRecording, WithoutARateSaysToPassOneAndWhatTheClockSuggests) {
  const ScratchDir dir("gui_no_rate");
  const GuiSpin spin = MakeGuiSpin(256 * 5, 256.0, 30.0);
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_DateTime.csv", spin.date_time);
  EXPECT_THAT(LoadError(XimuGuiFileSet::Find(dir / "S"), {}),
              AllOf(HasSubstr("S_CalInertialAndMag.csv: found no S_Registers.csv beside it"), HasSubstr("--rate HZ"),
                    HasSubstr("suggests --rate 256")));
}

TEST(ReadXimuGuiRecording, TheRealTimeClockCatchesAWrongRateAndReportsLostPackets) {
  const ScratchDir dir("gui_rtc");
  GuiSpin spin = MakeGuiSpin(256 * 5, 256.0, 30.0);
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_DateTime.csv", spin.date_time);
  const XimuGuiFileSet files = XimuGuiFileSet::Find(dir / "S");
  EXPECT_TRUE(ReadXimuGuiRecording(files, WithRate(256.0)).warnings.empty());
  EXPECT_THAT(LoadError(files, WithRate(128.0)),
              AllOf(HasSubstr("S_DateTime.csv: found 256 inertial rows per real-time-clock second"),
                    HasSubstr("expected 128 rows per second, the rate from --rate")));
  // Drop every 20th inertial row: 5 % lost, still 256 Hz.
  std::istringstream lines(spin.inertial);
  std::string line;
  std::string thinned;
  for (int k = 0; std::getline(lines, line); ++k) {
    if (k == 0 || k % 20 != 7) thinned += line + "\n";
  }
  dir.Write("S_CalInertialAndMag.csv", thinned);
  const Recording r = ReadXimuGuiRecording(files, WithRate(256.0));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], AllOf(HasSubstr("243"), HasSubstr("% of the inertial packets were lost")));
}

TEST(ReadXimuGuiRecording, RecomputesANaNPitchFromTheQuaternionOfTheSamePacket) {
  const ScratchDir dir("gui_nan_pitch");
  GuiSpin spin = MakeGuiSpin(20, 256.0, 30.0);
  std::string euler = spin.euler;
  const std::size_t line5 = [&] {
    std::size_t at = 0;
    for (int k = 0; k < 4; ++k) at = euler.find('\n', at) + 1;
    return at;
  }();
  const std::size_t pitch = euler.find(',', euler.find(',', line5) + 1) + 1;
  euler.replace(pitch, euler.find(',', pitch) - pitch, "NaN");
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_EulerAngles.csv", euler);
  EXPECT_THAT(LoadError(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0)),
              AllOf(HasSubstr("S_EulerAngles.csv:5:"), HasSubstr("found 'NaN', expected a finite pitch"),
                    HasSubstr("_Quaternion.csv")));
  dir.Write("S_Quaternion.csv", spin.quaternion);
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0));
  EXPECT_NEAR(r.euler_zyx[3][1], -3.0 * kRadPerDeg, kPrintedQuaternion_rad);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], AllOf(HasSubstr("S_EulerAngles.csv:5"), HasSubstr("recomputed from the quaternion")));
}

TEST(ReadXimuGuiRecording, MountingTurnsSensorAxesIntoBlockAxes) {
  const ScratchDir dir("gui_mounting");
  const GuiSpin spin = MakeGuiSpin(50, 256.0, 30.0);
  dir.Write("S_CalInertialAndMag.csv", spin.inertial);
  dir.Write("S_EulerAngles.csv", spin.euler);
  const XimuGuiFileSet files = XimuGuiFileSet::Find(dir / "S");
  const Recording sensor = ReadXimuGuiRecording(files, WithRate(256.0));
  LoadOptions options = WithRate(256.0);
  options.mounting = Mounting::Parse("x,-y,-z");
  const Recording block = ReadXimuGuiRecording(files, options);
  EXPECT_EQ(block.mounting, "x,-y,-z");
  for (std::size_t k = 0; k < block.size(); k += 7) {
    EXPECT_TRUE(block.w_B[k].isApprox(Eigen::Vector3d(sensor.w_B[k].x(), -sensor.w_B[k].y(), -sensor.w_B[k].z())));
    const Eigen::Matrix3d R_WB = RotationFromEulerZyx(sensor.euler_zyx[k]) * options.mounting.R_BS().transpose();
    EXPECT_TRUE(RotationFromEulerZyx(block.euler_zyx[k]).isApprox(R_WB, 1e-12));
  }
}

TEST(ReadXimuGuiRecording, RefusesAPacketNumberThatTwoFilesShare) {
  const ScratchDir dir("gui_shared_packet");
  dir.Write("S_CalInertialAndMag.csv", testing::kGuiInertialHeader + "\n0,0,0,0,0,0,1,0,0,0\n2,0,0,0,0,0,1,0,0,0\n");
  dir.Write("S_EulerAngles.csv", testing::kGuiEulerHeader + "\n1,0,0,0\n2,0,0,0\n");
  EXPECT_THAT(LoadError(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0)),
              AllOf(HasSubstr("S_EulerAngles.csv"), HasSubstr("packet number 2, which is also an inertial packet")));
}

TEST(ReadXimuGuiRecording, RawCountsOnlyAreRefusedWithTheReason) {
  const ScratchDir dir("gui_raw");
  dir.Write("S_RawInertialAndMag.csv", "Packet number,Gyroscope X (lsb)\n0,1\n");
  EXPECT_THAT(LoadError(XimuGuiFileSet::Find(dir / "S"), WithRate(256.0)),
              AllOf(HasSubstr("only raw sensor counts (lsb)"), HasSubstr("SensorDataMode")));
}

// --- the real recordings beside the checkout (RealImuDir(), skipped when absent) --------------

struct QuaternionRow {
  double packet = 0;
  double q[4] = {0, 0, 0, 0};
};

TEST(ReadXimuGuiRecording, RealOscillatoryEulerAnglesAgreeWithItsQuaternions) {
  ROCKFIT_REQUIRE_REAL_IMU();
  const auto prefix = testing::RealImuDir() / "Oscillatory-Motion-Tracking-With-x-IMU/LoggedData/LoggedData";
  const Recording r = ReadXimuGuiRecording(XimuGuiFileSet::Find(prefix), WithRate(256.0));
  ASSERT_EQ(r.orientation_source, "LoggedData_EulerAngles.csv");
  // Quaternion rows pair one to one with inertial rows (both 256 Hz, packet numbers odd/even).
  const auto quaternions = testing::ReadCsvNumbers(prefix.string() + "_Quaternion.csv");
  ASSERT_EQ(quaternions.size(), r.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const double q0 = quaternions[k][1], q1 = quaternions[k][2], q2 = quaternions[k][3], q3 = quaternions[k][4];
    // The GUI's own formulas (docs/file-formats.md §1.6) on the file quaternion, Earth relative to sensor.
    const double phi = std::atan2(2 * (q2 * q3 - q0 * q1), 2 * q0 * q0 - 1 + 2 * q3 * q3);
    const double s = 2 * (q1 * q3 + q0 * q2);
    const double theta = -std::atan(s / std::sqrt(1 - s * s));
    const double psi = std::atan2(2 * (q1 * q2 - q0 * q3), 2 * q0 * q0 - 1 + 2 * q1 * q1);
    worst = std::max({worst, std::abs(Wrapped(r.euler_zyx[k][0] - psi)), std::abs(r.euler_zyx[k][1] - theta),
                      std::abs(Wrapped(r.euler_zyx[k][2] - phi))});
  }
  EXPECT_LE(worst, kEulerVsQuaternion_rad);
  EXPECT_GT(worst, 0.0);  // the two files really are different data
  RecordProperty("max_euler_vs_quaternion_rad", testing::G7(worst));
}

TEST(ReadXimuGuiRecording, RealOscillatoryAttitudeIsTheSameFromEulerQuaternionAndMatrixFiles) {
  ROCKFIT_REQUIRE_REAL_IMU();
  const auto files = XimuGuiFileSet::Find(testing::RealImuDir() / "Oscillatory-Motion-Tracking-With-x-IMU/LoggedData/LoggedData");
  const Recording from_euler = ReadXimuGuiRecording(files, WithRate(256.0));
  for (OrientationChoice choice : {OrientationChoice::kQuaternion, OrientationChoice::kRotationMatrix}) {
    LoadOptions options = WithRate(256.0);
    options.orientation = choice;
    const Recording other = ReadXimuGuiRecording(files, options);
    ASSERT_EQ(other.size(), from_euler.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < other.size(); ++k) {
      worst = std::max(worst, (other.euler_zyx[k] - from_euler.euler_zyx[k]).cwiseAbs().maxCoeff());
    }
    EXPECT_LE(worst, kEulerVsQuaternion_rad) << OrientationChoiceName(choice);
  }
}

}  // namespace
}  // namespace rockfit::io
