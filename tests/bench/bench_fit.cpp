// Fitting speed (docs/design.md §11): one five-parameter fit of a synthetic trial from no starting point on one core
// (target ≤ 2 s), one evaluation of (28) (one simulation of the window), and the bundled sample campaign
// (data-samples/manifest.toml) on two cores (target: 80 trials in ≤ 1 min); each with the interval settings of
// `--intervals` (none, fast, thorough).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/mounting.hpp"
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

void FitOneTrial(benchmark::State& state, fitting::FitMethod method,
                 fitting::IntervalMethod intervals = fitting::IntervalMethod::kFast) {
  const Trial& trial = SyntheticTrial();
  fitting::FitOptions options;
  options.method = method;
  options.intervals.method = intervals;
  options.num_threads = 1;  // one core
  double simulations = 0.0, epsilon = 0.0, rate = 0.0, interval_simulations = 0.0;
  for (auto _ : state) {
    // Everything `rockfit fit` does after reading the files: data estimate, bias, window, fit.
    const fitting::TrialProblem problem =
        fitting::PrepareTrialProblem(trial.signal, trial.block, fitting::ParameterSet::Defaults());
    const fitting::FitSummary summary = fitting::Fit(problem.objective, problem.start, options);
    simulations = static_cast<double>(summary.simulations);
    epsilon = summary.epsilon_rad_s;
    rate = summary.simulations_per_second;
    interval_simulations = static_cast<double>(summary.uncertainty.evaluations);
    benchmark::ClobberMemory();
  }
  state.counters["simulations"] = simulations;
  state.counters["interval_simulations"] = interval_simulations;
  state.counters["sims_per_s"] = rate;
  // In mrad/s: this Google Benchmark prints counters below 1 wrongly.
  state.counters["epsilon_mrad_s"] = 1e3 * epsilon;
}

void BM_FitOneTrialAuto(benchmark::State& state) { FitOneTrial(state, fitting::FitMethod::kAuto); }
void BM_FitOneTrialNelderMead(benchmark::State& state) { FitOneTrial(state, fitting::FitMethod::kNelderMead); }
void BM_FitOneTrialCeres(benchmark::State& state) { FitOneTrial(state, fitting::FitMethod::kCeres); }
// `rockfit fit` with each --intervals setting (auto): the cost of the intervals per trial.
void BM_FitOneTrialIntervalsNone(benchmark::State& state) {
  FitOneTrial(state, fitting::FitMethod::kAuto, fitting::IntervalMethod::kNone);
}
void BM_FitOneTrialIntervalsThorough(benchmark::State& state) {
  FitOneTrial(state, fitting::FitMethod::kAuto, fitting::IntervalMethod::kThorough);
}
BENCHMARK(BM_FitOneTrialAuto)->Unit(benchmark::kMillisecond)->Iterations(3);  // --intervals fast
BENCHMARK(BM_FitOneTrialIntervalsNone)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FitOneTrialIntervalsThorough)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FitOneTrialNelderMead)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FitOneTrialCeres)->Unit(benchmark::kMillisecond)->Iterations(3);

// The synthetic trial's own parameters, t0 free within ±0.1 s.
fitting::ParameterSet TruthOfSyntheticTrial() {
  fitting::ParameterSet p = fitting::ParameterSet::Defaults();
  p[fitting::ParameterId::kT0] = {1.0, 0.9, 1.1, false};
  p[fitting::ParameterId::kAlpha].value = 0.197;
  p[fitting::ParameterId::kLambda].value = 2.185;
  p[fitting::ParameterId::kLambdaLat].value = -2.032;
  p[fitting::ParameterId::kLambdaLon].value = 0.197;
  return p;
}

// One evaluation of (28): one simulation of the window at the measured sample times.
void BM_Error28Evaluation(benchmark::State& state) {
  const Trial& trial = SyntheticTrial();
  const fitting::ParameterSet p = TruthOfSyntheticTrial();
  const fitting::Objective objective(trial.signal, 1.0 + 0.8, std::make_shared<fitting::SimulatorModel>(trial.block), p);
  double epsilon = 0.0;
  for (auto _ : state) {
    epsilon += objective.Evaluate(p).epsilon_rad_s;
    benchmark::ClobberMemory();
  }
  state.counters["epsilon_mrad_s"] = 1e3 * epsilon / static_cast<double>(state.iterations());
}
BENCHMARK(BM_Error28Evaluation)->Unit(benchmark::kMicrosecond);

// The same evaluation with the simulator's relative tolerance 10^-Arg (absolute tolerance 100 times smaller): what a
// looser tolerance saves, and how far ε moves (epsilon_change_rel against the default 1e-12).
void BM_Error28EvaluationAtTolerance(benchmark::State& state) {
  const Trial& trial = SyntheticTrial();
  const fitting::ParameterSet p = TruthOfSyntheticTrial();
  fitting::SimulatorModelOptions loose;
  loose.simulation.rel_tol = std::pow(10.0, -static_cast<double>(state.range(0)));
  loose.simulation.abs_tol = 1e-2 * loose.simulation.rel_tol;
  const fitting::Objective reference(trial.signal, 1.8, std::make_shared<fitting::SimulatorModel>(trial.block), p);
  const fitting::Objective objective(trial.signal, 1.8, std::make_shared<fitting::SimulatorModel>(trial.block, loose), p);
  double epsilon = 0.0;
  for (auto _ : state) {
    epsilon = objective.Evaluate(p).epsilon_rad_s;
    benchmark::ClobberMemory();
  }
  const double epsilon_reference = reference.Evaluate(p).epsilon_rad_s;
  state.counters["epsilon_change_rel"] = std::abs(epsilon - epsilon_reference) / epsilon_reference;
}
BENCHMARK(BM_Error28EvaluationAtTolerance)->Arg(12)->Arg(10)->Arg(9)->Arg(8)->Arg(7)->Unit(benchmark::kMicrosecond);

// The bundled sample campaign, every trial, two trials at a time (as `rockfit batch -j 2`, without the files).
void FitSampleCampaign(benchmark::State& state, fitting::IntervalMethod intervals) {
  const std::filesystem::path manifest_path = std::filesystem::path(ROCKFIT_SOURCE_DIR) / "data-samples" / "manifest.toml";
  if (!std::filesystem::exists(manifest_path)) {
    state.SkipWithError("data-samples/manifest.toml is not there");
    return;
  }
  const io::Manifest manifest = io::ReadManifest(manifest_path);
  std::vector<fitting::MeasuredSignal> signals;
  std::vector<core::Block> blocks;
  for (const io::TrialSpec& trial : manifest.trials) {
    io::LoadOptions o;
    o.rate_hz = trial.rate_hz;
    o.rate_origin = io::RateSource::kManifest;
    if (!trial.mounting.empty()) o.mounting = io::Mounting::Parse(trial.mounting);
    const io::Recording r = io::LoadRecording(trial.files, o);
    signals.push_back({r.t_s, r.w_B});
    blocks.push_back(manifest.FindBlock(trial.block_id).ToBlock());
  }
  fitting::FitOptions options;
  options.num_threads = 1;
  options.intervals.method = intervals;
  std::vector<double> epsilon(signals.size(), 0.0);
  tbb::task_arena arena(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, signals.size(), [&](std::size_t i) {
        const fitting::TrialProblem problem =
            fitting::PrepareTrialProblem(signals[i], blocks[i], fitting::ParameterSet::Defaults());
        epsilon[i] = fitting::Fit(problem.objective, problem.start, options).epsilon_rad_s;
      });
    });
  }
  double mean = 0.0;
  for (double e : epsilon) mean += e / static_cast<double>(epsilon.size());
  state.counters["trials"] = static_cast<double>(signals.size());
  state.counters["mean_epsilon_mrad_s"] = 1e3 * mean;
}
// `rockfit batch -j 2` with --intervals fast, and with the command line's default (thorough).
void BM_FitSampleCampaign(benchmark::State& state) { FitSampleCampaign(state, fitting::IntervalMethod::kFast); }
void BM_FitSampleCampaignIntervalsThorough(benchmark::State& state) {
  FitSampleCampaign(state, fitting::IntervalMethod::kThorough);
}
BENCHMARK(BM_FitSampleCampaign)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_FitSampleCampaignIntervalsThorough)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
