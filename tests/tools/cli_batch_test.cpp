// `rockfit batch` (tools/src/cmd_batch.cpp): a small campaign pointing at the bundled sample recordings, the HDF5
// layout seen by h5py, failures isolated, and kill -9 followed by --resume losing nothing.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "python_h5py.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

// Linearised intervals: the profiles of the default (`thorough`) cost thousands of simulations, too slow for the
// sanitizer build; tests/tools/cli_fit_intervals_test.cpp covers them in optimised builds.
const std::vector<std::string> kQuick = {"--method", "nelder-mead", "--max-evaluations", "15", "--no-global",
                                         "--intervals", "fast"};

// A manifest of the given sample trials (block2) in `dir`, the files given as absolute paths.
std::string WriteManifest(const ScratchDir& dir, const std::vector<std::string>& trials, bool add_missing = false) {
  std::string text = "[[blocks]]\nid = \"block2\"\nb1 = 0.05000453\nb2 = 0.035\nh = 0.2\ndensity = 2692\n";
  for (const std::string& id : trials) {
    text += fmt::format("\n[[trials]]\nid = \"{}\"\nblock = \"block2\"\nposition = \"{}\"\nfiles = \"{}\"\n"
                        "format = \"ximu-gui\"\nrate = 256\nmounting = \"x,y,z\"\n",
                        id, id.substr(7, 1), (SourceDir() / "data-samples" / "recordings" / id).string());
  }
  if (add_missing) {
    text += "\n[[trials]]\nid = \"missing\"\nblock = \"block2\"\nposition = \"A\"\nfiles = \"nowhere/missing\"\n"
            "format = \"ximu-gui\"\nrate = 256\n";
  }
  return dir.Write("manifest.toml", text).string();
}

std::vector<std::string> Batch(const std::string& manifest, const std::string& out, std::vector<std::string> extra) {
  std::vector<std::string> args = {"batch", manifest, "-o", out};
  args.insert(args.end(), kQuick.begin(), kQuick.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

TEST(CliBatch, FitsEveryTrialIntoOneFileWithSummaryTables) {
  if (!HaveH5py()) GTEST_SKIP() << "/usr/bin/python3 with h5py is missing";
  const ScratchDir dir("cli_batch");
  const std::string manifest = WriteManifest(dir, {"block2-A-1", "block2-B-1"});
  const std::string out = (dir / "fits.h5").string();
  const CommandResult r = RunRockfit(Batch(manifest, out, {"-j", "2", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["fitted"], 2);
  EXPECT_EQ(j["failed"], 0);
  EXPECT_NE(r.err.find("[2/2]"), std::string::npos) << "plain progress lines when stderr is not a terminal: " << r.err;
  const CommandResult check = RunH5pyScript(R"(
import sys, h5py
f = h5py.File(sys.argv[1], 'r')
assert sorted(f['fits'].keys()) == ['block2-A-1', 'block2-B-1'], list(f['fits'].keys())
for t in f['fits']:
    assert len(f['fits'][t].attrs['settings_hash']) == 16
t = f['summary/fits/per_trial']
assert len(t['trial']) == 2 and len(t['alpha']) == 2
g = f['summary/fits/per_group']
assert list(g['n'][()]) == [1, 1], list(g['n'][()])
for name in ['alpha_interval_68_lower', 'alpha_interval_95_upper', 'lambda_lat_determined']:
    assert len(t[name]) == 2, name
for name in ['alpha_pooled', 'alpha_pooled_95_lower', 'alpha_pooled_95_upper', 'alpha_n_pooled', 'alpha_chi2_per_dof',
             'alpha_consistency_p']:
    assert len(g[name]) == 2, name
print('ok')
)",
                                            out);
  EXPECT_EQ(check.exit_code, 0) << check.out;
}

TEST(CliBatch, FailedTrialIsListedAndTheOthersAreKept) {
  const ScratchDir dir("cli_batch_fail");
  const std::string manifest = WriteManifest(dir, {"block2-A-1"}, /*add_missing=*/true);
  const std::string out = (dir / "fits.h5").string();
  const CommandResult r = RunRockfit(Batch(manifest, out, {"--json"}));
  EXPECT_NE(r.exit_code, 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["fitted"], 1);
  EXPECT_EQ(j["failed"], 1);
  EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
  // A resume with the same settings skips the fitted trial and fails the missing one again.
  const nlohmann::json again = nlohmann::json::parse(RunRockfit(Batch(manifest, out, {"--json", "--resume"})).out);
  EXPECT_EQ(again["skipped"], 1);
  EXPECT_EQ(again["failed"], 1);
  // Other settings: fitted again.
  const CommandResult other = RunRockfit(
      {"batch", manifest, "-o", out, "--resume", "--json", "--method", "nelder-mead", "--max-evaluations", "16",
       "--no-global", "--intervals", "fast"});
  EXPECT_EQ(nlohmann::json::parse(other.out)["skipped"], 0);
}

TEST(CliBatch, KilledBatchResumesWithoutLosingTrials) {
  const ScratchDir dir("cli_batch_kill");
  const std::string manifest = WriteManifest(dir, {"block2-A-1", "block2-A-2", "block2-B-1"});
  const std::string out = (dir / "fits.h5").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::vector<std::string> args = Batch(manifest, out, {"-j", "1"});
    std::vector<char*> argv;
    const std::string binary = RockfitBinary().string();
    argv.push_back(const_cast<char*>(binary.c_str()));
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    freopen("/dev/null", "w", stderr);
    freopen("/dev/null", "w", stdout);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  // Kill as soon as the first trial is committed (the file appears then), in the middle of the next fit.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!std::filesystem::exists(out) && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  ASSERT_TRUE(std::filesystem::exists(out));

  const CommandResult r = RunRockfit(Batch(manifest, out, {"--resume", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_GE(j["skipped"].get<int>(), 1) << "the trial committed before the kill is kept";
  EXPECT_EQ(j["skipped"].get<int>() + j["fitted"].get<int>(), 3);
  // Nothing half-written is left next to the file.
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "fits.h5" || name == "manifest.toml") << "left over: " << name;
  }
  if (HaveH5py()) {
    const CommandResult check = RunH5pyScript(
        "import sys, h5py\nf = h5py.File(sys.argv[1], 'r')\nassert len(f['fits']) == 3, list(f['fits'])\n"
        "assert len(f['summary/fits/per_trial/trial']) == 3\nprint('ok')\n",
        out);
    EXPECT_EQ(check.exit_code, 0) << check.out;
  }
}

}  // namespace
}  // namespace rockfit::testing
