// Speed of the hybrid simulator (docs/design.md §11: the paper's Fig. 14 window — about 1 s of motion, 25 impacts,
// 256 Hz output — in at most 0.5 ms on one core). Simulations per second are reported as items/s; run with
// --benchmark_repetitions=N --benchmark_report_aggregates_only=true for the median.
#include <benchmark/benchmark.h>

#include <cmath>

#include "rockfit/core/simulator.hpp"
#include "simulation_cases.hpp"

namespace {

using rockfit::core::Block;
using rockfit::core::ModelParameters;
using rockfit::core::SimulationOptions;
using rockfit::core::Trajectory;

using rockfit::testing::Fig14Parameters;
using rockfit::testing::WithinBoundsParameters;

void Run(benchmark::State& state, const ModelParameters& params, bool sample_attitude) {
  SimulationOptions options;  // stop at phase 4, 256 Hz
  options.sample_attitude = sample_attitude;
  std::size_t impacts = 0;
  std::size_t samples = 0;
  long evaluations = 0;
  long guard_evaluations = 0;
  long steps = 0;
  double t_end = 0.0;
  const Block block = rockfit::testing::Fig14Block();  // built once, outside the timed loop
  for (auto _ : state) {
    const Trajectory tr = rockfit::core::Simulate(block, params, options);
    benchmark::DoNotOptimize(tr.w_B.data());
    if (tr.end_reason != rockfit::core::EndReason::kPhase4) state.SkipWithError("the run did not reach phase 4");
    impacts = tr.impacts.size();
    samples = tr.t_s.size();
    evaluations = tr.num_evaluations;
    guard_evaluations = tr.num_guard_evaluations;
    steps = tr.num_steps;
    t_end = tr.t_end_s;
  }
  state.SetItemsProcessed(state.iterations());  // simulations
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["rhs_evaluations"] = static_cast<double>(evaluations);
  state.counters["guard_evaluations"] = static_cast<double>(guard_evaluations);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["t_end_s"] = t_end;
}

void BM_SimulateFig14(benchmark::State& state) { Run(state, Fig14Parameters(), true); }
BENCHMARK(BM_SimulateFig14)->Unit(benchmark::kMicrosecond);

void BM_SimulateFig14_NoAttitude(benchmark::State& state) { Run(state, Fig14Parameters(), false); }
BENCHMARK(BM_SimulateFig14_NoAttitude)->Unit(benchmark::kMicrosecond);

void BM_SimulateWithinBoundsZeno(benchmark::State& state) { Run(state, WithinBoundsParameters(), true); }
BENCHMARK(BM_SimulateWithinBoundsZeno)->Unit(benchmark::kMicrosecond);

void BM_SimulateWithinBoundsZeno_NoAttitude(benchmark::State& state) { Run(state, WithinBoundsParameters(), false); }
BENCHMARK(BM_SimulateWithinBoundsZeno_NoAttitude)->Unit(benchmark::kMicrosecond);

// One run as a fit makes it (fitting::SimulatorModel): the Fig. 14 case over the 0.8 s window of the fitting
// benchmark's trial, ω sampled at 256 Hz without attitudes, stopped at the last sample, at relative tolerance
// 10^-Arg (absolute tolerance 100 times smaller). Its cost is per vertex segment (one DOP853 step or two between
// impacts), so it hardly falls with the tolerance (README.md, "Performance").
void BM_SimulateFitWindow(benchmark::State& state) {
  SimulationOptions options;
  options.stop = rockfit::core::StopCondition::kTMax;
  options.sample_attitude = false;
  options.max_impacts = 5000;
  options.rel_tol = std::pow(10.0, -static_cast<double>(state.range(0)));
  options.abs_tol = 1e-2 * options.rel_tol;
  constexpr double kRate_hz = 256.0;
  constexpr double kWindow_s = 0.8;
  for (int n = 0; n / kRate_hz <= kWindow_s; ++n) options.sample_times_s.push_back(n / kRate_hz);
  options.t_max_s = options.sample_times_s.back();
  const Block block = rockfit::testing::Fig14Block();
  const ModelParameters params = Fig14Parameters();
  std::size_t impacts = 0, segments = 0;
  long evaluations = 0, steps = 0, guard_evaluations = 0;
  for (auto _ : state) {
    const Trajectory tr = rockfit::core::Simulate(block, params, options);
    benchmark::DoNotOptimize(tr.w_B.data());
    if (tr.w_B.size() != options.sample_times_s.size()) state.SkipWithError("the run ended before its last sample");
    impacts = tr.impacts.size();
    segments = tr.segments.size();
    evaluations = tr.num_evaluations;
    guard_evaluations = tr.num_guard_evaluations;
    steps = tr.num_steps;
  }
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["segments"] = static_cast<double>(segments);
  state.counters["rhs_evaluations"] = static_cast<double>(evaluations);
  state.counters["guard_evaluations"] = static_cast<double>(guard_evaluations);
  state.counters["steps"] = static_cast<double>(steps);
}
BENCHMARK(BM_SimulateFitWindow)->Arg(12)->Arg(9)->Arg(7)->Unit(benchmark::kMicrosecond);

// The planar Housner case run to rest (about 4.4 s, 85 facet impacts, 256 Hz samples, default tolerances). The
// time per simulated second is the reported time divided by the counter t_end_s (also given as us_per_sim_s).
void RunPlanar(benchmark::State& state, bool sample_attitude) {
  SimulationOptions options;
  options.stop = rockfit::core::StopCondition::kRest;
  options.sample_attitude = sample_attitude;
  const Block block = rockfit::testing::PlanarHousnerBlock();
  const ModelParameters params = rockfit::testing::PlanarHousnerParameters();
  std::size_t impacts = 0;
  double t_end = 0.0;
  for (auto _ : state) {
    const Trajectory tr = rockfit::core::Simulate(block, params, options);
    benchmark::DoNotOptimize(tr.w_B.data());
    if (tr.end_reason != rockfit::core::EndReason::kRest) state.SkipWithError("the run did not come to rest");
    impacts = tr.impacts.size();
    t_end = tr.t_end_s;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["t_end_s"] = t_end;
  // Simulated seconds per wall second, inverted by benchmark's kIsRate|kInvert: microseconds per simulated second.
  state.counters["us_per_sim_s"] = benchmark::Counter(t_end * static_cast<double>(state.iterations()) * 1e-6,
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_SimulatePlanarHousnerToRest(benchmark::State& state) { RunPlanar(state, true); }
BENCHMARK(BM_SimulatePlanarHousnerToRest)->Unit(benchmark::kMicrosecond);

void BM_SimulatePlanarHousnerToRest_NoAttitude(benchmark::State& state) { RunPlanar(state, false); }
BENCHMARK(BM_SimulatePlanarHousnerToRest_NoAttitude)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
