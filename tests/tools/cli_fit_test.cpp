// CLI tests of `rockfit fit`, `rockfit batch` and `rockfit plot fit|parameters` on synthetic x-IMU recordings
// (written with the measurement model of `rockfit synth`), run through the real binary.
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "python_h5py.hpp"
#include "rockfit/io/synth_recording.hpp"

namespace rockfit::testing {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kBlock = {"--b1", "0.05", "--b2", "0.04", "--h", "0.2", "--density", "2692"};

std::vector<std::string> With(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// In the Debug sanitizer build whole fits are too slow for a test (build_type.hpp): there the commands run
// with the local stage only and a small budget, and only what does not depend on the fit's quality is checked.
std::vector<std::string> Budget() {
  if (kOptimisedBuild) return {};
  return {"--no-global", "--method", "nelder-mead", "--max-evaluations", "40"};
}

bool HaveGnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

class CliFit : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("rockfit_cli_fit_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "raw");
    const core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);
    const double truths[4][5] = {{0.19, 0.9, -1.8, 0.7, 1.0}, {0.2, 1.2, 2.0, 0.5, 1.0},
                                 {0.18, 0.8, -1.2, 0.9, 1.0}, {0.2, 0.5, 0.0, 0.7, 2.45}};  // the last: no impact
    for (int i = 0; i < 4; ++i) {
      core::ModelParameters p;
      p.alpha_rad = truths[i][0];
      p.lambda = truths[i][1];
      p.lambda_lat = truths[i][2];
      p.lambda_lon = truths[i][3];
      io::SynthRecordingOptions o;
      o.t0_s = truths[i][4];
      o.duration_s = 2.5;
      o.measurement.seed = static_cast<std::uint64_t>(60 + i);
      o.measurement.gyro_bias_dps = Eigen::Vector3d(0.3, -0.2, 0.1);
      o.files.rotation_matrix_file = false;
      io::WriteSynthRecording((dir_ / "raw" / ("T" + std::to_string(i + 1))).string(), block, p, o,
                              io::Synthesize(block, p, o));
    }
    std::ofstream manifest(dir_ / "manifest.toml");
    manifest << "[[blocks]]\nid = \"B4\"\nb1 = 0.05\nb2 = 0.04\nh = 0.2\ndensity = 2692\n";
    const char* positions[] = {"A", "A", "B", "B"};
    for (int i = 1; i <= 3; ++i) {
      manifest << "\n[[trials]]\nid = \"T" << i << "\"\nblock = \"B4\"\nposition = \"" << positions[i - 1]
               << "\"\nfiles = \"raw/T" << i << "\"\n";
    }
    manifest << "\n[[trials]]\nid = \"missing\"\nblock = \"B4\"\nposition = \"B\"\nfiles = \"raw/none\"\n";
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string Raw(int i) { return (dir_ / "raw" / ("T" + std::to_string(i))).string(); }
  static fs::path dir_;
};
fs::path CliFit::dir_;

TEST_F(CliFit, FitPrintsTheDocumentedJsonAndFindsTheParameters) {
  const CommandResult r = RunRockfit(With(With({"fit", Raw(1), "--json"}, kBlock), Budget()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["trial"], "T1");
  for (const char* key : {"parameters", "epsilon", "epsilon_initial", "t_end", "simulations", "wall_s", "termination",
                          "warnings"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  for (const char* name : {"t0", "alpha", "lambda", "lambda_lat", "lambda_lon", "tau_edge"}) {
    for (const char* key : {"value", "lower", "upper", "fixed", "std_error"}) {
      EXPECT_TRUE(j["parameters"][name].contains(key)) << name << "." << key;
    }
  }
  EXPECT_TRUE(j["parameters"]["tau_edge"]["fixed"].get<bool>());
  EXPECT_TRUE(j["parameters"]["tau_edge"]["std_error"].is_null());
  if (!kOptimisedBuild) return;
  // The system tests hold the strict tolerances; here: the right basin.
  EXPECT_NEAR(j["parameters"]["t0"]["value"].get<double>(), 1.0, 0.005);
  EXPECT_NEAR(j["parameters"]["alpha"]["value"].get<double>(), 0.19, 0.005);
  EXPECT_NEAR(j["parameters"]["lambda_lat"]["value"].get<double>(), -1.8, 0.2);
  EXPECT_LT(j["epsilon"].get<double>(), j["epsilon_initial"].get<double>());
}

TEST_F(CliFit, FitStoresTheFitInHdf5ForH5pyAndDrawsIt) {
  const fs::path out = dir_ / "one.h5";
  const fs::path png = dir_ / "one.png";
  std::vector<std::string> args = With({"fit", "manifest.toml", "--trial", "T2", "-o", out.string()}, Budget());
  if (HaveGnuplot()) args = With(args, {"--plot", png.string()});
  const CommandResult r = RunRockfit(args, dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("lambda_lat"), std::string::npos);
  if (HaveGnuplot()) {
    EXPECT_GT(fs::file_size(png), 1000u);
  }
  if (!HaveH5py()) GTEST_SKIP() << "h5py not available";
  const CommandResult check = RunH5pyScript(
      "import h5py, sys\n"
      "f = h5py.File(sys.argv[1], 'r')\n"
      "g = f['fits/T2']\n"
      "assert g.attrs['status'] == 'ok'\n"
      "n = g['time_s'].shape[0]\n"
      "assert g['w_measured_B_rad_s'].shape == (n, 3) and g['w_simulated_B_rad_s'].shape == (n, 3)\n"
      "assert g['w_simulated_B_rad_s'].attrs['units'] == 'rad/s'\n"
      "names = [x.decode() if isinstance(x, bytes) else x for x in g['parameters/name'][:]]\n"
      "assert names == ['t0', 'alpha', 'lambda', 'lambda_lat', 'lambda_lon', 'tau_edge'], names\n"
      "assert abs(g['parameters/value'][1] - 0.2) < 0.01\n"
      "assert f['fit_summary/trials/lambda_lat'].shape == (1,)\n"
      "assert 'rockfit_schema_version' in f.attrs\n",
      out);
  EXPECT_EQ(check.exit_code, 0) << check.out;
}

TEST_F(CliFit, EvaluatePrintsTheErrorOfGivenParameters) {
  const CommandResult r = RunRockfit(With({"fit", Raw(1), "--json", "--evaluate",
                                           "t0=1.0,alpha=0.19,lambda=0.9,lambda_lat=-1.8,lambda_lon=0.7"},
                                          kBlock));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["feasible"].get<bool>());
  EXPECT_GT(j["epsilon"].get<double>(), 0.0);
  EXPECT_LT(j["epsilon"].get<double>(), 0.02);  // the truth: only measurement errors remain
  EXPECT_TRUE(j["parameters"]["alpha"]["given"].get<bool>());
  // A worse guess has a larger error.
  const CommandResult worse = RunRockfit(With({"fit", Raw(1), "--json", "--evaluate", "lambda_lat=1.8"}, kBlock));
  ASSERT_EQ(worse.exit_code, 0) << worse.err;
  EXPECT_GT(nlohmann::json::parse(worse.out)["epsilon"].get<double>(), j["epsilon"].get<double>());
}

TEST_F(CliFit, UsageErrorsNameTheOptionAndExitWithOne) {
  const CommandResult fix = RunRockfit(With({"fit", Raw(1), "--fix", "lambda_x=0"}, kBlock));
  EXPECT_EQ(fix.exit_code, 1);
  EXPECT_NE(fix.err.find("lambda_lat"), std::string::npos) << fix.err;  // lists the valid names
  const CommandResult bound = RunRockfit(With({"fit", Raw(1), "--bound", "alpha=0.3:0.1"}, kBlock));
  EXPECT_EQ(bound.exit_code, 1);
  EXPECT_NE(bound.err.find("--bound"), std::string::npos) << bound.err;
  const CommandResult method = RunRockfit(With({"fit", Raw(1), "--method", "simplex"}, kBlock));
  EXPECT_EQ(method.exit_code, 1);
  const CommandResult block = RunRockfit({"fit", Raw(1)});
  EXPECT_EQ(block.exit_code, 1);
  EXPECT_NE(block.err.find("--b1"), std::string::npos) << block.err;
}

TEST_F(CliFit, ARecordingWithoutImpactIsBadInputWithExitTwo) {
  const CommandResult r = RunRockfit(With({"fit", Raw(4)}, kBlock));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("impact"), std::string::npos) << r.err;
}

TEST_F(CliFit, BatchFitsAllTrialsListsTheFailureAndResumes) {
  const fs::path out = dir_ / "batch.h5";
  const CommandResult r = RunRockfit(With({"batch", "manifest.toml", "-o", out.string(), "-j", "2", "--json"}, Budget()), dir_);
  EXPECT_EQ(r.exit_code, 3) << r.err;  // one trial failed
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], 3);
  EXPECT_EQ(j["failed"], 1);
  EXPECT_EQ(j["trials"][3]["trial"], "missing");
  EXPECT_EQ(j["trials"][3]["status"], "failed");
  EXPECT_NE(r.err.find("missing"), std::string::npos);  // listed for people too
  EXPECT_FALSE(fs::exists(out.string() + ".parts"));

  const CommandResult again =
      RunRockfit(With({"batch", "manifest.toml", "-o", out.string(), "--resume", "--json"}, Budget()), dir_);
  const auto k = nlohmann::json::parse(again.out);
  EXPECT_EQ(k["skipped"], 3);
  EXPECT_EQ(k["failed"], 1);

  if (HaveGnuplot()) {
    const CommandResult fit_png = RunRockfit({"plot", "fit", out.string(), "--trial", "T1", "-o", (dir_ / "t1.png").string()});
    EXPECT_EQ(fit_png.exit_code, 0) << fit_png.err;
    const CommandResult params = RunRockfit({"plot", "parameters", out.string(), "-o", (dir_ / "p.svg").string(), "--json"});
    ASSERT_EQ(params.exit_code, 0) << params.err;
    EXPECT_EQ(nlohmann::json::parse(params.out)["trials"], 3);
  }
}

TEST_F(CliFit, ABatchKilledAtAnyMomentLosesNothingOnResume) {
  const fs::path reference = dir_ / "reference.h5";
  const fs::path killed = dir_ / "killed.h5";
  RunRockfit(With({"batch", "manifest.toml", "-o", reference.string(), "-j", "1", "--no-progress"}, Budget()), dir_);
  std::string budget;
  for (const std::string& a : Budget()) budget += " " + a;
  // Start the same batch, kill it hard as soon as the first trial is stored.
  const fs::path pid_file = dir_ / "batch.pid";
  const std::string start = "cd " + ShellQuote(dir_.string()) + " && (" + ShellQuote(RockfitBinary().string()) +
                            " batch manifest.toml -o " + ShellQuote(killed.string()) +
                            " -j 1 --no-progress" + budget + " >/dev/null 2>&1 & echo $! > " +
                            ShellQuote(pid_file.string()) + ")";
  ASSERT_EQ(std::system(start.c_str()), 0);
  pid_t pid = 0;
  for (int i = 0; i < 200 && pid == 0; ++i) {
    std::ifstream(pid_file) >> pid;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_GT(pid, 0);
  const fs::path parts = killed.string() + ".parts";
  // A committed part is named <trial>.h5 (temporary files being written carry another name).
  auto committed_parts = [&] {
    int n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(parts, ec)) n += e.path().extension() == ".h5" ? 1 : 0;
    return n;
  };
  for (int i = 0; i < 2000 && committed_parts() == 0; ++i) {  // up to 20 s (sanitizer builds are slow)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  while (::kill(pid, 0) == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const CommandResult resumed =
      RunRockfit(With({"batch", "manifest.toml", "-o", killed.string(), "--resume", "--json"}, Budget()), dir_);
  const auto j = nlohmann::json::parse(resumed.out);
  EXPECT_EQ(j["ok"].get<int>() + j["skipped"].get<int>(), 3);
  EXPECT_GE(j["skipped"].get<int>(), 1) << "the trial stored before the kill is not fitted again";
  if (!HaveH5py()) GTEST_SKIP() << "h5py not available";
  // Every trial ends with the same result as in the uninterrupted run (the fits are deterministic).
  const CommandResult compare = RunH5pyScript(
      "import h5py, sys\n"
      "a = h5py.File(sys.argv[1], 'r')\n"
      "b = h5py.File(" + std::string("'") + killed.string() + "', 'r')\n"
      "for t in ['T1', 'T2', 'T3']:\n"
      "    assert a['fits/' + t].attrs['epsilon_rad_s'] == b['fits/' + t].attrs['epsilon_rad_s'], t\n",
      reference);
  EXPECT_EQ(compare.exit_code, 0) << compare.out;
}

}  // namespace
}  // namespace rockfit::testing
