// `rockfit synth`: a synthetic x-IMU recording of one rocking trial from known parameters, with the
// measurement model of io/README.md ("Synthetic recordings"): noise, bias, quantisation, ringing, drift.
#include <algorithm>
#include <cstdint>
#include <iostream>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "rockfit/app/activity.hpp"
#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/run_limits.hpp"
#include "rockfit/app/synth_setup.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/mounting.hpp"
#include "rockfit/io/synth_recording.hpp"

namespace rockfit::tools {
namespace {

// The values the options fill: SynthArgs directly where the option is the value; the vectors as text (parsed
// naming their option) and the negative flags as given.
struct SynthCommand {
  BlockArgs block;
  SynthArgs args;
  std::string sensor_position;
  std::string gyro_bias_dps;
  std::string drift_slope_dps;
  std::string drift_walk;
  bool no_rotation_matrix = false;
  bool no_quantisation = false;
  bool no_ringing = false;
  bool no_drift = false;
  bool no_noise = false;
  std::string output;
  bool json = false;
};

std::optional<Eigen::Vector3d> OptionalVector(const std::string& text, const std::string& option) {
  if (text.empty()) return std::nullopt;
  return ParseVector3(text, option);
}

SynthArgs CompleteArgs(const SynthCommand& cmd) {
  SynthArgs a = cmd.args;
  a.sensor_position_B_m = OptionalVector(cmd.sensor_position, "--sensor-position-m");
  a.gyro_bias_dps = OptionalVector(cmd.gyro_bias_dps, "--gyro-bias-dps");
  a.drift_slope_dps = OptionalVector(cmd.drift_slope_dps, "--drift-slope-dps");
  a.drift_walk_deg_per_rt_s = OptionalVector(cmd.drift_walk, "--drift-walk-deg-per-rt-s");
  a.rotation_matrix_file = !cmd.no_rotation_matrix;
  a.quantisation = !cmd.no_quantisation;
  a.ringing = !cmd.no_ringing;
  a.drift = !cmd.no_drift;
  a.noise = !cmd.no_noise;
  return a;
}

std::string Vector3Text(const Eigen::Vector3d& v) { return fmt::format("{},{},{}", v.x(), v.y(), v.z()); }

// A path as one shell word: in single quotes when it holds anything but letters, digits and ./_-+,=.
std::string ShellWord(const std::string& text) {
  const bool plain = !text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789./_-+,=") == std::string::npos;
  if (plain) return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// The command that reproduces this recording, with every effective value spelled out (for the truth file).
std::string ReproducingCommand(const SynthCommand& cmd, const core::ModelParameters& p, const io::SynthRecordingOptions& o) {
  std::string c = "rockfit synth";
  if (!cmd.block.manifest_path.empty()) {
    c += fmt::format(" --manifest {} --block {}", ShellWord(cmd.block.manifest_path), ShellWord(cmd.block.block_id));
  }
  if (cmd.block.b1_m) c += fmt::format(" --b1 {} --b2 {} --h {}", *cmd.block.b1_m, *cmd.block.b2_m, *cmd.block.h_m);
  if (cmd.block.density_kg_m3) c += fmt::format(" --density {}", *cmd.block.density_kg_m3);
  if (cmd.block.mass_kg) c += fmt::format(" --mass {}", *cmd.block.mass_kg);
  c += fmt::format(" --alpha {} --lambda {} --lambda-lat {} --lambda-lon {} --tau-edge {} --facet-tau {}", p.alpha_rad,
                   p.lambda, p.lambda_lat, p.lambda_lon, p.tau_edge, cmd.args.facet_tau);
  if (p.release_roll_rad != 0.0) c += fmt::format(" --release-roll {}", p.release_roll_rad);
  if (cmd.args.rest_energy_height_m) c += fmt::format(" --rest-energy-height-m {}", *cmd.args.rest_energy_height_m);
  c += fmt::format(" --t0 {} --duration {} --rate {} --quaternion-rate {} --mounting={}", o.t0_s, o.duration_s, o.rate_hz,
                   o.files.quaternion_rate_hz, o.mounting_text);
  if (o.sensor_position_B) c += " --sensor-position-m=" + Vector3Text(*o.sensor_position_B);
  c += fmt::format(" --rtc-start-s {}", o.files.rtc_start_s);
  if (!o.files.rotation_matrix_file) c += " --no-rotation-matrix";
  if (o.files.crlf_line_endings) c += " --crlf";
  const io::MeasurementOptions& m = o.measurement;
  c += fmt::format(" --seed {}", m.seed);
  if (cmd.no_noise) {
    c += " --no-noise";
  } else {
    c += fmt::format(" --gyro-noise-dps {} --gyro-bias-dps={}", m.gyro_noise_dps, Vector3Text(m.gyro_bias_dps));
    if (!m.quantisation) c += " --no-quantisation";
    c += fmt::format(" --ringing-gain {} --ringing-frequency-hz {} --ringing-decay-time-s {}", m.ringing_gain,
                     m.ringing_frequency_hz, m.ringing_decay_time_s);
    c += " --drift-slope-dps=" + Vector3Text(m.drift_slope_dps) + " --drift-walk-deg-per-rt-s=" +
         Vector3Text(m.drift_walk_deg_per_rt_s);
    c += fmt::format(" --accel-noise-g {}", m.accel_noise_g);
  }
  return c + " -o " + ShellWord(cmd.output);
}

int RunSynth(const SynthCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  const SynthArgs args = CompleteArgs(cmd);
  const core::ModelParameters params = MakeSynthParameters(args);
  io::SynthRecordingOptions o = MakeSynthOptions(args);
  o.command_line = ReproducingCommand(cmd, params, o);
  RequireTrajectorySamplesWithinLimit(o.duration_s, std::max(o.rate_hz, o.files.quaternion_rate_hz),
                                      "--duration and --rate");
  const Activity activity("making the synthetic recording and its files");
  const io::SynthRecording recording = io::Synthesize(block, params, o);
  const std::vector<std::string> files = io::WriteSynthRecording(cmd.output, block, params, o, recording);

  if (cmd.json) {
    PrintJson(SynthResultJson(cmd.output, files, recording, o));
    return kExitOk;
  }
  const core::Trajectory& t = recording.trajectory;
  const std::optional<double> rest_s = SynthRestTime(recording, o);
  std::cout << fmt::format("synthetic x-IMU recording {}: {} samples at {:g} Hz ({:g} s), release at t0 = {:g} s\n",
                           cmd.output, recording.motion.size(), o.rate_hz, recording.motion.size() / o.rate_hz, o.t0_s)
            << fmt::format("motion: {} impacts", t.impacts.size());
  if (!t.impacts.empty()) std::cout << fmt::format(", the first at {:.4f} s", o.t0_s + t.impacts.front().t_s);
  if (recording.phase4_end_s) std::cout << fmt::format("; phase 4 ends at {:.4f} s", *recording.phase4_end_s);
  std::cout << (rest_s ? fmt::format("; at rest from {:.4f} s", *rest_s) : std::string("; still moving when the recording ends"));
  std::cout << "\nfiles:\n";
  for (const auto& f : files) std::cout << "  " << f << "\n";
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<SynthCommand>();
  CLI::App* app = root.add_subcommand(
      "synth",
      "Make a synthetic x-IMU recording (GUI CSV set + <prefix>_truth.json) of one rocking trial from known parameters:\n"
      "the block rests at tilt α until t0, rocks as the simulator says until it comes to rest, and rests after;\n"
      "the measurement model adds gyro noise, bias, quantisation, ringing after impacts and attitude drift.\n"
      "Deterministic for a given --seed.");
  AddBlockOptions(*app, cmd->block);
  app->add_option("--alpha", cmd->args.alpha_rad, "Release tilt α [rad]")->group("Model")->capture_default_str();
  app->add_option("--release-roll", cmd->args.release_roll_rad,
                  "Release roll β [rad]: the block released on one corner of its release edge, rolled β about the "
                  "edge's inward axis (0: on the edge)")
      ->group("Model")->capture_default_str();
  app->add_option("--lambda", cmd->args.lambda, "λ of edge impacts (19)")->group("Model")->capture_default_str();
  app->add_option("--lambda-lat", cmd->args.lambda_lat, "λ_lat of facet impacts (21)")->group("Model")->capture_default_str();
  app->add_option("--lambda-lon", cmd->args.lambda_lon, "λ_lon of facet impacts (21)")->group("Model")->capture_default_str();
  app->add_option("--tau-edge", cmd->args.tau_edge, "τ of edge impacts [N·m·s]")->group("Model")->capture_default_str();
  app->add_option("--facet-tau", cmd->args.facet_tau, "τ of facet impacts: no-spin (from (24)) or fixed (τ = 0, Sect. 5)")
      ->group("Model")->capture_default_str();
  app->add_option("--rest-energy-height-m", cmd->args.rest_energy_height_m,
                  "The motion ends at rest when the kinetic energy after a facet impact is below m·g·this [m] (simulator default 1e-9)")
      ->group("Model");

  app->add_option("--t0", cmd->args.t0_s, "Release time in the recording [s]")->group("Recording")->capture_default_str();
  app->add_option("--duration", cmd->args.duration_s, "Recording length [s]")->group("Recording")->capture_default_str();
  app->add_option("--rate", cmd->args.rate_hz, "Inertial sample rate [Hz], an x-IMU rate 2^(v−1): 1 … 512")
      ->group("Recording")->capture_default_str();
  app->add_option("--quaternion-rate", cmd->args.quaternion_rate_hz, "Quaternion/Euler rate [Hz] (default: --rate)")->group("Recording");
  app->add_option("--mounting", cmd->args.mounting,
                  "Sensor axes on the block: a permutation with signs 'x,-y,-z' (entry i = sensor axis along block axis i) "
                  "or a unit quaternion 'w,x,y,z' (q_BS), as for the readers")
      ->group("Recording")->capture_default_str();
  app->add_option("--sensor-position-m", cmd->sensor_position, "Accelerometer position in the block frame X,Y,Z [m] (default: top-face centre)")
      ->group("Recording");
  app->add_option("--rtc-start-s", cmd->args.rtc_start_s, "Device clock at start-up, seconds after 2000-01-01 00:00:00")
      ->group("Recording")->capture_default_str();
  app->add_flag("--no-rotation-matrix", cmd->no_rotation_matrix, "Do not write <prefix>_RotationMatrix.csv (the largest file)")
      ->group("Recording");
  app->add_flag("--crlf", cmd->args.crlf, "CRLF line endings, as the x-IMU GUI itself writes (default LF)")->group("Recording");

  app->add_option("--seed", cmd->args.seed, "Seed of every random part")->group("Measurement")->capture_default_str();
  auto* gyro_noise = app->add_option("--gyro-noise-dps", cmd->args.gyro_noise_dps, "Gyro white noise σ [deg/s] (default 0.1)")->group("Measurement");
  auto* gyro_bias = app->add_option("--gyro-bias-dps", cmd->gyro_bias_dps, "Gyro bias X,Y,Z [deg/s] (default 0,0,0)")->group("Measurement");
  auto* no_quant = app->add_flag("--no-quantisation", cmd->no_quantisation, "No fixed-point quantisation (gyro 1/16 deg/s, …)")->group("Measurement");
  auto* ringing_gain = app->add_option("--ringing-gain", cmd->args.ringing_gain, "Ringing amplitude per unit jump |Δω| (default 0.25)")->group("Measurement");
  auto* ringing_f = app->add_option("--ringing-frequency-hz", cmd->args.ringing_frequency_hz, "Ringing frequency [Hz] (default 38)")->group("Measurement");
  auto* ringing_t = app->add_option("--ringing-decay-time-s", cmd->args.ringing_decay_time_s, "Ringing e-folding time [s] (default 0.03)")->group("Measurement");
  auto* no_ringing = app->add_flag("--no-ringing", cmd->no_ringing, "No ringing after impacts")->group("Measurement");
  auto* drift_slope = app->add_option("--drift-slope-dps", cmd->drift_slope_dps, "Linear drift of roll,pitch,yaw [deg/s] (default 0.02,-0.05,0.4)")->group("Measurement");
  auto* drift_walk = app->add_option("--drift-walk-deg-per-rt-s", cmd->drift_walk, "Random-walk drift of roll,pitch,yaw [deg/√s] (default 0.01,0.01,0.03)")->group("Measurement");
  auto* no_drift = app->add_flag("--no-drift", cmd->no_drift, "No attitude drift")->group("Measurement");
  auto* accel_noise = app->add_option("--accel-noise-g", cmd->args.accel_noise_g, "Accelerometer white noise σ [g] (default 0.015)")->group("Measurement");
  auto* no_noise = app->add_flag("--no-noise", cmd->no_noise, "An ideal sensor: no noise, bias, quantisation, ringing or drift")->group("Measurement");
  for (auto* option : {gyro_noise, gyro_bias, no_quant, ringing_gain, ringing_f, ringing_t, no_ringing, drift_slope, drift_walk, no_drift, accel_noise}) {
    no_noise->excludes(option);
  }

  app->add_option("-o,--output", cmd->output, "Output prefix: writes PREFIX_CalInertialAndMag.csv, …, PREFIX_truth.json")->required();
  app->add_flag("--json", cmd->json,
                "Print one JSON object: prefix, files, samples, rate_hz, duration_s, t0_s, seed, impacts, first_impact_s, "
                "phase4_end_s, rest_s (times in recording time [s]; null when the event does not happen)");
  app->footer(LimitsHelp());
  app->callback([cmd] { SetExitCode(RunSynth(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
