#include "rockfit/app/synth_setup.hpp"

#include "rockfit/app/json_values.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/mounting.hpp"

namespace rockfit::app {

core::ModelParameters MakeSynthParameters(const SynthArgs& args) {
  core::ModelParameters params;
  params.alpha_rad = args.alpha_rad;
  params.release_roll_rad = args.release_roll_rad;
  params.lambda = args.lambda;
  params.lambda_lat = args.lambda_lat;
  params.lambda_lon = args.lambda_lon;
  params.tau_edge = args.tau_edge;
  params.facet_tau_rule = ParseFacetTauRule(args.facet_tau);
  return params;
}

namespace {

bool MeasurementGiven(const SynthArgs& a) {
  return a.gyro_noise_dps || a.gyro_bias_dps || !a.quantisation || a.ringing_gain || a.ringing_frequency_hz ||
         a.ringing_decay_time_s || !a.ringing || a.drift_slope_dps || a.drift_walk_deg_per_rt_s || !a.drift ||
         a.accel_noise_g;
}

io::MeasurementOptions MakeMeasurement(const SynthArgs& a) {
  if (!a.noise && MeasurementGiven(a)) {
    throw InvalidArgument("an ideal sensor (--no-noise, noise=False) takes no other measurement option");
  }
  io::MeasurementOptions m = a.noise ? io::MeasurementOptions{} : io::MeasurementOptions::Ideal();
  m.seed = a.seed;
  if (a.gyro_noise_dps) m.gyro_noise_dps = *a.gyro_noise_dps;
  if (a.gyro_bias_dps) m.gyro_bias_dps = *a.gyro_bias_dps;
  if (!a.quantisation) m.quantisation = false;
  if (a.ringing_gain) m.ringing_gain = *a.ringing_gain;
  if (a.ringing_frequency_hz) m.ringing_frequency_hz = *a.ringing_frequency_hz;
  if (a.ringing_decay_time_s) m.ringing_decay_time_s = *a.ringing_decay_time_s;
  if (!a.ringing) m.ringing_gain = 0.0;
  if (a.drift_slope_dps) m.drift_slope_dps = *a.drift_slope_dps;
  if (a.drift_walk_deg_per_rt_s) m.drift_walk_deg_per_rt_s = *a.drift_walk_deg_per_rt_s;
  if (!a.drift) {
    m.drift_slope_dps.setZero();
    m.drift_walk_deg_per_rt_s.setZero();
  }
  if (a.accel_noise_g) m.accel_noise_g = *a.accel_noise_g;
  return m;
}

}  // namespace

io::SynthRecordingOptions MakeSynthOptions(const SynthArgs& args) {
  io::SynthRecordingOptions o;
  o.t0_s = args.t0_s;
  if (args.rest_energy_height_m) o.simulation.rest_energy_height_m = *args.rest_energy_height_m;
  o.duration_s = args.duration_s;
  o.rate_hz = args.rate_hz;
  const io::Mounting mounting = io::Mounting::Parse(args.mounting);
  o.R_BS = mounting.R_BS();
  o.mounting_text = mounting.text();
  o.sensor_position_B = args.sensor_position_B_m;
  o.files.quaternion_rate_hz = args.quaternion_rate_hz.value_or(args.rate_hz);
  o.files.rotation_matrix_file = args.rotation_matrix_file;
  o.files.crlf_line_endings = args.crlf;
  o.files.rtc_start_s = args.rtc_start_s;
  o.files.seed = args.seed;
  o.measurement = MakeMeasurement(args);
  return o;
}

std::optional<double> SynthRestTime(const io::SynthRecording& recording, const io::SynthRecordingOptions& options) {
  // The simulator logs a "rest" record when the motion has ended; without one it lasts beyond the recording.
  const core::Trajectory& t = recording.trajectory;
  if (!t.impacts.empty() && t.impacts.back().kind == core::ImpactKind::kRest) return options.t0_s + t.impacts.back().t_s;
  return std::nullopt;
}

nlohmann::json SynthResultJson(const std::string& prefix, const std::vector<std::string>& files,
                               const io::SynthRecording& recording, const io::SynthRecordingOptions& options) {
  const core::Trajectory& t = recording.trajectory;
  nlohmann::json out;
  out["prefix"] = prefix;
  out["files"] = files;
  out["samples"] = recording.motion.size();
  out["rate_hz"] = options.rate_hz;
  out["duration_s"] = static_cast<double>(recording.motion.size()) / options.rate_hz;
  out["t0_s"] = options.t0_s;
  out["seed"] = options.measurement.seed;
  out["impacts"] = t.impacts.size();
  out["first_impact_s"] = t.impacts.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.t0_s + t.impacts.front().t_s);
  out["phase4_end_s"] = OrNull(recording.phase4_end_s);
  out["rest_s"] = OrNull(SynthRestTime(recording, options));
  return out;
}

}  // namespace rockfit::app
