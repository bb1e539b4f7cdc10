// A full disk and an unwritable directory: every writer gives a clear message and exit code 4, leaves no partial
// or temporary file, and leaves the old output intact. The full disk is a file-size limit (RLIMIT_FSIZE, set in
// the child before exec) below the size of the new output.
#include <algorithm>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_runner.hpp"
#include "process_control.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

constexpr int kExitCannotWrite = 4;

std::string SamplePath(const std::string& trial) {
  return (SourceDir() / "data-samples" / "recordings" / trial).string();
}

void WriteManifest(const ScratchDir& dir, const std::string& name, const std::vector<std::string>& trials) {
  std::string text = "[[blocks]]\nid = \"block2\"\nb1 = 0.05000453\nb2 = 0.035\nh = 0.2\ndensity = 2692\n";
  for (const std::string& id : trials) {
    text += fmt::format("\n[[trials]]\nid = \"{}\"\nblock = \"block2\"\nposition = \"{}\"\nfiles = \"{}\"\n", id,
                        id.substr(7, 1), SamplePath(id));
  }
  dir.Write(name, text);
}

struct FullDiskCase {
  std::string name;
  std::vector<std::string> old_args;
  std::vector<std::string> new_args;
  std::string output;  // the file checked (old intact); every file of the directory is checked for leftovers
};

void PrintTo(const FullDiskCase& c, std::ostream* os) { *os << c.name; }

std::vector<FullDiskCase> FullDiskCases() {
  const std::vector<std::string> simulate = {"simulate",  "--b1", "0.05",     "--b2", "0.04",   "--h", "0.2",
                                             "--density", "2692", "--lambda", "0.9",  "--stop", "rest"};
  const std::vector<std::string> synth = {"synth", "--b1",    "0.05", "--b2", "0.035", "--h", "0.2",  "--density",
                                          "2692",  "--alpha", "0.18", "--t0", "0.5",   "-o",  "trial"};
  auto with = [](std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  return {
      {"summary_hdf5", {"summary", "one.toml", "-o", "out.h5"}, {"summary", "two.toml", "-o", "out.h5"}, "out.h5"},
      {"correct_hdf5",
       {"correct", SamplePath("block2-A-1"), "-o", "out.h5"},
       {"correct", SamplePath("block2-A-2"), "--name", "x", "-o", "out.h5"},
       "out.h5"},
      {"correct_csv",
       {"correct", SamplePath("block2-A-1"), "-o", "out.csv"},
       {"correct", SamplePath("block2-A-2"), "-o", "out.csv"},
       "out.csv"},
      {"simulate_json", with(simulate, {"--alpha", "0.1", "-o", "sim.json"}),
       with(simulate, {"--alpha", "0.2", "-o", "sim.json"}), "sim.json"},
      {"simulate_hdf5", with(simulate, {"--alpha", "0.1", "--format", "hdf5", "-o", "sim.h5"}),
       with(simulate, {"--alpha", "0.2", "--format", "hdf5", "-o", "sim.h5"}), "sim.h5"},
      {"synth", with(synth, {"--duration", "2", "--seed", "1"}), with(synth, {"--duration", "4", "--seed", "2"}),
       "trial_CalInertialAndMag.csv"},
      {"plot_summary",
       {"plot", "summary", "one.toml", "-o", "summary.png"},
       {"plot", "summary", "two.toml", "-o", "summary.png"},
       "summary.png"},
  };
}

std::vector<std::string> Listing(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class FullDisk : public ::testing::TestWithParam<FullDiskCase> {};

TEST_P(FullDisk, FileSizeLimitGivesExitFourAndLeavesTheOldFileAndNoPartialFile) {
  const FullDiskCase& c = GetParam();
  const ScratchDir dir("full_disk_" + c.name);
  WriteManifest(dir, "one.toml", {"block2-A-1"});
  WriteManifest(dir, "two.toml", {"block2-A-1", "block2-B-1"});
  ASSERT_EQ(WaitForExit(StartRockfit(c.old_args, dir.path().string())), 0);
  const std::string old_bytes = ReadWholeFile(dir / c.output);
  const std::vector<std::string> before = Listing(dir.path());
  // The new output would be larger than the old one; a limit at half the old size stops every writer part-way
  // (an HDF5 transaction first copies the old file).
  const rlim_t limit = std::max<rlim_t>(old_bytes.size() / 2, 512);
  const std::string err_path = (dir.path().parent_path() / (dir.path().filename().string() + ".err")).string();
  const int code = WaitForExit(StartRockfit(c.new_args, dir.path().string(), err_path, {limit}));
  const std::string err = ReadWholeFile(err_path);
  std::filesystem::remove(err_path);
  EXPECT_EQ(code, kExitCannotWrite) << c.name << ": " << err;
  EXPECT_NE(err.find("rockfit: "), std::string::npos) << err;
  EXPECT_EQ(err.find("internal error"), std::string::npos) << err;
  EXPECT_NE(err.find(c.name == "synth" ? "trial_" : c.output), std::string::npos) << "names the file: " << err;
  EXPECT_EQ(ReadWholeFile(dir / c.output), old_bytes) << c.name << ": the old file changed";
  EXPECT_EQ(Listing(dir.path()), before) << c.name << ": a partial or temporary file was left";
  std::printf("%-14s limit %6zu B: exit %d, %s", c.name.c_str(), static_cast<std::size_t>(limit), code, err.c_str());
}

INSTANTIATE_TEST_SUITE_P(EveryWriter, FullDisk, ::testing::ValuesIn(FullDiskCases()),
                         [](const ::testing::TestParamInfo<FullDiskCase>& info) { return info.param.name; });

TEST(UnwritableDirectory, WritersGiveExitFourAndLeaveTheOldFile) {
  const ScratchDir dir("unwritable");
  WriteManifest(dir, "one.toml", {"block2-A-1"});
  ASSERT_EQ(WaitForExit(StartRockfit({"summary", "one.toml", "-o", "out.h5"}, dir.path().string())), 0);
  // A directory the process cannot create files in. Root ignores permission bits, so root gets /proc, where no
  // one can create a file (tests run as root in CI); the old-file part then needs a non-root run.
  const bool root = ::geteuid() == 0;
  std::filesystem::path target_dir = dir / "locked";
  if (root) {
    target_dir = "/proc";
  } else {
    std::filesystem::create_directories(target_dir);
    std::filesystem::copy_file(dir / "out.h5", target_dir / "out.h5");
    ::chmod(target_dir.c_str(), 0555);
  }
  const std::string old_bytes = ReadWholeFile(target_dir / "out.h5");
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"summary", "one.toml", "-o", (target_dir / "out.h5").string()},
           {"correct", SamplePath("block2-A-1"), "-o", (target_dir / "out.csv").string()},
           {"simulate", "--b1", "0.05", "--b2", "0.04", "--h", "0.2", "--density", "2692", "--alpha", "0.1", "-o",
            (target_dir / "out.json").string()},
           {"plot", "summary", "one.toml", "-o", (target_dir / "out.png").string()}}) {
    const CommandResult r = RunRockfit(args, dir.path());
    EXPECT_EQ(r.exit_code, kExitCannotWrite) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find(target_dir.string()), std::string::npos) << "names the place: " << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  }
  if (root) {
    GTEST_SKIP() << "running as root, which may write into a read-only directory: checked the clear error in /proc; "
                    "the old-file part needs a non-root run";
  }
  EXPECT_EQ(ReadWholeFile(target_dir / "out.h5"), old_bytes);
  EXPECT_EQ(Listing(target_dir), std::vector<std::string>{"out.h5"});
  ::chmod(target_dir.c_str(), 0755);
}

}  // namespace
}  // namespace rockfit::testing
