// Speed of the impact maps: the simulator calls EdgeImpact at every edge impact and FacetImpact at every
// facet impact, and a fit runs thousands of simulations.
#include <benchmark/benchmark.h>

#include "rockfit/core/impact_maps.hpp"

namespace {

using rockfit::core::Block;

const Block& Fig11Block() {
  static const Block block = Block::FromMass(0.05, 0.03, 0.20, 1.0);
  return block;
}

void BM_EdgeImpact(benchmark::State& state) {
  const Block& block = Fig11Block();
  const Eigen::Matrix3d R_WB = rockfit::core::EdgeImpactAttitude(block, 3, 4, 0.05);
  Eigen::Vector3d w_minus(0.5, -0.3, 0.1);
  const rockfit::core::EdgeImpactParameters params{0.6, 0.0};
  for (auto _ : state) {
    benchmark::DoNotOptimize(w_minus);
    const rockfit::core::ImpactOutcome out = rockfit::core::EdgeImpact(block, R_WB, 3, 4, w_minus, params);
    benchmark::DoNotOptimize(out.w_plus_W);
  }
}
BENCHMARK(BM_EdgeImpact);

void BM_FacetImpactNoSpin(benchmark::State& state) {
  const Block& block = Fig11Block();
  Eigen::Vector3d w_minus(0.0, 1.0, 0.0);
  const rockfit::core::FacetImpactParameters params{0.3, 0.8};
  for (auto _ : state) {
    benchmark::DoNotOptimize(w_minus);
    const rockfit::core::ImpactOutcome out = rockfit::core::FacetImpact(block, 2, w_minus, params);
    benchmark::DoNotOptimize(out.w_plus_W);
  }
}
BENCHMARK(BM_FacetImpactNoSpin);

void BM_EdgeImpactSingularLambdas(benchmark::State& state) {
  const Block& block = Fig11Block();
  const Eigen::Matrix3d R_WB = rockfit::core::EdgeImpactAttitude(block, 3, 4, 0.05);
  for (auto _ : state) benchmark::DoNotOptimize(rockfit::core::EdgeImpactSingularLambdas(block, R_WB, 3, 4));
}
BENCHMARK(BM_EdgeImpactSingularLambdas);

}  // namespace

BENCHMARK_MAIN();
