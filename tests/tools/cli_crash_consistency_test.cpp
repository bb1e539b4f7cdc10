// Crash consistency of every command that writes a file: the real `rockfit` binary is killed with SIGKILL at
// random instants (fixed seed) while it writes over an existing output — 100 kills over summary -o, fit -o,
// batch, correct -o (HDF5 and CSV), synth, simulate -o (JSON and HDF5) and the two plots. After each kill every
// output is byte for byte the old file or a complete new one that opens, and `batch --resume` loses no trial.
// The next successful run removes the temporaries the killed process left (atomic_file.hpp).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "png_header.hpp"
#include "process_control.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

const std::vector<std::string> kQuickFit = {"--method", "nelder-mead", "--max-evaluations", "12", "--no-global"};

std::string SamplePath(const std::string& trial) {
  return (SourceDir() / "data-samples" / "recordings" / trial).string();
}

// A manifest of sample trials of block2 (absolute file paths).
void WriteManifest(const ScratchDir& dir, const std::string& name, const std::vector<std::string>& trials) {
  std::string text = "[[blocks]]\nid = \"block2\"\nb1 = 0.05000453\nb2 = 0.035\nh = 0.2\ndensity = 2692\n";
  for (const std::string& id : trials) {
    text += fmt::format(
        "\n[[trials]]\nid = \"{}\"\nblock = \"block2\"\nposition = \"{}\"\nfiles = \"{}\"\n"
        "format = \"ximu-gui\"\n",
        id, id.substr(7, 1), SamplePath(id));
  }
  dir.Write(name, text);
}

bool Hdf5HasAll(const std::filesystem::path& path, const std::vector<std::string>& objects) {
  try {
    const io::hdf5::File file = io::hdf5::File::Open(path);
    for (const auto& o : objects)
      if (!file.Root().Exists(o)) return false;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

bool IsCompletePng(const std::filesystem::path& path) {
  const std::string bytes = ReadWholeFile(path);
  const std::string end("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  return ReadPngHeader(path).valid && bytes.size() > end.size() &&
         bytes.compare(bytes.size() - end.size(), end.size(), end) == 0;
}

// One output of a writer: how to tell a complete new file when the bytes may differ from run to run (HDF5
// object times, wall times in JSON). Without `complete`, only the bytes of the reference run count as new.
struct Output {
  std::string name;
  std::function<bool(const std::filesystem::path&)> complete;
};

struct WriterCase {
  std::string name;
  std::vector<std::string> old_args;  // writes the old outputs
  std::vector<std::string> new_args;  // overwrites them; killed at random instants
  std::vector<Output> outputs;
  int kills = 0;
  bool needs_optimised_build = false;  // whole fits
};

// Test names and messages show the case's name rather than its bytes.
void PrintTo(const WriterCase& c, std::ostream* os) { *os << c.name; }

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<WriterCase> WriterCases() {
  const auto json_with_end_reason = [](const std::filesystem::path& p) {
    try {
      return nlohmann::json::parse(ReadWholeFile(p)).contains("end_reason");
    } catch (const std::exception&) {
      return false;
    }
  };
  std::vector<WriterCase> cases;
  cases.push_back({"summary",
                   {"summary", "one.toml", "-o", "campaign.h5"},
                   {"summary", "two.toml", "-o", "campaign.h5"},
                   {{"campaign.h5",
                     [](const std::filesystem::path& p) {
                       try {
                         return io::ReadSummaryHdf5(p).trials.size() == 2;
                       } catch (const std::exception&) {
                         return false;
                       }
                     }}},
                   12});
  cases.push_back({"fit",
                   Concat({"fit", "two.toml", "--trial", "block2-A-1", "-o", "fits.h5"}, kQuickFit),
                   Concat({"fit", "two.toml", "--trial", "block2-B-1", "-o", "fits.h5"}, kQuickFit),
                   {{"fits.h5",
                     [](const auto& p) {
                       return Hdf5HasAll(p, {"fits/block2-A-1", "fits/block2-B-1"});
                     }}},
                   12,
                   true});
  cases.push_back({"correct_hdf5",
                   {"correct", SamplePath("block2-A-1"), "--name", "first", "-o", "corrected.h5"},
                   {"correct", SamplePath("block2-A-2"), "--name", "second", "-o", "corrected.h5"},
                   {{"corrected.h5",
                     [](const auto& p) {
                       return Hdf5HasAll(p, {"trials/first", "trials/second"});
                     }}},
                   10});
  cases.push_back({"correct_csv",
                   {"correct", SamplePath("block2-A-1"), "-o", "corrected.csv"},
                   {"correct", SamplePath("block2-A-2"), "-o", "corrected.csv"},
                   {{"corrected.csv", nullptr}, {"corrected_impacts.csv", nullptr}},
                   9});
  const std::vector<std::string> synth = {"synth",     "--b1",       "0.05",    "--b2", "0.035",    "--h", "0.2",
                                          "--density", "2692",       "--alpha", "0.18", "--lambda", "0.9", "--t0",
                                          "0.5",       "--duration", "3",       "-o",   "trial"};
  std::vector<Output> synth_outputs;
  for (const char* type : {"CalInertialAndMag", "DateTime", "EulerAngles", "Quaternion", "RotationMatrix", "Registers",
                           "CalBattAndTherm"}) {
    synth_outputs.push_back({fmt::format("trial_{}.csv", type), nullptr});
  }
  synth_outputs.push_back({"trial_truth.json", nullptr});
  cases.push_back({"synth", Concat(synth, {"--seed", "1"}), Concat(synth, {"--seed", "2"}), synth_outputs, 12});
  const std::vector<std::string> simulate = {"simulate",  "--b1", "0.05",     "--b2", "0.04",   "--h", "0.2",
                                             "--density", "2692", "--lambda", "0.9",  "--stop", "rest"};
  cases.push_back({"simulate_json",
                   Concat(simulate, {"--alpha", "0.1", "-o", "sim.json"}),
                   Concat(simulate, {"--alpha", "0.2", "-o", "sim.json"}),
                   {{"sim.json", json_with_end_reason}},
                   9});
  cases.push_back({"simulate_hdf5",
                   Concat(simulate, {"--alpha", "0.1", "--format", "hdf5", "-o", "sim.h5"}),
                   Concat(simulate, {"--alpha", "0.2", "--format", "hdf5", "-o", "sim.h5"}),
                   {{"sim.h5", [](const auto& p) { return Hdf5HasAll(p, {}); }}},
                   8});
  cases.push_back({"plot_euler",
                   {"plot", "euler", "source.h5", "--trial", "block2-A-1", "-o", "euler.png"},
                   {"plot", "euler", "source.h5", "--trial", "block2-B-1", "-o", "euler.png"},
                   {{"euler.png", IsCompletePng}},
                   8});
  cases.push_back({"plot_summary",
                   {"plot", "summary", "one.toml", "-o", "summary.png"},
                   {"plot", "summary", "two.toml", "-o", "summary.png"},
                   {{"summary.png", IsCompletePng}},
                   8});
  return cases;
}

// Kills in all: the writer cases above plus the batch test below.
constexpr int kBatchKills = 12;

bool HasTemporaries(const std::filesystem::path& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().find(".rockfit-tmp-") != std::string::npos) return true;
  return false;
}

class CrashConsistency : public ::testing::TestWithParam<WriterCase> {};

TEST_P(CrashConsistency, KilledAtRandomInstantsLeavesTheOldFileOrTheCompleteNewOne) {
  const WriterCase& c = GetParam();
  if (c.needs_optimised_build) ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("crash_" + c.name);
  WriteManifest(dir, "one.toml", {"block2-A-1"});
  WriteManifest(dir, "two.toml", {"block2-A-1", "block2-B-1"});
  if (c.name == "plot_euler") {
    ASSERT_EQ(RunRockfitTimed({"summary", "two.toml", "-o", "source.h5"}, dir.path().string()).first, 0);
  }
  // The old outputs, and the new ones with the time a whole run takes.
  ASSERT_EQ(RunRockfitTimed(c.old_args, dir.path().string()).first, 0) << c.name;
  std::vector<std::string> old_bytes, new_bytes;
  for (const auto& o : c.outputs) old_bytes.push_back(ReadWholeFile(dir / o.name));
  const auto [code, run_s] = RunRockfitTimed(c.new_args, dir.path().string());
  ASSERT_EQ(code, 0) << c.name;
  std::size_t changed = 0;
  for (std::size_t k = 0; k < c.outputs.size(); ++k) {
    new_bytes.push_back(ReadWholeFile(dir / c.outputs[k].name));
    ASSERT_FALSE(old_bytes[k].empty()) << c.outputs[k].name;
    changed += old_bytes[k] != new_bytes[k];  // synth's registers and clock files do not depend on the seed
  }
  ASSERT_GT(changed, 0u) << c.name << ": the new run must change the output";
  const int kills = kOptimisedBuild ? c.kills : 2;  // the sanitizer build runs every case, twice
  std::mt19937_64 rng(std::hash<std::string>{}(c.name) ^ 20261125);
  int killed = 0, kept_old = 0, got_new = 0, attempts = 0;
  // Instants at which the run had already ended do not count: draw again until `kills` processes died by SIGKILL.
  // Up to ten draws a kill: the run timed above may be slower than the killed ones on a loaded machine (a 0.044 s
  // run once saw only 9 of 40 instants fall inside it).
  for (int k = 0; killed < kills && attempts < 10 * kills; ++k, ++attempts) {
    for (std::size_t i = 0; i < c.outputs.size(); ++i) dir.Write(c.outputs[i].name, old_bytes[i]);  // restore
    // Half the kills anywhere in the run, half in its last fifth, where the files are written.
    const double instant_s = std::uniform_real_distribution<double>(k % 2 ? 0.8 * run_s : 0.0, run_s)(rng);
    const pid_t pid = StartRockfit(c.new_args, dir.path().string());
    std::this_thread::sleep_for(std::chrono::duration<double>(instant_s));
    ::kill(pid, SIGKILL);
    if (WaitForExit(pid) == -SIGKILL) ++killed;
    for (std::size_t i = 0; i < c.outputs.size(); ++i) {
      const std::filesystem::path path = dir / c.outputs[i].name;
      const std::string bytes = ReadWholeFile(path);
      const bool is_old = bytes == old_bytes[i];
      const bool is_new = bytes == new_bytes[i] || (c.outputs[i].complete && c.outputs[i].complete(path));
      EXPECT_TRUE(is_old || is_new) << c.name << ": " << c.outputs[i].name << " is neither the old file nor a complete "
                                    << "new one after a kill at " << instant_s << " s (" << bytes.size() << " bytes)";
      kept_old += is_old;
      got_new += is_new && !is_old;
    }
  }
  // A last, whole run removes what the killed processes left behind.
  ASSERT_EQ(RunRockfitTimed(c.new_args, dir.path().string()).first, 0) << c.name;
  EXPECT_FALSE(HasTemporaries(dir.path())) << c.name << ": temporaries of killed processes left behind";
  EXPECT_EQ(killed, kills) << c.name << ": too few instants fell inside the run";
  std::printf("%-14s run %.3f s, %d SIGKILLs in %d attempts: %d outputs old, %d new\n", c.name.c_str(), run_s, killed,
              attempts, kept_old, got_new);
}

INSTANTIATE_TEST_SUITE_P(EveryWriter, CrashConsistency, ::testing::ValuesIn(WriterCases()),
                         [](const ::testing::TestParamInfo<WriterCase>& info) { return info.param.name; });

TEST(CrashConsistencyTotal, HundredKillsOverAllWriters) {
  int total = kBatchKills;
  for (const auto& c : WriterCases()) total += c.kills;
  EXPECT_EQ(total, 100);
}

TEST(CrashConsistencyBatch, KilledAtRandomInstantsAndResumedLosesNoFittedTrial) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const ScratchDir dir("crash_batch");
  WriteManifest(dir, "three.toml", {"block2-A-1", "block2-A-2", "block2-B-1"});
  const std::vector<std::string> batch =
      Concat({"batch", "three.toml", "-o", "fits.h5", "--resume", "-j", "1"}, kQuickFit);
  // The time of a whole batch, in a directory of its own.
  const ScratchDir reference("crash_batch_reference");
  WriteManifest(reference, "three.toml", {"block2-A-1", "block2-A-2", "block2-B-1"});
  const auto [code, run_s] = RunRockfitTimed(batch, reference.path().string());
  ASSERT_EQ(code, 0);
  std::mt19937_64 rng(20261125);
  std::size_t fitted_before = 0;
  const auto fitted = [&]() -> std::size_t {
    if (!std::filesystem::exists(dir / "fits.h5")) return 0;
    const io::hdf5::File file = io::hdf5::File::Open(dir / "fits.h5");  // throws if the file does not open
    return file.Root().Exists("fits") ? file.Root().OpenGroup("fits").Children().size() : 0;
  };
  for (int k = 0; k < kBatchKills; ++k) {
    const double instant_s = std::uniform_real_distribution<double>(0.0, run_s / 2)(rng);
    const pid_t pid = StartRockfit(batch, dir.path().string());
    std::this_thread::sleep_for(std::chrono::duration<double>(instant_s));
    ::kill(pid, SIGKILL);
    WaitForExit(pid);
    std::size_t now = 0;
    ASSERT_NO_THROW(now = fitted()) << "fits.h5 does not open after a kill at " << instant_s << " s";
    EXPECT_GE(now, fitted_before) << "a kill lost a fitted trial";
    fitted_before = now;
  }
  const CommandResult r = RunRockfit(Concat(batch, {"--json"}), dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["skipped"].get<std::size_t>(), fitted_before) << "every trial fitted before the kills is kept";
  EXPECT_EQ(j["skipped"].get<std::size_t>() + j["fitted"].get<std::size_t>(), 3u);
  EXPECT_EQ(fitted(), 3u);
  EXPECT_FALSE(HasTemporaries(dir.path()));
  std::printf("batch: %d kills, %zu of 3 trials fitted before the last resume\n", kBatchKills, fitted_before);
}

}  // namespace
}  // namespace rockfit::testing
