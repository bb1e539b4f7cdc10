#include "rockfit/io/synth_recording.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "recording/attitude.hpp"
#include "rockfit/io/units.hpp"
#include "ximu/ximu_register_map.hpp"

namespace rockfit::io {
namespace {

using nlohmann::json;

constexpr double kDegPerRad = 180.0 / kPi;
// Schema of <prefix>_truth.json; bump when keys change meaning.
constexpr int kTruthSchemaVersion = 1;
// Significant digits of the impact log's numbers: 1e-12 relative, far below any measurement resolution, and a
// third smaller than the 17 digits of an exact double (a trial can log thousands of impacts).
constexpr int kImpactDigits = 12;

// round(duration · rate) inertial samples; with a slower orientation stream the recording ends on an orientation
// packet (the largest count ≤ that with (N − 1) a multiple of the decimation), so every gyro sample lies
// within the attitude samples and a reader need not drop or extrapolate any.
std::size_t SampleCount(const SynthRecordingOptions& o) {
  const auto samples = static_cast<std::size_t>(std::llround(o.duration_s * o.rate_hz));
  const auto decimation = static_cast<std::size_t>(std::llround(o.rate_hz / o.files.quaternion_rate_hz));
  if (samples == 0 || decimation <= 1) return samples;
  return (samples - 1) / decimation * decimation + 1;
}

// First inertial sample n with n / rate − t0 ≥ 0.
std::size_t ReleaseSample(double t0_s, double rate_hz) {
  auto n = static_cast<std::size_t>(std::max(0.0, std::ceil(t0_s * rate_hz)));
  while (n > 0 && static_cast<double>(n - 1) / rate_hz - t0_s >= 0.0) --n;
  while (static_cast<double>(n) / rate_hz - t0_s < 0.0) ++n;
  return n;
}

core::SimulationOptions RecordingSimulation(const SynthRecordingOptions& o) {
  core::SimulationOptions sim = o.simulation;
  const std::size_t samples = SampleCount(o);
  const std::size_t release = ReleaseSample(o.t0_s, o.rate_hz);
  sim.sample_times_s = {0.0};
  for (std::size_t n = release; n < samples; ++n) {
    const double tau = static_cast<double>(n) / o.rate_hz - o.t0_s;
    if (tau > 0.0) sim.sample_times_s.push_back(tau);
  }
  // t_max at the end of the recording: the simulator keeps a block that came to rest at rest until then.
  sim.stop = core::StopCondition::kTMax;
  sim.t_max_s = static_cast<double>(samples - 1) / o.rate_hz - o.t0_s;
  sim.sample_attitude = true;
  sim.initial_state.reset();
  return sim;
}

json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json Matrix(const Eigen::Matrix3d& m) {
  return json::array({json::array({m(0, 0), m(0, 1), m(0, 2)}), json::array({m(1, 0), m(1, 1), m(1, 2)}),
                      json::array({m(2, 0), m(2, 1), m(2, 2)})});
}

json TruthJson(const core::Block& block, const core::ModelParameters& params, const SynthRecordingOptions& o,
               const SynthRecording& r, const std::vector<std::string>& files) {
  json j;
  j["format"] = "rockfit synthetic recording truth";
  j["schema_version"] = kTruthSchemaVersion;
  j["synthetic"] = true;
  if (!o.command_line.empty()) j["command"] = o.command_line;
  j["block"] = {{"b1_m", block.b1()}, {"b2_m", block.b2()}, {"h_m", block.h()}, {"mass_kg", block.mass()},
                {"density_kg_m3", block.density()}};
  j["parameters"] = {{"alpha_rad", params.alpha_rad},
                     {"lambda", params.lambda},
                     {"tau_edge_N_m_s", params.tau_edge},
                     {"lambda_lat", params.lambda_lat},
                     {"lambda_lon", params.lambda_lon},
                     {"facet_tau_rule", core::ToString(params.facet_tau_rule)},
                     {"t0_s", o.t0_s}};
  // Only for a rolled release, so that the truth of a release on the edge reads as before.
  if (params.release_roll_rad != 0.0) j["parameters"]["release_roll_rad"] = params.release_roll_rad;
  j["recording"] = {{"duration_s", o.duration_s},
                    {"rate_hz", o.rate_hz},
                    {"samples", r.motion.size()},
                    {"release_sample", r.release_sample},
                    {"quaternion_rate_hz", o.files.quaternion_rate_hz},
                    {"time_base", "the n-th row of _CalInertialAndMag.csv is at t = n / rate_hz (n from 0)"}};
  j["mounting"] = {{"text", o.mounting_text}, {"R_BS", Matrix(r.mounting.R_BS)}, {"p_BS_B_m", Vec(r.mounting.p_BS_B)}};
  const MeasurementOptions& m = o.measurement;
  j["measurement"] = {{"seed", m.seed},
                      {"gyro_noise_dps", m.gyro_noise_dps},
                      {"gyro_bias_dps", Vec(m.gyro_bias_dps)},
                      {"gyro_full_scale_dps", m.gyro_full_scale_dps},
                      {"ringing_gain", m.ringing_gain},
                      {"ringing_frequency_hz", m.ringing_frequency_hz},
                      {"ringing_decay_time_s", m.ringing_decay_time_s},
                      {"drift_slope_dps", Vec(m.drift_slope_dps)},
                      {"drift_walk_deg_per_rt_s", Vec(m.drift_walk_deg_per_rt_s)},
                      {"accel_noise_g", m.accel_noise_g},
                      {"accel_full_scale_g", m.accel_full_scale_g},
                      {"mag_field_W_G", Vec(m.mag_field_W_G)},
                      {"mag_noise_G", m.mag_noise_G},
                      {"quantisation", m.quantisation}};
  j["files"] = {{"written", files},
                {"date_time_rate_hz", o.files.date_time_rate_hz},
                {"battery_rate_hz", o.files.battery_rate_hz},
                {"rotation_matrix_file", o.files.rotation_matrix_file},
                {"crlf_line_endings", o.files.crlf_line_endings},
                {"rtc_start_s", o.files.rtc_start_s}};

  const core::Trajectory& t = r.trajectory;
  const core::SimulationOptions& s = o.simulation;
  j["simulation"] = {{"stop", "t_max (at rest after a rest record)"},
                     {"t_max_s", RecordingSimulation(o).t_max_s},
                     {"end_reason", core::ToString(t.end_reason)},
                     {"t_end_since_release_s", t.t_end_s},
                     {"t_end_s", o.t0_s + t.t_end_s},
                     {"release_edge", "V" + std::to_string(s.release_edge_first) + "V" + std::to_string(s.release_edge_second)},
                     {"gravity_m_s2", s.gravity_m_s2},
                     {"zeno_dt_s", s.zeno_dt_s},
                     {"rest_energy_height_m", s.rest_energy_height_m},
                     {"rel_tol", s.rel_tol},
                     {"abs_tol", s.abs_tol}};
  if (!t.message.empty()) j["simulation"]["message"] = t.message;

  // Summary of the true motion: impact counts and the out-of-plane motion after the first impact (the OPMF
  // of docs/design.md §6 on the true, drift-free Euler angles).
  std::size_t facet = 0;
  std::size_t edge = 0;
  std::size_t zeno = 0;
  for (const auto& impact : t.impacts) {
    facet += impact.kind == core::ImpactKind::kFacet;
    edge += impact.kind == core::ImpactKind::kEdge;
    zeno += impact.kind == core::ImpactKind::kZeno;
  }
  json summary = {{"impacts", t.impacts.size()}, {"facet_impacts", facet}, {"edge_impacts", edge}, {"zeno_switches", zeno}};
  // The simulator marks the end of the motion with a "rest" record; without one the recording ends in motion.
  const bool rests = !t.impacts.empty() && t.impacts.back().kind == core::ImpactKind::kRest;
  summary["rest_s"] = rests ? json(o.t0_s + t.impacts.back().t_s) : json(nullptr);
  if (!t.impacts.empty()) {
    const double first_impact_s = o.t0_s + t.impacts.front().t_s;
    summary["first_impact_s"] = first_impact_s;
    Eigen::Vector3d max_abs_deg = Eigen::Vector3d::Zero();  // (x, y, z)
    for (std::size_t n = 0; n < r.motion.size(); ++n) {
      if (r.motion.t_s(n) < first_impact_s) continue;
      const Eigen::Vector3d zyx = EulerZyxFromQuaternion(r.motion.q_WB[n]);
      max_abs_deg = max_abs_deg.cwiseMax(kDegPerRad * Eigen::Vector3d(zyx[2], zyx[1], zyx[0]).cwiseAbs());
    }
    summary["max_abs_euler_after_first_impact_deg"] = Vec(max_abs_deg);
    if (max_abs_deg.y() > 0.0) summary["opmf"] = max_abs_deg.x() / max_abs_deg.y();
  }
  summary["phase4_end_s"] = r.phase4_end_s ? json(*r.phase4_end_s) : json(nullptr);
  j["summary"] = summary;

  return j;
}

// The truth file's text: the summary as indented JSON, then the impact log as one compact row per impact with
// kImpactDigits significant digits (a trial can have thousands of small impacts; one object per impact with
// exact doubles would make the file several times larger).
std::string TruthText(const json& truth, const core::Trajectory& trajectory, double t0_s) {
  std::string text = truth.dump(2);
  text.erase(text.find_last_of('}'));
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  text += ",\n  \"impact_columns\": " +
          json::array({"t_s", "kind", "contact_before", "contact_after", "w_minus_B_x_rad_s", "w_minus_B_y_rad_s",
                       "w_minus_B_z_rad_s", "w_plus_B_x_rad_s", "w_plus_B_y_rad_s", "w_plus_B_z_rad_s", "tau_N_m_s",
                       "delta_energy_J", "status"})
              .dump() +
          ",\n  \"impacts\": [";
  const char* separator = "\n    ";
  const auto number = [](double x) { return std::isfinite(x) ? fmt::format("{:.{}g}", x, kImpactDigits) : std::string("null"); };
  for (const auto& impact : trajectory.impacts) {
    const Eigen::Vector3d& a = impact.w_minus_B;
    const Eigen::Vector3d& b = impact.w_plus_B;
    text += separator;
    text += fmt::format("[{},\"{}\",\"{}\",\"{}\",{},{},{},{},{},{},{},{},\"{}\"]", number(t0_s + impact.t_s),
                        core::ToString(impact.kind), impact.contact_before.ToString(), impact.contact_after.ToString(),
                        number(a.x()), number(a.y()), number(a.z()), number(b.x()), number(b.y()), number(b.z()),
                        number(impact.tau), number(impact.delta_energy_J), core::ToString(impact.status));
    separator = ",\n    ";
  }
  text += trajectory.impacts.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return text;
}

}  // namespace

void SynthRecordingOptions::Validate() const {
  XimuRateRegisterValue(rate_hz, "the sample rate (--rate)");
  if (rate_hz == 0.0) throw InvalidArgument("the sample rate (--rate) must not be 0");
  if (!(std::isfinite(duration_s) && duration_s > 0.0)) {
    throw InvalidArgument("the recording duration must be a positive number of seconds, got " + std::to_string(duration_s));
  }
  files.Validate(rate_hz);
  const std::size_t samples = SampleCount(*this);
  if (samples < 2) throw InvalidArgument("the recording must hold at least two samples; increase the duration");
  const double last_s = static_cast<double>(samples - 1) / rate_hz;
  if (!(std::isfinite(t0_s) && t0_s >= 0.0 && t0_s < last_s)) {
    throw InvalidArgument("the release time t0 must lie in [0, " + std::to_string(last_s) + ") s of the recording, got " +
                          std::to_string(t0_s));
  }
  SensorMounting mounting{R_BS, sensor_position_B.value_or(Eigen::Vector3d::Zero())};
  mounting.Validate();
  measurement.Validate();
  RecordingSimulation(*this).Validate();
}

SynthRecording Synthesize(const core::Block& block, const core::ModelParameters& params, const SynthRecordingOptions& o) {
  o.Validate();
  const std::size_t samples = SampleCount(o);
  SynthRecording r;
  r.release_sample = ReleaseSample(o.t0_s, o.rate_hz);
  const core::SimulationOptions sim = RecordingSimulation(o);
  r.trajectory = core::Simulate(block, params, sim);
  if (r.trajectory.end_reason == core::EndReason::kFailed) {
    throw NumericalFailure("the simulation failed at " + std::to_string(r.trajectory.t_end_s) +
                           " s after the release: " + r.trajectory.message);
  }
  if (r.trajectory.end_reason == core::EndReason::kOverturned) {
    throw NumericalFailure("the block overturned " + std::to_string(r.trajectory.t_end_s) +
                           " s after the release; a rocking trial needs a smaller tilt α or other impact parameters");
  }
  r.motion = BlockMotionFromTrajectory(block, r.trajectory, o.t0_s, o.rate_hz, samples, r.release_sample, sim.gravity_m_s2);
  r.mounting.R_BS = o.R_BS;
  r.mounting.p_BS_B = o.sensor_position_B.value_or(Eigen::Vector3d(0.0, 0.0, 2.0 * block.h()));
  r.device = MeasureMotion(r.motion, r.mounting, o.measurement);

  // Phase 4 ends with the first impact on the release side after the first facet impact (docs/design.md §4).
  core::SimulationOptions phase4 = sim;
  phase4.stop = core::StopCondition::kPhase4;
  phase4.sample_times_s = {0.0};
  phase4.sample_attitude = false;
  const core::Trajectory phase4_run = core::Simulate(block, params, phase4);
  if (phase4_run.end_reason == core::EndReason::kPhase4) r.phase4_end_s = o.t0_s + phase4_run.t_end_s;
  return r;
}

std::vector<std::string> WriteSynthRecording(const std::string& prefix, const core::Block& block,
                                             const core::ModelParameters& params, const SynthRecordingOptions& options,
                                             const SynthRecording& recording) {
  std::vector<std::string> files = WriteXimuGuiCsv(prefix, recording.device, options.files);
  const std::string truth_path = prefix + "_truth.json";
  std::vector<std::string> names;
  for (const auto& f : files) names.push_back(std::filesystem::path(f).filename().string());
  const std::string truth = TruthText(TruthJson(block, params, options, recording, names), recording.trajectory, options.t0_s);
  WriteFileAtomically(truth_path, [&truth](std::ostream& out) { out << truth; });
  files.push_back(truth_path);
  return files;
}

}  // namespace rockfit::io
