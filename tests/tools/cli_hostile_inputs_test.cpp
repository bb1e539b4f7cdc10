// Hostile sizes, special files and impossible parameters, given to the real `rockfit` binary under a virtual
// memory limit of 2 GB (ulimit -v): each ends at once with its documented exit code and a message that names
// the option or file (and the limit), never with a hang, a crash, a replaced device or "please report".
// Device nodes are made with mknod in the test's own directory (never under /dev); without root those cases are
// skipped. Not run under the sanitizers (.ci/run): their shadow memory does not fit the limit.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "scratch_dir.hpp"
#include "special_files.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

constexpr unsigned long kVirtualMemoryKib = 2000000;  // the ulimit -v of the hostile runs

CommandResult RunLimited(const std::vector<std::string>& args) { return RunRockfit(args, {}, kVirtualMemoryKib); }

std::string SampleRecord() { return (SourceDir() / "data-samples/ground-motions/cp-seed1-0.30g.AT2").string(); }

const std::vector<std::string> kBlock{"--b1", "0.05", "--b2", "0.05", "--h", "0.2", "--density", "2692"};

std::vector<std::string> Join(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

void ExpectRefused(const CommandResult& r, int exit_code, const std::string& words) {
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Please report"), std::string::npos) << r.err;
}

TEST(HostileInputs, OutputOntoDeviceNodesFifoOrSocketIsRefusedAndTheNodeStays) {
  const ScratchDir dir("hostile_output");
  const bool root = MakeCharacterDevice(dir / "null", kNullDeviceMajor, kNullDeviceMinor) &&
                    MakeCharacterDevice(dir / "full", kFullDeviceMajor, kFullDeviceMinor);
  ASSERT_TRUE(MakeFifo(dir / "fifo"));
  ASSERT_TRUE(MakeSocketFile(dir / "socket"));
  std::vector<std::string> targets{"fifo", "socket"};
  if (root) targets.insert(targets.end(), {"null", "full"});
  for (const std::string& name : targets) {
    const mode_t type = FileTypeOf(dir / name);
    ExpectRefused(RunLimited({"ground-motion", "synth", "--duration", "2", "-o", (dir / name).string()}), 4,
                  "not a regular file");
    ExpectRefused(RunLimited(Join({"respond", "--record", SampleRecord(), "-o", (dir / name).string()}, kBlock)), 4,
                  "not a regular file");
    EXPECT_EQ(FileTypeOf(dir / name), type) << name << " was replaced";
  }
  if (!root) GTEST_SKIP() << "the device cases need root (mknod)";
}

TEST(HostileInputs, OutputThroughASymlinkReplacesTheFileItNamesAndKeepsTheLink) {
  const ScratchDir dir("hostile_symlink");
  std::filesystem::create_symlink("real.AT2", dir / "link.AT2");
  const CommandResult r = RunLimited({"ground-motion", "synth", "--duration", "2", "-o", (dir / "link.AT2").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.AT2"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "real.AT2"));
}

TEST(HostileInputs, SpecialFilesAsInputsAreRefusedAtOnceWithExit2) {
  const ScratchDir dir("hostile_inputs");
  ASSERT_TRUE(MakeFifo(dir / "fifo.AT2"));
  ASSERT_TRUE(MakeFifo(dir / "fifo.csv"));
  ASSERT_TRUE(MakeFifo(dir / "fifo.toml"));
  std::filesystem::create_directory(dir / "dir.AT2");
  const auto start = std::chrono::steady_clock::now();
  ExpectRefused(RunLimited(Join({"respond", "--record", (dir / "fifo.AT2").string()}, kBlock)), 2, "a FIFO (named pipe)");
  ExpectRefused(RunLimited(Join({"respond", "--record", (dir / "fifo.csv").string(), "--dt", "0.01"}, kBlock)), 2,
                "a FIFO (named pipe)");
  ExpectRefused(RunLimited({"summary", (dir / "fifo.toml").string()}), 2, "a FIFO (named pipe)");
  ExpectRefused(RunLimited({"inspect", (dir / "fifo.csv").string()}), 2, "FIFO");
  ExpectRefused(RunLimited(Join({"respond", "--record", (dir / "dir.AT2").string()}, kBlock)), 2, "found a directory");
  ExpectRefused(RunLimited({"summary", (dir / "dir.AT2").string()}), 2, "found a directory");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(60));  // no run waited for a writer
  if (MakeCharacterDevice(dir / "zero", 1, 5) && MakeCharacterDevice(dir / "urandom", 1, 9)) {  // /dev/zero, urandom
    ExpectRefused(RunLimited(Join({"respond", "--record", (dir / "zero").string()}, kBlock)), 2, "a character device");
    ExpectRefused(RunLimited(Join({"respond", "--record", (dir / "urandom").string(), "--record-format", "csv", "--dt",
                                   "0.01"}, kBlock)), 2, "a character device");
  }
}

TEST(HostileInputs, RecordFileAboveTheSizeLimitIsRefusedBeforeItIsRead) {
  const ScratchDir dir("hostile_large");
  dir.Write("big.AT2", "");
  std::filesystem::resize_file(dir / "big.AT2", (std::uintmax_t{256} << 20) + 1);  // sparse: no disk, never read
  ExpectRefused(RunLimited(Join({"respond", "--record", (dir / "big.AT2").string()}, kBlock)), 2, "up to 268 MB");
}

TEST(HostileInputs, CountsFromOptionsAboveTheirLimitsAreRefusedBeforeAllocation) {
  const ScratchDir dir("hostile_counts");
  const std::string out = (dir / "x.h5").string();
  const std::vector<std::string> fragility = Join({"fragility", "--record", SampleRecord(), "-o", out}, kBlock);
  ExpectRefused(RunLimited(Join(fragility, {"--pga", "0.1:0.5:1000000000", "--samples", "1"})), 1,
                "more than the 1000 a study may have");
  ExpectRefused(RunLimited(Join(fragility, {"--pga", "0.1,0.2", "--samples", "2000000000"})), 1,
                "more than the 1000000 a study may have");
  ExpectRefused(RunLimited(Join({"fragility", "--synthetic-records", "100000000", "--pga", "0.1,0.2", "-o", out}, kBlock)),
                1, "more than the 10000 records a study may have");
  ExpectRefused(RunLimited(Join({"fragility", "--synthetic-records", "9000", "--pga", "0.1,0.2", "-o", out}, kBlock)), 1,
                "more than the 20000000 a study may hold");
  ExpectRefused(RunLimited(Join({"respond", "--synthetic", "1", "--synthetic-duration", "499000"}, kBlock)), 1,
                "more than the 10000000 of the largest record");
  ExpectRefused(RunLimited(Join({"respond", "--synthetic", "1", "--synthetic-duration", "20000"}, kBlock)), 1,
                "lower --synthetic-duration or --rate");
  ExpectRefused(RunLimited(Join(fragility, {"--pga", "0.1,0.2", "--tail", "1e9"})), 1, "lower --tail or --rate");
  ExpectRefused(RunLimited(Join({"simulate", "--alpha", "0.1", "--t-max", "99999", "--rate", "1000"}, kBlock)), 1,
                "--t-max and --rate ask for 99999000 samples");
  ExpectRefused(RunLimited(Join({"synth", "--alpha", "0.1", "--t0", "1", "--duration", "300000", "-o",
                                 (dir / "trial").string()}, kBlock)), 1, "--duration and --rate ask for 76800000");
}

TEST(HostileInputs, AllocationFailureIsOutOfMemoryNamingTheStepNotPleaseReport) {
  // Within every limit (9·10⁶ samples, 9·10⁵ response samples at 20 Hz) but not within 350 MB of address space.
  const CommandResult r = RunRockfit(Join({"respond", "--synthetic", "1", "--synthetic-duration", "45000", "--rate",
                                           "20"}, kBlock), {}, 350000);
  ExpectRefused(r, 3, "rockfit: out of memory while ");
}

TEST(HostileInputs, DeepDottedTomlKeyIsRefusedWithoutACrash) {
  const ScratchDir dir("hostile_toml");
  std::string key = "a";
  for (int k = 1; k < 40000; ++k) key += ".a";
  dir.Write("m.toml", key + " = 1\n");
  ExpectRefused(RunLimited({"summary", (dir / "m.toml").string()}), 2, "m.toml:1:128: a dotted key");
  ExpectRefused(RunLimited({"batch", (dir / "m.toml").string(), "-o", (dir / "b.h5").string()}), 2, "more than 64 parts");
}

TEST(HostileInputs, ImpossibleGeneratorParametersAreRefusedNamingTheParameter) {
  const ScratchDir dir("hostile_synth");
  const std::string out = (dir / "wf.AT2").string();
  ExpectRefused(RunLimited({"ground-motion", "synth", "--omega-f", "1000", "-o", out}), 1, "omega_f = 1000 rad/s");
  ExpectRefused(RunLimited({"ground-motion", "synth", "--omega-g", "1000", "-o", out}), 1, "omega_g = 1000 rad/s");
  ExpectRefused(RunLimited({"ground-motion", "synth", "--zeta-g", "1e300", "-o", out}), 1, "zeta_g = 1e+300");
  ExpectRefused(RunLimited({"ground-motion", "synth", "--dt", "100", "-o", out}), 1, "at least two samples");
  ExpectRefused(RunLimited({"ground-motion", "synth", "--pga", "-1", "-o", out}), 1, "--pga must be a positive");
  EXPECT_FALSE(std::filesystem::exists(out));
  // The edge of the allowed region writes a record that rockfit reads back.
  ASSERT_EQ(RunLimited({"ground-motion", "synth", "--omega-g", "400", "--zeta-g", "1", "-o", out}).exit_code, 0);
  EXPECT_EQ(RunLimited({"ground-motion", "inspect", out}).exit_code, 0);
}

TEST(HostileInputs, BadRecordValuesAndStepsNameTheFileOrOptionAndExistingOptionsOnly) {
  const ScratchDir dir("hostile_records");
  const std::string big = dir.Write("big.AT2", "a\nb\nc\nNPTS=  3, DT= .01 SEC\n  0.1  1e308  0.2\n").string();
  ExpectRefused(RunLimited(Join({"respond", "--record", big}, kBlock)), 2, "big.AT2:5:8: acceleration value 2");
  const std::string slow = dir.Write("slow.AT2", "a\nb\nc\nNPTS=  3, DT= 1e300 SEC\n  0.1  0.3  0.2\n").string();
  const CommandResult respond = RunLimited(Join({"respond", "--record", slow}, kBlock));
  ExpectRefused(respond, 2, "slow.AT2: the record lasts");
  EXPECT_EQ(respond.err.find("--t-max"), std::string::npos) << respond.err;
  ExpectRefused(RunLimited(Join({"fragility", "--record", slow, "--pga", "0.1,0.2", "-o", (dir / "f.h5").string()},
                                kBlock)), 2, "slow.AT2: the record lasts");
  const std::string csv = dir.Write("notime.csv", "x\n0.1\n0.2\n0.1\n").string();
  for (const char* dt : {"0", "-1", "nan"}) {
    ExpectRefused(RunLimited(Join({"respond", "--record", csv, "--dt", dt}, kBlock)), 1, "--dt must be a positive");
  }
  ExpectRefused(RunLimited(Join({"respond", "--record", csv, "--dt", "1e300"}, kBlock)), 2, "check DT (and --dt)");
  const std::string twice = dir.Write("xx.csv", "x,x\n0.1,0.2\n0.2,0.1\n").string();
  ExpectRefused(RunLimited(Join({"respond", "--record", twice, "--dt", "0.01"}, kBlock)), 2,
                "a second column for the first horizontal component (x), which column 1 'x' already is");
}

TEST(HostileInputs, FragilityWithoutOneCountedSampleIsANumericalFailureNotASilentSuccess) {
  const ScratchDir dir("hostile_uncounted");
  ExpectRefused(RunLimited(Join({"fragility", "--synthetic-records", "1", "--synthetic-duration", "2", "--scale",
                                 "1e300,1e305", "--samples", "2", "-o", (dir / "f.h5").string()}, kBlock)), 3,
                "none of the 4 samples gave an outcome that counts (4 failed)");
}

TEST(HostileInputs, DirectoryWhereTheJournalGoesIsBadInputNotAnInternalError) {
  const ScratchDir dir("hostile_journal");
  const std::string out = (dir / "f.h5").string();
  std::filesystem::create_directory(out + ".journal");
  ExpectRefused(RunLimited(Join({"fragility", "--record", SampleRecord(), "--pga", "0.1,0.2", "--samples", "1", "-o",
                                 out}, kBlock)), 2, "found a directory, expected a rockfit journal");
}

}  // namespace
}  // namespace rockfit::testing
