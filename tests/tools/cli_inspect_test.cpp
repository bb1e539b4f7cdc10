// rockfit inspect through the real binary: the JSON keys of docs/file-formats.md §9, exit codes, and the bad-file corpus.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bad_recordings.hpp"
#include "cli_runner.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

using ::testing::HasSubstr;

TEST(CliInspect, HelpNamesThePathFormsAndOptions) {
  const CommandResult r = RunRockfit({"inspect", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, AllOf(HasSubstr("--rate"), HasSubstr("--mounting"), HasSubstr("--json"), HasSubstr("--columns"),
                           HasSubstr("x-IMU3")));
}

TEST(CliInspect, JsonHasTheDocumentedKeysForASyntheticSet) {
  const ScratchDir dir("cli_inspect_json");
  const GuiSpin spin = MakeGuiSpin(512, 256.0, 45.0);
  dir.Write("T_CalInertialAndMag.csv", spin.inertial);
  dir.Write("T_EulerAngles.csv", spin.euler);
  const CommandResult r = RunRockfit({"inspect", (dir / "T").string(), "--rate", "256", "--mounting", "x,-y,-z", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  for (const char* key : {"format", "rate_hz", "samples", "duration_s", "columns", "gaps", "warnings", "rate_source",
                          "ranges", "orientation_source", "mounting"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["format"], "ximu-gui");
  EXPECT_EQ(json["samples"], 512);
  EXPECT_DOUBLE_EQ(json["rate_hz"].get<double>(), 256.0);
  EXPECT_EQ(json["rate_source"], "option");
  EXPECT_DOUBLE_EQ(json["duration_s"].get<double>(), 511.0 / 256.0);
  EXPECT_EQ(json["mounting"], "x,-y,-z");
  EXPECT_EQ(json["columns"].size(), 9u);
  // Mounted upside down: block z = −sensor z, so the yaw rate reads negative.
  const auto w_z = json["ranges"]["w_B_rad_s"]["z"];
  EXPECT_LT(w_z[1].get<double>(), 0.0);
  EXPECT_TRUE(json["ranges"].contains("euler_zyx_rad"));
  EXPECT_TRUE(json["ranges"].contains("accel_B_m_s2"));
}

TEST(CliInspect, TextSummaryShowsRateSamplesAndAttitude) {
  const ScratchDir dir("cli_inspect_text");
  const GuiSpin spin = MakeGuiSpin(64, 256.0, 45.0);
  dir.Write("T_CalInertialAndMag.csv", spin.inertial);
  const CommandResult r = RunRockfit({"inspect", (dir / "T_CalInertialAndMag.csv").string(), "--rate", "256"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, AllOf(HasSubstr("format       ximu-gui"), HasSubstr("rate         256 Hz (from --rate)"),
                           HasSubstr("samples      64 over 0.2461 s"), HasSubstr("attitude     none"),
                           HasSubstr("warnings     none")));
}

TEST(CliInspect, BadOptionsAreUsageErrors) {
  const ScratchDir dir("cli_inspect_usage");
  dir.Write("T_CalInertialAndMag.csv", MakeGuiSpin(8, 256.0, 1.0).inertial);
  const std::string path = (dir / "T").string();
  EXPECT_EQ(RunRockfit({"inspect", path, "--rate", "256", "--mounting", "x,y,-z"}).exit_code, 1);
  EXPECT_THAT(RunRockfit({"inspect", path, "--rate", "256", "--mounting", "x,y,-z"}).err, HasSubstr("mirror image"));
  EXPECT_EQ(RunRockfit({"inspect", path, "--rate", "-1"}).exit_code, 1);
  EXPECT_EQ(RunRockfit({"inspect", path, "--rate", "256", "--orientation", "sideways"}).exit_code, 1);
  EXPECT_EQ(RunRockfit({"inspect"}).exit_code, 1);
}

TEST(CliInspect, EveryCraftedBadFileExitsWithCodeTwoAndItsMessage) {
  for (const BadRecordingCase& c : BadRecordingCorpus()) {
    SCOPED_TRACE(c.name);
    const ScratchDir dir("cli_bad_" + c.name);
    for (const auto& [name, bytes] : c.files) dir.Write(name, bytes);
    std::vector<std::string> args = {"inspect", (dir / c.load).string(), "--json"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CommandResult r = RunRockfit(args);
    if (c.repaired) {
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const auto json = nlohmann::json::parse(r.out);
      std::string warnings;
      for (const auto& warning : json["warnings"]) warnings += warning.get<std::string>() + "\n";
      for (const std::string& fragment : c.fragments) EXPECT_THAT(warnings, HasSubstr(fragment));
      continue;
    }
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    for (const std::string& fragment : c.fragments) EXPECT_THAT(r.err, HasSubstr(fragment));
  }
}

TEST(CliInspect, RealOscillatorySetNeedsARateAndLoadsWithRate256) {
  ROCKFIT_REQUIRE_REAL_IMU();
  const std::string prefix = (RealImuDir() / "Oscillatory-Motion-Tracking-With-x-IMU/LoggedData/LoggedData").string();
  const CommandResult without = RunRockfit({"inspect", prefix});
  EXPECT_EQ(without.exit_code, 2);
  EXPECT_THAT(without.err, AllOf(HasSubstr("Pass --rate HZ"), HasSubstr("suggests --rate 256")));
  const CommandResult with = RunRockfit({"inspect", prefix, "--rate", "256", "--json"});
  ASSERT_EQ(with.exit_code, 0) << with.err;
  const auto json = nlohmann::json::parse(with.out);
  EXPECT_EQ(json["samples"], 11617);
  EXPECT_DOUBLE_EQ(json["duration_s"].get<double>(), 11616.0 / 256.0);
}

TEST(CliInspect, RealXimu3LogReportsItsDroppedMessagesAsGaps) {
  ROCKFIT_REQUIRE_REAL_IMU();
  const CommandResult r = RunRockfit({"inspect", (RealImuDir() / "x-IMU3-CSV/Logged Data").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["format"], "ximu3");
  EXPECT_EQ(json["samples"], 362);
  EXPECT_EQ(json["rate_source"], "timestamps");
  ASSERT_EQ(json["gaps"].size(), 4u);
  for (const auto& gap : json["gaps"]) EXPECT_EQ(gap["missing"], 1);
}

}  // namespace
}  // namespace rockfit::testing
