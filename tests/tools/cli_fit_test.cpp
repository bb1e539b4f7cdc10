// `rockfit fit` (tools/src/cmd_fit.cpp) on a bundled sample trial: the JSON keys, ε from the fit no worse than at
// the start, --evaluate, HDF5 output, and usage errors. Small budgets keep it fast under the sanitizers.
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "png_header.hpp"
#include "python_h5py.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

std::string SampleManifest() { return (SourceDir() / "data-samples" / "manifest.toml").string(); }

// A local search from the data estimate with a small budget: what the test checks does not need a full fit.
std::vector<std::string> QuickFit(std::vector<std::string> extra) {
  std::vector<std::string> args = {"fit",     SampleManifest(), "--trial",           "block2-A-1",
                                   "--method", "nelder-mead",    "--max-evaluations", "40",
                                   "--no-global",    "--intervals", "fast"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

TEST(CliFit, JsonHasTheDocumentedKeysAndEpsilonNotAboveTheStart) {
  const CommandResult r = RunRockfit(QuickFit({"--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"trial", "parameters", "correlation", "uncertainty_method", "uncertainty", "epsilon",
                          "epsilon_initial", "t_end", "window", "simulations", "wall_s", "termination", "warnings",
                          "mounting", "lateral_motion", "model_error", "motion_before_release", "release_roll_choice",
                          "release_tilt"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j.size(), 19u) << "only the documented keys";
  // Released from rest: the recording is still before the fitted t0, and nothing is said about it.
  EXPECT_TRUE(j["motion_before_release"]["available"].get<bool>());
  EXPECT_FALSE(j["motion_before_release"]["moving"].get<bool>());
  // The sample recording rests before the release and after the rocking: its tilt at rest is compared with the fit's
  // α, and the two agree (it was released from rest at the tilt its model falls from).
  EXPECT_TRUE(j["release_tilt"]["available"].get<bool>());
  EXPECT_TRUE(j["release_tilt"]["consistent"].get<bool>());
  EXPECT_LT(std::abs(j["release_tilt"]["z"].get<double>()), 3.0);
  EXPECT_EQ(j["release_tilt"]["fitted_rad"], j["parameters"]["alpha"]["value"]);
  EXPECT_EQ(j["release_tilt"]["rest_rad"], j["mounting"]["release_tilt_rad"]);
  // The sample trial was released on its edge: the fall shows no roll, and the roll is not fitted.
  EXPECT_EQ(j["release_roll_choice"]["mode"], "auto");
  EXPECT_TRUE(j["release_roll_choice"]["judged"].get<bool>());
  EXPECT_FALSE(j["release_roll_choice"]["fitted"].get<bool>());
  EXPECT_FALSE(j["parameters"].contains("release_roll"));
  // The window's report: the release is on the edge, so λ_lat is determined by the first window.
  EXPECT_EQ(j["window"]["t_end"], j["t_end"]);
  EXPECT_EQ(j["window"]["first_t_end"], j["t_end"]);
  EXPECT_EQ(j["window"]["extensions"], 0);
  // The model-error statement of the sample trial: its rest before the release is 2.3 s long.
  EXPECT_TRUE(j["model_error"]["available"].get<bool>());
  EXPECT_NEAR(j["model_error"]["noise_share"].get<double>() + j["model_error"]["model_error_share"].get<double>(), 1.0,
              1e-12);
  EXPECT_EQ(j["trial"], "block2-A-1");
  for (const char* name : {"t0", "alpha", "lambda", "lambda_lat", "lambda_lon", "tau_edge"}) {
    ASSERT_TRUE(j["parameters"].contains(name)) << name;
    for (const char* field : {"value", "lower", "upper", "fixed", "std_error", "interval_68", "interval_95", "determined"}) {
      EXPECT_TRUE(j["parameters"][name].contains(field)) << name << "." << field;
    }
  }
  const double eps = j["epsilon"].get<double>();
  EXPECT_TRUE(std::isfinite(eps));
  EXPECT_LE(eps, j["epsilon_initial"].get<double>());
  EXPECT_TRUE(j["parameters"]["tau_edge"]["fixed"].get<bool>());
  // The window ends 12 ms (window_end_margin_s) before the impact that ends phase 4; the truth file gives
  // phase4_end_s = 3.378 s, detected to one sample (3.9 ms).
  EXPECT_NEAR(j["t_end"].get<double>(), 3.378 - 0.012, 0.004);
}

TEST(CliFit, AnEstimatedGyroScaleIsReportedWithItsIntervalAndABadModeIsRefused) {
  const CommandResult r = RunRockfit(QuickFit({"--json", "--estimate-gyro-scale", "common"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("gyro_scale"));
  EXPECT_EQ(j["gyro_scale"]["mode"], "common");
  const double s = j["gyro_scale"]["value"][0].get<double>();
  EXPECT_EQ(j["gyro_scale"]["value"][1].get<double>(), s);  // one scale for the three axes
  // The sample trial was made without a scale error: 1 lies in the interval, which holds the estimate.
  const nlohmann::json& i = j["gyro_scale"]["interval_95"][1];
  EXPECT_LE(i[0].get<double>(), s);
  EXPECT_GE(i[1].get<double>(), s);
  EXPECT_LE(i[0].get<double>(), 1.0);
  EXPECT_GE(i[1].get<double>(), 1.0);
  const CommandResult text = RunRockfit(QuickFit({"--estimate-gyro-scale", "per-axis"}));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("gyro scale  per-axis: s_x ="), std::string::npos) << text.out;
  const CommandResult bad = RunRockfit(QuickFit({"--estimate-gyro-scale", "yes"}));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--estimate-gyro-scale"), std::string::npos) << bad.err;
}

TEST(CliFit, TextShowsTheIntervalsAndHowTheyWereMade) {
  const CommandResult r = RunRockfit(QuickFit({}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("68 % interval"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("95 % interval"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("determined"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("intervals    fast: linearised"), std::string::npos) << r.out;
}

TEST(CliFit, EvaluatePrintsEpsilonWithoutFitting) {
  const CommandResult truth = RunRockfit({"fit", SampleManifest(), "--trial", "block2-A-1", "--evaluate", "--json",
                                          "--t0", "2.33", "--alpha", "0.197", "--lambda", "2.185", "--lambda-lat",
                                          "-2.032", "--lambda-lon", "0.197"});
  ASSERT_EQ(truth.exit_code, 0) << truth.err;
  const nlohmann::json t = nlohmann::json::parse(truth.out);
  const CommandResult off = RunRockfit({"fit", SampleManifest(), "--trial", "block2-A-1", "--evaluate", "--json",
                                        "--t0", "2.33", "--alpha", "0.197", "--lambda", "2.185", "--lambda-lat",
                                        "2.032", "--lambda-lon", "0.197"});
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const double eps_truth = t["epsilon"].get<double>();
  // At the true parameters only the measurement errors remain (gyro noise 0.1 °/s, ringing, drift): far below the
  // |ω| of ~1 rad/s; the wrong sign of λ_lat sends the block the other way and must cost more.
  EXPECT_GT(eps_truth, 0.0);
  EXPECT_LT(eps_truth, 0.1);
  EXPECT_GT(nlohmann::json::parse(off.out)["epsilon"].get<double>(), 2.0 * eps_truth);
  const CommandResult text = RunRockfit({"fit", SampleManifest(), "--trial", "block2-A-1", "--evaluate"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("ε (28)"), std::string::npos) << text.out;
}

TEST(CliFit, UnknownParameterNameIsAUsageError) {
  const CommandResult r = RunRockfit(QuickFit({"--fix", "lambda_side"}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("lambda_side"), std::string::npos) << r.err;
  EXPECT_EQ(RunRockfit(QuickFit({"--lower", "alpha"})).exit_code, 1);
  EXPECT_EQ(RunRockfit(QuickFit({"--method", "simplex"})).exit_code, 1);
}

TEST(CliFit, WritesTheFitGroupAndKeepsOthers) {
  if (!HaveH5py()) GTEST_SKIP() << "/usr/bin/python3 with h5py is missing";
  const ScratchDir dir("cli_fit");
  const std::string out = (dir / "fits.h5").string();
  ASSERT_EQ(RunRockfit(QuickFit({"--fix", "t0,alpha", "-o", out})).exit_code, 0);
  const CommandResult r = RunRockfit(
      {"fit", SampleManifest(), "--trial", "block2-B-1", "--method", "nelder-mead", "--max-evaluations", "20",
       "--no-global", "--intervals", "fast", "-o", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CommandResult check = RunH5pyScript(R"(
import sys, h5py
f = h5py.File(sys.argv[1], 'r')
assert sorted(f['fits'].keys()) == ['block2-A-1', 'block2-B-1'], list(f['fits'].keys())
g = f['fits/block2-A-1']
names = [n.decode() if isinstance(n, bytes) else n for n in g['parameters/name'][()]]
assert names == ['t0', 'alpha', 'lambda', 'lambda_lat', 'lambda_lon', 'tau_edge'], names
assert list(g['parameters/fixed'][()]) == [1, 1, 0, 0, 0, 1]
assert g['w_B_simulated'].shape == g['w_B_measured'].shape and g['w_B_measured'].shape[1] == 3
assert g.attrs['epsilon_rad_s'] <= g.attrs['epsilon_initial_rad_s']
assert len(g['impacts/t_s']) > 0
# α held: the tilt at rest is stored, but not compared
assert 0.18 < g.attrs['release_tilt_rest_rad'] < 0.22 and g.attrs['release_tilt_rest_std_error_rad'] > 0
assert g.attrs['release_tilt_consistent'] == -1 and g.attrs['release_tilt_z'] != g.attrs['release_tilt_z']
h = f['fits/block2-B-1']
assert h.attrs['release_tilt_consistent'] in (0, 1) and abs(h.attrs['release_tilt_z']) < 10
assert 'σ apart' in h.attrs['release_tilt_check'], h.attrs['release_tilt_check']
print('ok')
)",
                                            out);
  EXPECT_EQ(check.exit_code, 0) << check.out;
}

TEST(CliFit, WritesAnEstimatedGyroScaleWithItsIntervalAndTheScaledModel) {
  if (!HaveH5py()) GTEST_SKIP() << "/usr/bin/python3 with h5py is missing";
  const ScratchDir dir("cli_fit_gyro_scale");
  const std::string out = (dir / "fits.h5").string();
  const CommandResult r = RunRockfit(QuickFit({"--estimate-gyro-scale", "common", "--json", "-o", out}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  // The file holds what the JSON says, and w_B_simulated is the model as fitted: (28) of it is the fit's ε.
  const std::string expected_scale = j["gyro_scale"]["value"][1].dump();  // round-trip digits
  const CommandResult check = RunH5pyScript("expected_scale = " + expected_scale + R"(
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], 'r')
g = f['fits/block2-A-1']
s = g['gyro_scale'][()]
mode = g['gyro_scale'].attrs['mode']
assert (mode.decode() if isinstance(mode, bytes) else mode) == 'common', mode
assert abs(s[1] - expected_scale) < 1e-15 and s[0] == s[1] == s[2], s
lo, hi = g['gyro_scale_interval_95_lower'][()], g['gyro_scale_interval_95_upper'][()]
assert all(lo <= s) and all(s <= hi), (lo, s, hi)
assert list(g['gyro_scale_determined'][()]) in ([1, 1, 1], [0, 0, 0])
settings = g.attrs['settings']
assert (settings.decode() if isinstance(settings, bytes) else settings).endswith('; gyro_scale=common')
t = g['time_s'][()]
d = np.linalg.norm(g['w_B_measured'][()] - g['w_B_simulated'][()], axis=1)
w = np.empty_like(t)
w[1:-1] = 0.5 * (t[2:] - t[:-2]); w[0] = 0.5 * (t[1] - t[0]); w[-1] = 0.5 * (t[-1] - t[-2])
eps = float(np.sum(w * d) / (t[-1] - t[0]))
assert abs(eps - g.attrs['epsilon_rad_s']) < 1e-9 * g.attrs['epsilon_rad_s'], (eps, g.attrs['epsilon_rad_s'])
print('ok')
)",
                                            out);
  EXPECT_EQ(check.exit_code, 0) << check.out;
}

// The size of the PNG at `path` ({0, 0} when it is not a PNG).
std::pair<unsigned, unsigned> PngSize(const std::filesystem::path& path) {
  const PngHeader header = ReadPngHeader(path);
  return header.valid ? std::make_pair(header.width, header.height) : std::make_pair(0u, 0u);
}

TEST(CliFit, PlotsOfTheFitAndOfTheParameters) {
  const ScratchDir dir("cli_fit_plot");
  const std::string out = (dir / "fits.h5").string();
  const auto direct = dir / "direct.png";
  const CommandResult fit = RunRockfit(QuickFit({"-o", out, "--plot", direct.string()}));
  if (fit.exit_code == 4 && fit.err.find("gnuplot") != std::string::npos) GTEST_SKIP() << "gnuplot is missing";
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(PngSize(direct), std::make_pair(1200u, 900u));
  const auto from_file = dir / "fit.png";
  ASSERT_EQ(RunRockfit({"plot", "fit", out, "--trial", "block2-A-1", "-o", from_file.string()}).exit_code, 0);
  EXPECT_EQ(PngSize(from_file), std::make_pair(1200u, 900u));
  const auto params = dir / "params.png";
  const CommandResult p = RunRockfit({"plot", "parameters", out, "-o", params.string(), "--json"});
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const nlohmann::json j = nlohmann::json::parse(p.out);
  EXPECT_EQ(j["fits"], 1);
  // The keys every plot kind prints, and the picture really has the size it reports.
  EXPECT_EQ(j["kind"], "parameters");
  EXPECT_EQ(j["format"], "png");
  EXPECT_EQ(PngSize(params), std::make_pair(j["width_px"].get<unsigned>(), j["height_px"].get<unsigned>()));
  EXPECT_EQ(PngSize(params), std::make_pair(1200u, 1200u));
  // A trial that is not in the file: bad input with its name.
  const CommandResult missing = RunRockfit({"plot", "fit", out, "--trial", "nope", "-o", (dir / "x.png").string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace rockfit::testing
