// `synth` for both front ends: the arguments of a synthetic recording (model, recording, measurement) as plain
// values, what the library is given for them, and the JSON document of the result (`rockfit synth --json`, the
// dictionary of `rockfit.synth`).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "rockfit/core/simulator.hpp"
#include "rockfit/io/synth_recording.hpp"

namespace rockfit::app {

struct SynthArgs {
  // Model.
  double alpha_rad = 0.2;
  double release_roll_rad = 0.0;  // core::ModelParameters::release_roll_rad (0: released on the edge)
  double lambda = 1.0;
  double lambda_lat = 0.0;
  double lambda_lon = 1.0;
  double tau_edge = 0.0;
  std::string facet_tau = "no-spin";  // core::ToString(FacetTauRule)
  std::optional<double> rest_energy_height_m;
  // Recording.
  double t0_s = 2.0;
  double duration_s = 10.0;
  double rate_hz = 256.0;
  std::optional<double> quaternion_rate_hz;  // default: rate_hz
  std::string mounting = "x,y,z";
  std::optional<Eigen::Vector3d> sensor_position_B_m;
  std::int64_t rtc_start_s = 0;
  bool rotation_matrix_file = true;
  bool crlf = false;
  // Measurement: an ideal sensor when `noise` is false (then no other measurement value may be given).
  std::uint64_t seed = 1;
  bool noise = true;
  std::optional<double> gyro_noise_dps;
  std::optional<Eigen::Vector3d> gyro_bias_dps;
  bool quantisation = true;
  std::optional<double> ringing_gain;
  std::optional<double> ringing_frequency_hz;
  std::optional<double> ringing_decay_time_s;
  bool ringing = true;
  std::optional<Eigen::Vector3d> drift_slope_dps;
  std::optional<Eigen::Vector3d> drift_walk_deg_per_rt_s;
  bool drift = true;
  std::optional<double> accel_noise_g;
};

// Throws InvalidArgument for an unknown facet-τ rule.
core::ModelParameters MakeSynthParameters(const SynthArgs& args);
// Throws InvalidArgument when noise is off and a measurement value is given, or for a bad mounting (BadInput).
io::SynthRecordingOptions MakeSynthOptions(const SynthArgs& args);

// The time of the "rest" record in recording time [s], or none when the motion lasts beyond the recording.
std::optional<double> SynthRestTime(const io::SynthRecording& recording, const io::SynthRecordingOptions& options);

// prefix, files, samples, rate_hz, duration_s, t0_s, seed, impacts, first_impact_s, phase4_end_s, rest_s.
nlohmann::json SynthResultJson(const std::string& prefix, const std::vector<std::string>& files,
                               const io::SynthRecording& recording, const io::SynthRecordingOptions& options);

}  // namespace rockfit::app
