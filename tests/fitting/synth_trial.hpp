// Synthetic trials from the real simulator and the x-IMU measurement model of `rockfit synth`
// (io/synth_recording.hpp), held in memory: noise, quantisation, bias, ringing after impacts.
#pragma once

#include <cmath>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/io/synth_recording.hpp"

namespace rockfit::testing {

struct SynthTrial {
  core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);  // θ_c = 0.245 rad (paper Sect. 3.1)
  fitting::ParameterSet truth = fitting::ParameterSet::Defaults();
  fitting::MeasuredSignal signal;
  std::optional<double> phase4_end_s;
};

// A recording of `duration_s` with the release at t0_s; gyro bias in deg/s per axis.
inline SynthTrial MakeSynthTrial(double alpha, double lambda, double lambda_lat, double lambda_lon, std::uint64_t seed = 1,
                                 double t0_s = 1.0, double duration_s = 2.5,
                                 const Eigen::Vector3d& gyro_bias_dps = Eigen::Vector3d(0.3, -0.2, 0.1),
                                 const core::Block& block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0),
                                 bool ideal_sensor = false) {
  SynthTrial trial;
  trial.block = block;
  using fitting::ParameterId;
  trial.truth[ParameterId::kT0].value = t0_s;
  trial.truth[ParameterId::kAlpha].value = alpha;
  trial.truth[ParameterId::kLambda].value = lambda;
  trial.truth[ParameterId::kLambdaLat].value = lambda_lat;
  trial.truth[ParameterId::kLambdaLon].value = lambda_lon;
  io::SynthRecordingOptions options;
  options.t0_s = t0_s;
  options.duration_s = duration_s;
  if (ideal_sensor) options.measurement = io::MeasurementOptions::Ideal();
  options.measurement.seed = seed;
  if (!ideal_sensor) options.measurement.gyro_bias_dps = gyro_bias_dps;
  options.files.rotation_matrix_file = false;
  const io::SynthRecording rec = io::Synthesize(block, trial.truth.ToModel(), options);
  for (std::size_t n = 0; n < rec.device.size(); ++n) {
    trial.signal.t_s.push_back(static_cast<double>(n) / rec.device.rate_hz);
    trial.signal.w_B.push_back(rec.device.gyro_dps[n].cast<double>() * (M_PI / 180.0));  // R_BS = identity
  }
  trial.phase4_end_s = rec.phase4_end_s;
  return trial;
}

// A `synth` recording (noise, bias, quantisation, ringing) of a release rolled `roll_rad` off the rocking plane
// (0: on the edge), R_WB = Ry(−α)·Rx(β) at rest on one corner of the release edge.
inline SynthTrial MakeRolledSynthTrial(double alpha_rad, double roll_rad, std::uint64_t seed) {
  SynthTrial trial;
  using fitting::ParameterId;
  trial.truth[ParameterId::kT0].value = 1.0;
  trial.truth[ParameterId::kAlpha].value = alpha_rad;
  trial.truth[ParameterId::kLambda].value = 0.9;
  trial.truth[ParameterId::kLambdaLat].value = 0.5;
  trial.truth[ParameterId::kLambdaLon].value = 0.8;
  trial.truth[ParameterId::kReleaseRoll].value = roll_rad;
  io::SynthRecordingOptions options;
  options.t0_s = 1.0;
  options.duration_s = 2.5;
  options.measurement.seed = seed;
  options.files.rotation_matrix_file = false;
  const io::SynthRecording rec = io::Synthesize(trial.block, trial.truth.ToModel(), options);
  for (std::size_t n = 0; n < rec.device.size(); ++n) {
    trial.signal.t_s.push_back(static_cast<double>(n) / rec.device.rate_hz);
    trial.signal.w_B.push_back(rec.device.gyro_dps[n].cast<double>() * (M_PI / 180.0));
  }
  trial.phase4_end_s = rec.phase4_end_s;
  return trial;
}

}  // namespace rockfit::testing
