// Resource limits: a very long recording and a manifest of 10⁴ trials are read by the real `rockfit` binary
// within a stated memory bound, and a fragility study's threads share its record (peak resident set of the child,
// from wait4). Time is reported, not asserted (speed is measured with Google Benchmark). The CI sizes are 10⁶ rows (10⁵ under the sanitizers);
// ROCKFIT_LARGE_RECORDING_ROWS=10000000 is the documented manual check of the README's "Reliability" section.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "imu_test_files.hpp"
#include "process_control.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

// What reading an x-IMU inertial file may cost per row: the file text (~75 bytes a row), the lexer's cell
// spans (10 cells of 16 bytes) and the recording (time, ω, specific force: 56 bytes), with room to spare.
constexpr double kMaxBytesPerRow = 600.0;
// The program, its libraries and a small recording.
constexpr double kBaseResidentBytes = 150e6;

struct ChildUsage {
  int exit_code = -1;
  double wall_s = 0.0;
  double peak_resident_bytes = 0.0;
  std::string out;
};

ChildUsage RunMeasured(const std::vector<std::string>& args, const std::filesystem::path& dir) {
  const std::string out_path = (dir / "stdout.txt").string();
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string binary = RockfitBinary().string();
    std::vector<std::string> copy = args;
    std::vector<char*> argv{const_cast<char*>(binary.c_str())};
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (!std::freopen(out_path.c_str(), "w", stdout) || !std::freopen("/dev/null", "w", stderr)) ::_exit(126);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  ChildUsage u;
  u.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  u.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  u.peak_resident_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;  // ru_maxrss is in KiB on Linux
  u.out = ReadWholeFile(out_path);
  return u;
}

long LargeRecordingRows() {
  if (const char* text = std::getenv("ROCKFIT_LARGE_RECORDING_ROWS")) return std::strtol(text, nullptr, 10);
  return kOptimisedBuild ? 1000000 : 100000;
}

TEST(ResourceLimits, LongXimuRecordingIsReadWithinTheStatedMemory) {
  const long rows = LargeRecordingRows();
  const ScratchDir dir("large_recording");
  {
    // A slow sway about y, printed as the GUI prints it; written in blocks so that the test itself stays small.
    std::ofstream out(dir / "LoggedData_CalInertialAndMag.csv", std::ios::binary);
    out << kGuiInertialHeader << "\n";
    std::string block;
    for (long k = 0; k < rows; ++k) {
      const double gy = 20.0 * std::sin(static_cast<double>(k) * 0.01);
      block += fmt::format("{},0.0625,{:.7g},-0.0625,0.01,0.02,0.98,0.1,0.2,0.3\n", 2 * k, gy);
      if (block.size() > (1u << 20)) {
        out << block;
        block.clear();
      }
    }
    out << block;
  }
  const double file_bytes = static_cast<double>(std::filesystem::file_size(dir / "LoggedData_CalInertialAndMag.csv"));
  const ChildUsage u = RunMeasured({"inspect", (dir / "LoggedData").string(), "--rate", "256", "--json"}, dir.path());
  ASSERT_EQ(u.exit_code, 0) << u.out;
  EXPECT_EQ(nlohmann::json::parse(u.out)["samples"].get<long>(), rows);
  const double bound = kBaseResidentBytes + kMaxBytesPerRow * static_cast<double>(rows);
  if (!kAddressSanitizedBuild) {
    EXPECT_LT(u.peak_resident_bytes, bound);  // build_type.hpp: not under ASan
  }
  std::printf("inspect of %ld rows (%.0f MB): %.2f s, peak resident %.0f MB (bound %.0f MB)\n", rows, file_bytes / 1e6,
              u.wall_s, u.peak_resident_bytes / 1e6, bound / 1e6);
}

TEST(ResourceLimits, ManifestOfTenThousandTrialsIsSummarisedWithinTheStatedMemory) {
  constexpr int kTrials = 10000;
  const ScratchDir dir("large_manifest");
  std::string text = "[[blocks]]\nid = \"b\"\nb1 = 0.05\nb2 = 0.035\nh = 0.2\ndensity = 2692\n";
  // Every trial names a missing recording: summary reports each as a load error, so the run measures the
  // manifest, the table and the HDF5 store of 10⁴ rows, not 10⁴ recordings.
  for (int k = 0; k < kTrials; ++k) {
    text += fmt::format("\n[[trials]]\nid = \"t{:05d}\"\nblock = \"b\"\nposition = \"{}\"\nfiles = \"missing/t{}\"\n",
                        k, k % 2 ? "A" : "B", k);
  }
  dir.Write("big.toml", text);
  const ChildUsage u =
      RunMeasured({"summary", (dir / "big.toml").string(), "-o", (dir / "big.h5").string(), "--json"}, dir.path());
  ASSERT_TRUE(u.exit_code == 0 || u.exit_code == 2) << u.out;
  const nlohmann::json j = nlohmann::json::parse(u.out);
  EXPECT_EQ(j["trials"].size(), static_cast<std::size_t>(kTrials));
  EXPECT_TRUE(std::filesystem::exists(dir / "big.h5"));
  constexpr double kBound = 400e6;  // 10⁴ rows of a few hundred bytes each, the TOML tree and the HDF5 library
  if (!kAddressSanitizedBuild) {
    EXPECT_LT(u.peak_resident_bytes, kBound);  // build_type.hpp: not under ASan
  }
  std::printf("summary of %d trials (manifest %.1f MB): exit %d, %.2f s, peak resident %.0f MB\n", kTrials,
              static_cast<double>(text.size()) / 1e6, u.exit_code, u.wall_s, u.peak_resident_bytes / 1e6);
}

TEST(ResourceLimits, FragilityThreadsShareTheRecordInsteadOfEachHoldingACopy) {
  // One generated record of 2·10⁶ samples (48 MB as the study holds it); a block at rest under 0.05 and 0.1 g, so
  // that the runs are short and their responses (at 1 Hz) small: what more threads could add is record copies.
  constexpr double kRecordBytes = 2e6 * 24.0;
  const ScratchDir dir("fragility_threads");
  const auto run = [&dir](const std::string& threads) {
    const std::string output = (dir / ("f" + threads + ".h5")).string();
    return RunMeasured({"fragility", "--b1", "0.05", "--b2", "0.05", "--h", "0.2", "--density", "2692",
                        "--synthetic-records", "1", "--synthetic-duration", "10000", "--rate", "1", "--tail", "0",
                        "--pga", "0.05,0.1", "--samples", "4", "-j", threads, "-o", output, "--json"},
                       dir.path());
  };
  const ChildUsage one = run("1");
  const ChildUsage four = run("4");
  ASSERT_EQ(one.exit_code, 0) << one.out;
  ASSERT_EQ(four.exit_code, 0) << four.out;
  if (!kAddressSanitizedBuild) {
    EXPECT_LT(four.peak_resident_bytes - one.peak_resident_bytes, 0.25 * kRecordBytes);  // build_type.hpp
  }
  std::printf("fragility on a 2e6-sample record: peak resident %.0f MB on 1 thread, %.0f MB on 4\n",
              one.peak_resident_bytes / 1e6, four.peak_resident_bytes / 1e6);
}

}  // namespace
}  // namespace rockfit::testing
