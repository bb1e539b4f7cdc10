// rockfit.synth: a synthetic x-IMU recording of one trial with known truth (io/synth_recording.hpp), as
// `rockfit synth`: the same inputs give the same files.
#include <fstream>
#include <optional>

#include <fmt/format.h>

#include "bindings.hpp"
#include "path_argument.hpp"
#include "rockfit/app/synth_setup.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/mounting.hpp"
#include "rockfit/io/synth_recording.hpp"

namespace rockfit::python {
namespace {

struct SynthKeywords {
  double alpha, lambda, lambda_lat, lambda_lon, tau_edge;
  std::string facet_tau;
  std::optional<double> rest_energy_height;
  double t0, duration, rate;
  std::optional<double> quaternion_rate;
  std::string mounting;
  py::object sensor_position;
  std::int64_t rtc_start_s;
  bool rotation_matrix, crlf;
  std::uint64_t seed;
  bool noise;
  std::optional<double> gyro_noise_dps;
  py::object gyro_bias_dps;
  bool quantisation;
  std::optional<double> ringing_gain, ringing_frequency_hz, ringing_decay_time_s;
  bool ringing;
  py::object drift_slope_dps, drift_walk_deg_per_rt_s;
  bool drift;
  std::optional<double> accel_noise_g;
  double release_roll;  // [rad], 0: released on the edge
};

std::optional<Eigen::Vector3d> OptionalVector(const py::object& value, const char* name) {
  if (value.is_none()) return std::nullopt;
  return ToVector3(value, name);
}

// The arguments as `rockfit synth` fills them from its flags.
app::SynthArgs MakeArgs(const SynthKeywords& k) {
  app::SynthArgs a;
  a.alpha_rad = k.alpha;
  a.release_roll_rad = k.release_roll;
  a.lambda = k.lambda;
  a.lambda_lat = k.lambda_lat;
  a.lambda_lon = k.lambda_lon;
  a.tau_edge = k.tau_edge;
  a.facet_tau = k.facet_tau;
  a.rest_energy_height_m = k.rest_energy_height;
  a.t0_s = k.t0;
  a.duration_s = k.duration;
  a.rate_hz = k.rate;
  a.quaternion_rate_hz = k.quaternion_rate;
  a.mounting = k.mounting;
  a.sensor_position_B_m = OptionalVector(k.sensor_position, "sensor_position");
  a.rtc_start_s = k.rtc_start_s;
  a.rotation_matrix_file = k.rotation_matrix;
  a.crlf = k.crlf;
  a.seed = k.seed;
  a.noise = k.noise;
  a.gyro_noise_dps = k.gyro_noise_dps;
  a.gyro_bias_dps = OptionalVector(k.gyro_bias_dps, "gyro_bias_dps");
  a.quantisation = k.quantisation;
  a.ringing_gain = k.ringing_gain;
  a.ringing_frequency_hz = k.ringing_frequency_hz;
  a.ringing_decay_time_s = k.ringing_decay_time_s;
  a.ringing = k.ringing;
  a.drift_slope_dps = OptionalVector(k.drift_slope_dps, "drift_slope_dps");
  a.drift_walk_deg_per_rt_s = OptionalVector(k.drift_walk_deg_per_rt_s, "drift_walk_deg_per_rt_s");
  a.drift = k.drift;
  a.accel_noise_g = k.accel_noise_g;
  return a;
}

py::object ReadTruth(const std::string& path) {
  std::ifstream in(path);
  if (!in) return py::none();
  return FromJson(nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false));
}

py::object Synth(const std::string& prefix, const core::Block& block, const SynthKeywords& k) {
  const app::SynthArgs args = MakeArgs(k);
  const core::ModelParameters params = app::MakeSynthParameters(args);
  io::SynthRecordingOptions o = app::MakeSynthOptions(args);
  o.command_line = fmt::format(
      "python3: rockfit.synth('{}', Block(b1={}, b2={}, h={}, mass={}), alpha={}, lambda_={}, lambda_lat={}, "
      "lambda_lon={}, tau_edge={}, facet_tau='{}', t0={}, duration={}, rate={}, mounting='{}', seed={}, noise={})",
      prefix, block.b1(), block.b2(), block.h(), block.mass(), k.alpha, k.lambda, k.lambda_lat, k.lambda_lon,
      k.tau_edge, k.facet_tau, k.t0, k.duration, k.rate, o.mounting_text, k.seed, k.noise ? "True" : "False");
  if (k.release_roll != 0.0) o.command_line.insert(o.command_line.size() - 1, fmt::format(", release_roll={}", k.release_roll));

  io::SynthRecording recording;
  std::vector<std::string> files;
  {
    py::gil_scoped_release release;
    recording = io::Synthesize(block, params, o);
    files = io::WriteSynthRecording(prefix, block, params, o, recording);
  }
  py::dict d = FromJson(app::SynthResultJson(prefix, files, recording, o));  // the keys of `rockfit synth --json`
  // The truth: the parameters, and the true motion at every inertial sample.
  d["parameters"] = py::dict(py::arg("t0") = o.t0_s, py::arg("alpha") = k.alpha, py::arg("lambda") = k.lambda,
                             py::arg("lambda_lat") = k.lambda_lat, py::arg("lambda_lon") = k.lambda_lon,
                             py::arg("tau_edge") = k.tau_edge, py::arg("facet_tau") = k.facet_tau);
  if (k.release_roll != 0.0) d["parameters"]["release_roll"] = k.release_roll;  // as in the truth file
  std::vector<double> times(recording.motion.size());
  for (std::size_t n = 0; n < times.size(); ++n) times[n] = recording.motion.t_s(n);
  d["t"] = OwnedArray(std::move(times));
  d["w_B_true"] = OwnedArray(std::move(recording.motion.w_B));
  d["truth"] = ReadTruth(prefix + "_truth.json");
  return MakeRecord("Synth", d);
}

}  // namespace

void RegisterSynth(py::module_& m) {
  const io::SynthRecordingOptions o;
  const core::ModelParameters p;
  m.def(
      "synth",
      [](const PathArgument& prefix, const core::Block& block, double alpha, double lambda, double lambda_lat,
         double lambda_lon, double tau_edge, const std::string& facet_tau, std::optional<double> rest_energy_height,
         double t0, double duration, double rate, std::optional<double> quaternion_rate, const std::string& mounting,
         py::object sensor_position, std::int64_t rtc_start_s, bool rotation_matrix, bool crlf, std::uint64_t seed,
         bool noise, std::optional<double> gyro_noise_dps, py::object gyro_bias_dps, bool quantisation,
         std::optional<double> ringing_gain, std::optional<double> ringing_frequency_hz,
         std::optional<double> ringing_decay_time_s, bool ringing, py::object drift_slope_dps,
         py::object drift_walk_deg_per_rt_s, bool drift, std::optional<double> accel_noise_g, double release_roll) {
        const SynthKeywords k{alpha, lambda, lambda_lat, lambda_lon, tau_edge, facet_tau, rest_energy_height, t0,
                              duration, rate, quaternion_rate, mounting, std::move(sensor_position), rtc_start_s,
                              rotation_matrix, crlf, seed, noise, gyro_noise_dps, std::move(gyro_bias_dps),
                              quantisation, ringing_gain, ringing_frequency_hz, ringing_decay_time_s, ringing,
                              std::move(drift_slope_dps), std::move(drift_walk_deg_per_rt_s), drift, accel_noise_g,
                              release_roll};
        return Synth(prefix.path, block, k);
      },
      py::arg("prefix"), py::arg("block"), py::kw_only(), py::arg("alpha") = p.alpha_rad, py::arg("lambda_") = p.lambda,
      py::arg("lambda_lat") = p.lambda_lat, py::arg("lambda_lon") = p.lambda_lon, py::arg("tau_edge") = p.tau_edge,
      py::arg("facet_tau") = "no-spin", py::arg("rest_energy_height") = py::none(), py::arg("t0") = o.t0_s,
      py::arg("duration") = o.duration_s, py::arg("rate") = o.rate_hz, py::arg("quaternion_rate") = py::none(),
      py::arg("mounting") = "x,y,z", py::arg("sensor_position") = py::none(), py::arg("rtc_start_s") = 0,
      py::arg("rotation_matrix") = true, py::arg("crlf") = false, py::arg("seed") = 1, py::arg("noise") = true,
      py::arg("gyro_noise_dps") = py::none(), py::arg("gyro_bias_dps") = py::none(), py::arg("quantisation") = true,
      py::arg("ringing_gain") = py::none(), py::arg("ringing_frequency_hz") = py::none(),
      py::arg("ringing_decay_time_s") = py::none(), py::arg("ringing") = true, py::arg("drift_slope_dps") = py::none(),
      py::arg("drift_walk_deg_per_rt_s") = py::none(), py::arg("drift") = true, py::arg("accel_noise_g") = py::none(),
      py::arg("release_roll") = p.release_roll_rad,
      "Writes a synthetic x-IMU recording (GUI CSV set + <prefix>_truth.json) of one rocking trial, as `rockfit\n"
      "synth`: the block rests at tilt alpha until t0, rocks as the simulator says, and rests after; the\n"
      "measurement model adds gyro noise, bias, quantisation, ringing after impacts and attitude drift. The same\n"
      "arguments (seed) give the same files as the program.\n\n"
      "Model: alpha [rad], lambda_ (19), lambda_lat, lambda_lon (21), tau_edge [N·m·s], facet_tau 'no-spin' or\n"
      "'fixed', rest_energy_height [m], release_roll [rad] (0: on the edge; otherwise on one corner of it, as\n"
      "`rockfit synth --release-roll`). Recording: t0 [s], duration [s], rate [Hz] (an x-IMU rate 2^(v−1)),\n"
      "quaternion_rate [Hz], mounting 'x,-y,-z' or 'w,x,y,z', sensor_position (3,) [m], rtc_start_s,\n"
      "rotation_matrix, crlf. Measurement: seed; noise=False for an ideal sensor; gyro_noise_dps (0.1),\n"
      "gyro_bias_dps (3,), quantisation, ringing_gain (0.25), ringing_frequency_hz (38), ringing_decay_time_s\n"
      "(0.03), ringing, drift_slope_dps (3,), drift_walk_deg_per_rt_s (3,), drift, accel_noise_g (0.015).\n\n"
      "Returns the truth, a Record 'Synth' with the keys of `rockfit synth --json` (prefix, files, samples, rate_hz,\n"
      "duration_s, t0_s, seed, impacts, first_impact_s, phase4_end_s, rest_s [s, recording time; None when the\n"
      "event does not happen]) and parameters, t [s] and w_B_true [rad/s] (the true motion at every sample), truth\n"
      "(the parsed truth file). Raises rockfit.NumericalError when the block overturns.");
}

}  // namespace rockfit::python
