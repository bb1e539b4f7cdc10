// Speed of a fragility study (fitting/quake/include/rockfit/quake/fragility_study.hpp): simulations per second on one core for 30 s
// Clough–Penzien records at 200 Hz on a granite block of the sample campaign (h = 0.2 m, b1 = 0.05 m, b2 = 0.035 m)
// with spread impact parameters and random incidence, PGA levels from below uplift (0.15 g) to certain overturning.
// items/s is simulations per second on one thread; the counters say how the samples ended.
#include <benchmark/benchmark.h>

#include <numeric>

#include "rockfit/quake/fragility_study.hpp"
#include "generated_records.hpp"
#include "rockfit/io/stochastic_ground_motion.hpp"

namespace {

using namespace rockfit;

quake::FragilityStudyOptions Study() {
  quake::FragilityStudyOptions s;
  quake::FragilityBlock b;
  b.id = "block2";
  b.block = core::Block::FromDensity(0.05000453, 0.035, 0.2, 2692);
  b.lambda = {2.2, 0.1};
  b.lambda_lat = {-1.9, 0.2};
  b.lambda_lon = {0.22, 0.02};
  s.blocks = {b};
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    s.records.push_back({"synthetic:" + std::to_string(seed), testing::GeneratedRecordAlongX(seed, 30.0, io::CloughPenzienOptions{}.pga_m_s2, 15.0)});
  }
  s.levels = {0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6};
  s.samples_per_level = 16;
  s.seed = 1;
  return s;
}

void BM_FragilitySamples30sRecords(benchmark::State& state) {
  const quake::FragilityStudyOptions study = Study();
  std::vector<std::int64_t> all(static_cast<std::size_t>(study.num_samples()));
  std::iota(all.begin(), all.end(), 0);
  std::vector<quake::SampleOutcome> out;
  for (auto _ : state) {
    out = quake::RunSamples(study, all, 1);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(all.size()));
  double overturned = 0, counted = 0, impacts = 0;
  for (const auto& o : out) overturned += o.overturned, counted += o.counted, impacts += static_cast<double>(o.num_impacts);
  state.counters["samples"] = static_cast<double>(out.size());
  state.counters["overturned"] = overturned;
  state.counters["counted"] = counted;
  state.counters["impacts_per_sample"] = impacts / static_cast<double>(out.size());
}
BENCHMARK(BM_FragilitySamples30sRecords)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
