// Synthetic measured signals from any trajectory model, with the disturbances of real gyro recordings: white
// noise, ringing after impacts (the paper's Sect. 5.2 notes gyro vibration at impacts) and a constant bias.
// For tests of the fitting machinery; `rockfit synth` makes full x-IMU recordings for the system tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/fitting/trajectory_model.hpp"

namespace rockfit::testing {

struct SyntheticSignalOptions {
  double rate_hz = 256.0;
  double t0_s = 0.5;                   // release time in recording time
  double duration_s = 2.0;             // whole recording
  double noise_rad_s = 0.0;            // standard deviation of white noise per axis
  double ringing_fraction = 0.0;       // ringing amplitude per unit jump of ω at an impact
  double ringing_hz = 55.0;
  double ringing_decay_s = 0.012;
  Eigen::Vector3d bias_rad_s = Eigen::Vector3d::Zero();
  std::uint64_t seed = 7;
};

struct SyntheticSignal {
  fitting::MeasuredSignal signal;
  std::vector<fitting::ModelEvent> events;  // in time after the release
};

// Standard normal deviates by Box–Muller from our own uniform conversion (reproducible on every platform).
inline double NormalDeviate(std::mt19937_64& rng) {
  const double u1 = (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;
  const double u2 = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

inline SyntheticSignal MakeSyntheticSignal(const fitting::TrajectoryModel& model, const core::ModelParameters& params,
                                           const SyntheticSignalOptions& options) {
  SyntheticSignal out;
  const auto n = static_cast<std::size_t>(std::floor(options.duration_s * options.rate_hz)) + 1;
  std::vector<double> after_release;
  std::size_t first_after = n;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / options.rate_hz;
    out.signal.t_s.push_back(t);
    if (t >= options.t0_s) {
      if (first_after == n) first_after = k;
      after_release.push_back(t - options.t0_s);
    }
  }
  fitting::ModelOutput model_out;
  model.Evaluate(params, after_release, &model_out);
  if (!model_out.ok()) throw std::runtime_error("synthetic signal: model failed: " + model_out.failure_category());
  out.events = model_out.events;
  out.signal.w_B.assign(n, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < after_release.size(); ++i) out.signal.w_B[first_after + i] = model_out.w_B[i];
  // Ringing after every impact, proportional to the jump of ω across it.
  std::vector<Eigen::Vector3d> clean = out.signal.w_B;
  for (const fitting::ModelEvent& e : out.events) {
    const double t_e = options.t0_s + e.t_s;
    const auto after = static_cast<std::size_t>(std::ceil(t_e * options.rate_hz));
    if (after == 0 || after >= n) continue;
    const Eigen::Vector3d jump = clean[after] - clean[after - 1];
    for (std::size_t k = after; k < n; ++k) {
      const double dt = out.signal.t_s[k] - t_e;
      if (dt > 10 * options.ringing_decay_s) break;
      out.signal.w_B[k] += options.ringing_fraction * jump * std::exp(-dt / options.ringing_decay_s) *
                           std::sin(2.0 * M_PI * options.ringing_hz * dt);
    }
  }
  std::mt19937_64 rng(options.seed);
  for (std::size_t k = 0; k < n; ++k) {
    for (int c = 0; c < 3; ++c) out.signal.w_B[k][c] += options.bias_rad_s[c] + options.noise_rad_s * NormalDeviate(rng);
  }
  return out;
}

}  // namespace rockfit::testing
