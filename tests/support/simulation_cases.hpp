// The block and parameter sets that several simulator tests and benchmarks run: the paper's Fig. 14 trial
// and a case within the bounds (25), (27). One definition, so that the tests and the benchmark time and
// check the same motion.
#pragma once

#include <cmath>

#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::testing {

// The block of the paper's Fig. 14 (its block 4): granite 2692 kg/m³, h = 0.20 m, b1 = h·tan 0.245, b2 = 0.04 m.
inline core::Block Fig14Block() { return core::Block::FromDensity(0.2 * std::tan(0.245), 0.04, 0.2, 2692.0); }

// ω samples only (no attitudes) at rate_hz from time_shift_s over window_s, the run ending at the last sample: the
// runs the fitting's model asks of the simulator.
inline core::SimulationOptions SampledRateOptions(double window_s, double rate_hz, double time_shift_s = 0.0) {
  core::SimulationOptions options;
  options.sample_attitude = false;
  options.stop = core::StopCondition::kTMax;
  const int n = static_cast<int>(window_s * rate_hz);
  for (int i = 0; i <= n; ++i) options.sample_times_s.push_back(i / rate_hz + time_shift_s);
  options.t_max_s = options.sample_times_s.back();
  return options;
}

// The model parameters of the Fig. 14 simulation.
inline core::ModelParameters Fig14Parameters() {
  core::ModelParameters p;
  p.alpha_rad = 0.197;
  p.lambda = 2.185;
  p.lambda_lat = -2.032;
  p.lambda_lon = 0.197;
  return p;
}

// Within the bounds (25), (27): about 180 edge impacts end in a Zeno sequence before phase 4.
inline core::ModelParameters WithinBoundsParameters() {
  core::ModelParameters p;
  p.alpha_rad = 0.2;
  p.lambda = 0.6;
  p.lambda_lat = 0.3;
  p.lambda_lon = 0.7;
  return p;
}

// The planar Housner case of the speed targets (docs/design.md §11): a 0.1 × 0.1 × 0.4 m granite block
// released at α = 0.2 about V1V2 with λ = λ_lon = 1 and λ_lat = 0, so that every facet impact follows (6) and the
// motion stays in the x–z plane; it comes to rest after about 4.4 s and 85 facet impacts.
inline core::Block PlanarHousnerBlock() { return core::Block::FromDensity(0.05, 0.05, 0.2, 2692.0); }

inline core::ModelParameters PlanarHousnerParameters() {
  core::ModelParameters p;
  p.alpha_rad = 0.2;
  p.lambda = 1.0;
  p.lambda_lat = 0.0;
  p.lambda_lon = 1.0;
  return p;
}

}  // namespace rockfit::testing
