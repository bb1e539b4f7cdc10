// Fitting speed (docs/design.md §11): one five-parameter fit of a synthetic trial from no starting point on one core
// (target ≤ 2 s), one evaluation of (28) (one simulation of the window), and the bundled sample campaign
// (data-samples/manifest.toml) on two cores (target: 80 trials in ≤ 1 min); each with the interval settings of
// `--intervals` (none, fast, thorough).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <memory>
#include <random>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "rockfit/app/recording_input.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "rockfit/fitting/trial_problem.hpp"
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

// The gyro of a synthetic recording as the fitter reads it (ω in rad/s at the device's sample times).
fitting::MeasuredSignal SignalOf(const io::SynthRecording& rec) {
  fitting::MeasuredSignal signal;
  for (std::size_t n = 0; n < rec.device.size(); ++n) {
    signal.t_s.push_back(static_cast<double>(n) / rec.device.rate_hz);
    signal.w_B.push_back(rec.device.gyro_dps[n].cast<double>() * (M_PI / 180.0));
  }
  return signal;
}

// The bundled sample campaign's trials as `rockfit batch` loads them (app::LoadManifestTrial), with their blocks;
// false (the benchmark skipped) when data-samples/manifest.toml is not there.
bool LoadSampleCampaign(benchmark::State& state, std::vector<fitting::MeasuredSignal>* signals,
                        std::vector<core::Block>* blocks) {
  const std::filesystem::path manifest_path = std::filesystem::path(ROCKFIT_SOURCE_DIR) / "data-samples" / "manifest.toml";
  if (!std::filesystem::exists(manifest_path)) {
    state.SkipWithError("data-samples/manifest.toml is not there");
    return false;
  }
  const io::Manifest manifest = io::ReadManifest(manifest_path);
  for (const io::TrialSpec& trial : manifest.trials) {
    const io::Recording r = app::LoadManifestTrial(trial);
    signals->push_back({r.t_s, r.w_B, {}, {}});
    blocks->push_back(manifest.FindBlock(trial.block_id).ToBlock());
  }
  return true;
}

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
    t.signal = SignalOf(io::Synthesize(t.block, p, o));
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
  fitting::FitSummary summary;
  for (auto _ : state) {
    // Everything `rockfit fit` does after reading the files: data estimate, bias, window, fit.
    const fitting::TrialProblem problem =
        fitting::PrepareTrialProblem(trial.signal, trial.block, fitting::ParameterSet::Defaults());
    summary = fitting::Fit(problem.objective, problem.start, options);
    simulations = static_cast<double>(summary.simulations);
    epsilon = summary.epsilon_rad_s;
    rate = summary.simulations_per_second;
    interval_simulations = static_cast<double>(summary.uncertainty.evaluations);
    benchmark::ClobberMemory();
  }
  state.counters["simulations"] = simulations;
  // Where the simulations go: the runs of each stage of the last fit.
  for (const fitting::StageReport& stage : summary.stages) {
    state.counters["sims_" + stage.name] += static_cast<double>(stage.evaluations);
  }
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

// A planar trial of the same block (λ_lat = 0, so the run stays in the plane), fitted with λ_lat fixed at 0: the
// case where the simulator gives exact derivatives (core/planar_sensitivity.hpp). Arg 1 uses them in Ceres
// (CeresOptions::exact_jacobian), Arg 0 the limited differences; same binary, same trial.
const Trial& PlanarSyntheticTrial() {
  static const Trial trial = [] {
    Trial t;
    core::ModelParameters p;
    p.alpha_rad = 0.15;
    p.lambda = 1.0;
    p.lambda_lat = 0.0;
    p.lambda_lon = 0.6;
    io::SynthRecordingOptions o;
    o.t0_s = 1.0;
    o.duration_s = 2.5;
    o.files.rotation_matrix_file = false;
    t.signal = SignalOf(io::Synthesize(t.block, p, o));
    return t;
  }();
  return trial;
}

fitting::ParameterSet PlanarParameters() {
  fitting::ParameterSet p = fitting::ParameterSet::Defaults();
  p[fitting::ParameterId::kLambdaLat].value = 0.0;
  p[fitting::ParameterId::kLambdaLat].fixed = true;
  return p;
}

// The whole fit (global stage, Nelder–Mead, Ceres; no intervals).
void BM_FitPlanarTrial(benchmark::State& state) {
  const Trial& trial = PlanarSyntheticTrial();
  fitting::FitOptions options;
  options.intervals.method = fitting::IntervalMethod::kNone;
  options.num_threads = 1;
  options.ceres.exact_jacobian = state.range(0) != 0;
  double simulations = 0.0, epsilon = 0.0;
  fitting::FitSummary summary;
  for (auto _ : state) {
    const fitting::TrialProblem problem = fitting::PrepareTrialProblem(trial.signal, trial.block, PlanarParameters());
    summary = fitting::Fit(problem.objective, problem.start, options);
    simulations = static_cast<double>(summary.simulations);
    epsilon = summary.epsilon_rad_s;
    benchmark::ClobberMemory();
  }
  // Where the simulations go: per stage, and the rest (start, identifiability, checks).
  double in_stages = 0.0;
  for (const fitting::StageReport& stage : summary.stages) {
    state.counters["sims_" + stage.name] += static_cast<double>(stage.evaluations);
    in_stages += static_cast<double>(stage.evaluations);
  }
  state.counters["sims_other"] = simulations - in_stages;
  state.counters["simulations"] = simulations;
  state.counters["epsilon_mrad_s"] = 1e3 * epsilon;
}
BENCHMARK(BM_FitPlanarTrial)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

// The Ceres local stage alone, from a start a few resolutions away from the truth (t0 + 2 ms, α − 4 mrad,
// λ_lon + 0.03).
void BM_CeresLocalStagePlanar(benchmark::State& state) {
  const Trial& trial = PlanarSyntheticTrial();
  const fitting::TrialProblem problem = fitting::PrepareTrialProblem(trial.signal, trial.block, PlanarParameters());
  fitting::ParameterSet start = problem.objective.parameters();
  start[fitting::ParameterId::kT0].value = std::clamp(1.002, start[fitting::ParameterId::kT0].lower,
                                                      start[fitting::ParameterId::kT0].upper);
  start[fitting::ParameterId::kAlpha].value = 0.146;
  start[fitting::ParameterId::kLambda].value = 1.0;
  start[fitting::ParameterId::kLambdaLon].value = 0.63;
  fitting::CeresOptions options;
  options.exact_jacobian = state.range(0) != 0;
  const auto ceres = fitting::MakeCeres(options);
  double runs = 0.0, epsilon = 0.0;
  for (auto _ : state) {
    const fitting::LocalResult r = ceres->Minimize(problem.objective, problem.objective.FreeValues(start));
    runs = static_cast<double>(r.evaluations);
    epsilon = r.epsilon_rad_s;
    benchmark::ClobberMemory();
  }
  state.counters["simulations"] = runs;
  state.counters["epsilon_mrad_s"] = 1e3 * epsilon;
}
BENCHMARK(BM_CeresLocalStagePlanar)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One model run of a trial's window (1 s at 256 Hz after the release) without (Arg 0) and with (Arg 1) the exact
// derivatives of its samples: the price of the sensitivity pass.
void RunWithSensitivities(benchmark::State& state, const core::Block& block, const core::ModelParameters& p) {
  const fitting::SimulatorModel model(block);
  std::vector<double> times;
  for (int k = 0; k <= 256; ++k) times.push_back(k / 256.0);
  fitting::ModelOutput out;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      model.Evaluate(p, times, &out);
    } else {
      model.EvaluateWithSensitivities(p, times, &out);
    }
    benchmark::ClobberMemory();
  }
  state.counters["with_derivatives"] = out.dw_B_dparams.empty() ? 0.0 : 1.0;
  state.counters["impacts"] = static_cast<double>(out.events.size());
}

// The planar trial's window.
void BM_PlanarRunWithSensitivities(benchmark::State& state) {
  core::ModelParameters p;
  p.alpha_rad = 0.15;
  p.lambda_lat = 0.0;
  p.lambda_lon = 0.6;
  RunWithSensitivities(state, PlanarSyntheticTrial().block, p);
}
BENCHMARK(BM_PlanarRunWithSensitivities)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The same for a 3D run (the synthetic trial's parameters, λ_lat = −2.032: vertex rocking and edge impacts) over
// 1 s: the price of the spatial pass (core/spatial_sensitivity.hpp).
void BM_SpatialRunWithSensitivities(benchmark::State& state) {
  core::ModelParameters p;
  p.alpha_rad = 0.197;
  p.lambda = 2.185;
  p.lambda_lat = -2.032;
  p.lambda_lon = 0.197;
  RunWithSensitivities(state, SyntheticTrial().block, p);
}
BENCHMARK(BM_SpatialRunWithSensitivities)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The quality criterion for CeresOptions::exact_jacobian: each trial fitted with and without it (no intervals, one
// core), the largest relative rise of ε over the trials, and the simulations of each. Arg 0: the bundled sample
// campaign (3D trials, λ_lat free: the derivatives of core/spatial_sensitivity.hpp where a run has them); Arg 1: 20
// planar synthetic trials (α, λ_lon, t0 and the noise seed drawn with a fixed seed; λ_lat fixed at 0).
void BM_ExactJacobianQuality(benchmark::State& state) {
  std::vector<fitting::MeasuredSignal> signals;
  std::vector<core::Block> blocks;
  std::vector<fitting::ParameterSet> parameters;
  if (state.range(0) == 0) {
    if (!LoadSampleCampaign(state, &signals, &blocks)) return;
    parameters.assign(signals.size(), fitting::ParameterSet::Defaults());
  } else {
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> alpha(0.08, 0.2), lambda_lon(0.3, 0.9), t0(0.8, 1.2);
    const core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);
    for (int i = 0; i < 20; ++i) {
      core::ModelParameters p;
      p.alpha_rad = alpha(rng);
      p.lambda_lat = 0.0;
      p.lambda_lon = lambda_lon(rng);
      io::SynthRecordingOptions o;
      o.t0_s = t0(rng);
      o.duration_s = 2.5;
      o.measurement.seed = static_cast<std::uint64_t>(i + 1);
      o.files.rotation_matrix_file = false;
      signals.push_back(SignalOf(io::Synthesize(block, p, o)));
      blocks.push_back(block);
      parameters.push_back(PlanarParameters());
    }
  }
  double worst_rise = -1.0, simulations_off = 0.0, simulations_on = 0.0, exact_better = 0.0;
  // The local stage (Ceres): its model runs and wall time with and without the exact Jacobian.
  double ceres_runs_off = 0.0, ceres_runs_on = 0.0, ceres_s_off = 0.0, ceres_s_on = 0.0;
  double fit_cpu_s_off = 0.0, fit_cpu_s_on = 0.0;
  auto add_ceres = [](const fitting::FitSummary& s, double* runs, double* seconds) {
    for (const fitting::StageReport& stage : s.stages) {
      if (stage.name != "ceres") continue;
      *runs += static_cast<double>(stage.evaluations);
      *seconds += stage.wall_time_s;
    }
  };
  for (auto _ : state) {
    for (std::size_t i = 0; i < signals.size(); ++i) {
      const fitting::TrialProblem problem = fitting::PrepareTrialProblem(signals[i], blocks[i], parameters[i]);
      fitting::FitOptions options;
      options.num_threads = 1;
      options.intervals.method = fitting::IntervalMethod::kNone;
      options.ceres.exact_jacobian = false;  // the differences: Nelder–Mead, then the Ceres polish
      // Process CPU time of each whole fit (one thread; the machine is shared, so wall time is not the measure).
      const std::clock_t c0 = std::clock();
      const fitting::FitSummary off = fitting::Fit(problem.objective, problem.start, options);
      const std::clock_t c1 = std::clock();
      options.ceres.exact_jacobian = true;
      const fitting::FitSummary on = fitting::Fit(problem.objective, problem.start, options);
      const std::clock_t c2 = std::clock();
      fit_cpu_s_off += static_cast<double>(c1 - c0) / CLOCKS_PER_SEC;
      fit_cpu_s_on += static_cast<double>(c2 - c1) / CLOCKS_PER_SEC;
      const double rise = (on.epsilon_rad_s - off.epsilon_rad_s) / off.epsilon_rad_s;
      worst_rise = std::max(worst_rise, rise);
      exact_better += rise < 0.0 ? 1.0 : 0.0;
      simulations_off += static_cast<double>(off.simulations);
      simulations_on += static_cast<double>(on.simulations);
      add_ceres(off, &ceres_runs_off, &ceres_s_off);
      add_ceres(on, &ceres_runs_on, &ceres_s_on);
    }
  }
  state.counters["ceres_runs_off"] = ceres_runs_off;
  state.counters["ceres_runs_on"] = ceres_runs_on;
  state.counters["ceres_ms_off"] = 1e3 * ceres_s_off;
  state.counters["ceres_ms_on"] = 1e3 * ceres_s_on;
  state.counters["fit_cpu_ms_off"] = 1e3 * fit_cpu_s_off;
  state.counters["fit_cpu_ms_on"] = 1e3 * fit_cpu_s_on;
  state.counters["trials"] = static_cast<double>(signals.size());
  // In parts per million: this Google Benchmark prints counters below 1 wrongly.
  state.counters["worst_epsilon_rise_ppm"] = 1e6 * worst_rise;
  state.counters["trials_lower_epsilon"] = exact_better;
  state.counters["simulations_off"] = simulations_off;
  state.counters["simulations_on"] = simulations_on;
}
BENCHMARK(BM_ExactJacobianQuality)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

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
  std::vector<fitting::MeasuredSignal> signals;
  std::vector<core::Block> blocks;
  if (!LoadSampleCampaign(state, &signals, &blocks)) return;
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
