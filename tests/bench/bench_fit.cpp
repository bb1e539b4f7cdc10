// Fitting speed (DESIGN §11): one five-parameter fit of a synthetic trial from no starting point on one core
// (target ≤ 2 s), one evaluation of (28) (one simulation of the window), and the bundled sample campaign
// (data-samples/manifest.toml) on two cores (target: 80 trials in ≤ 1 min).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "rockfit/fitting/batch.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "rockfit/fitting/trial_fit.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/synth_recording.hpp"

namespace {

using namespace rockfit;

// A trial like the paper's block 4 (b1 = 5 cm, h = 20 cm, b2 = 4 cm) with edge impacts in the window, measured
// as `rockfit synth` does by default (noise, quantisation, ringing, a small bias).
struct Trial {
  core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);
  fitting::MeasuredSignal signal;
};

const Trial& SyntheticTrial() {
  static const Trial trial = [] {
    Trial t;
    core::ModelParameters p;
    p.alpha_rad = 0.197;  // the values of the paper's Fig. 14, with λ within the empirical bounds
    p.lambda = 2.185;
    p.lambda_lat = -2.032;
    p.lambda_lon = 0.197;
    io::SynthRecordingOptions o;
    o.t0_s = 1.0;
    o.duration_s = 2.5;
    o.measurement.gyro_bias_dps = Eigen::Vector3d(0.3, -0.2, 0.1);
    o.files.rotation_matrix_file = false;
    const io::SynthRecording rec = io::Synthesize(t.block, p, o);
    for (std::size_t n = 0; n < rec.device.size(); ++n) {
      t.signal.t_s.push_back(static_cast<double>(n) / rec.device.rate_hz);
      t.signal.w_B.push_back(rec.device.gyro_dps[n].cast<double>() * (M_PI / 180.0));
    }
    return t;
  }();
  return trial;
}

void FitOneTrial(benchmark::State& state, fitting::FitMethod method) {
  const Trial& trial = SyntheticTrial();
  fitting::TrialFitOptions options;
  options.fit.method = method;
  options.fit.num_threads = 1;  // one core
  double simulations = 0.0, epsilon = 0.0, rate = 0.0;
  for (auto _ : state) {
    const fitting::TrialFit fit = fitting::FitTrial(trial.block, trial.signal, fitting::ParameterSet::Defaults(), options);
    simulations = static_cast<double>(fit.summary.simulations);
    epsilon = fit.summary.epsilon_rad_s;
    rate = fit.summary.simulations_per_second;
    benchmark::ClobberMemory();
  }
  state.counters["simulations"] = simulations;
  state.counters["sims_per_s"] = rate;
  // In mrad/s: this Google Benchmark prints counters below 1 wrongly.
  state.counters["epsilon_mrad_s"] = 1e3 * epsilon;
}

void BM_FitOneTrialAuto(benchmark::State& state) { FitOneTrial(state, fitting::FitMethod::kAuto); }
void BM_FitOneTrialNelderMead(benchmark::State& state) { FitOneTrial(state, fitting::FitMethod::kNelderMead); }
void BM_FitOneTrialCeres(benchmark::State& state) { FitOneTrial(state, fitting::FitMethod::kCeres); }
BENCHMARK(BM_FitOneTrialAuto)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FitOneTrialNelderMead)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FitOneTrialCeres)->Unit(benchmark::kMillisecond)->Iterations(3);

// One evaluation of (28): one simulation of the window at the measured sample times.
void BM_Error28Evaluation(benchmark::State& state) {
  const Trial& trial = SyntheticTrial();
  fitting::ParameterSet p = fitting::ParameterSet::Defaults();
  p[fitting::ParameterId::kT0] = {1.0, 0.9, 1.1, false};
  p[fitting::ParameterId::kAlpha].value = 0.197;
  p[fitting::ParameterId::kLambda].value = 2.185;
  p[fitting::ParameterId::kLambdaLat].value = -2.032;
  p[fitting::ParameterId::kLambdaLon].value = 0.197;
  const fitting::Objective objective(trial.signal, 1.0 + 0.8, std::make_shared<fitting::SimulatorModel>(trial.block), p);
  double epsilon = 0.0;
  for (auto _ : state) {
    epsilon += objective.Evaluate(p).epsilon_rad_s;
    benchmark::ClobberMemory();
  }
  state.counters["epsilon_mrad_s"] = 1e3 * epsilon / static_cast<double>(state.iterations());
}
BENCHMARK(BM_Error28Evaluation)->Unit(benchmark::kMicrosecond);

// The bundled sample campaign, every trial, two jobs.
void BM_FitSampleCampaign(benchmark::State& state) {
  const std::filesystem::path manifest_path = std::filesystem::path(ROCKFIT_SOURCE_DIR) / "data-samples" / "manifest.toml";
  if (!std::filesystem::exists(manifest_path)) {
    state.SkipWithError("data-samples/manifest.toml is not there");
    return;
  }
  const io::Manifest manifest = io::ReadManifest(manifest_path);
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "rockfit_bench_campaign.h5";
  fitting::BatchOptions options;
  options.jobs = static_cast<int>(state.range(0));
  const fitting::TrialLoader load = [](const io::TrialSpec& trial) {
    io::LoadOptions o;
    o.rate_hz = trial.rate_hz;
    o.rate_origin = "manifest";
    if (!trial.mounting.empty()) o.mounting = io::Mounting::Parse(trial.mounting);
    if (trial.format != "auto") o.format = *io::ParseFormatName(trial.format);
    return io::LoadRecording(trial.files, o);
  };
  std::size_t ok = 0, failed = 0;
  for (auto _ : state) {
    const fitting::BatchReport r = fitting::RunBatch(manifest, out, options, load);
    ok = r.ok;
    failed = r.failed;
  }
  std::filesystem::remove(out);
  state.counters["trials"] = static_cast<double>(manifest.trials.size());
  state.counters["ok"] = static_cast<double>(ok);
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_FitSampleCampaign)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
