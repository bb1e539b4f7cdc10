// `rockfit simulate`: the hybrid simulator of docs/design.md §4 — trajectory, impact log and diagnostics as JSON,
// CSV or HDF5.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "rockfit/app/activity.hpp"
#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/run_limits.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "rockfit/io/trajectory_hdf5.hpp"

namespace rockfit::tools {
namespace {

struct SimulateCommand {
  BlockArgs block;
  core::ModelParameters params;
  core::SimulationOptions options;
  std::string facet_tau = "no-spin";
  std::string release_edge = "1,2";
  std::string stop = "phase4";
  std::string format = "json";
  bool json = false;
  std::string output;
};

std::pair<int, int> ParseEdge(const std::string& text) {
  const std::size_t comma = text.find(',');
  const auto fail = [&text]() -> std::pair<int, int> {
    throw InvalidArgument("--release-edge expects two neighbouring vertex numbers I,J such as 1,2 or 3,4, got '" +
                          text + "'");
  };
  if (comma == std::string::npos) return fail();
  try {
    std::size_t used_first = 0;
    std::size_t used_second = 0;
    const std::string first = text.substr(0, comma);
    const std::string second = text.substr(comma + 1);
    const int i = std::stoi(first, &used_first);
    const int j = std::stoi(second, &used_second);
    if (used_first != first.size() || used_second != second.size()) return fail();
    return {i, j};
  } catch (const std::logic_error&) {
    return fail();
  }
}

// --stop is one of the names already (CLI::IsMember).
core::StopCondition ParseStop(const std::string& text) {
  core::StopCondition stop = core::StopCondition::kTMax;
  core::FromString(text, &stop);
  return stop;
}

// −0 (e.g. ψ̇·a_B with ψ̇ = 0) printed as 0.
double Clean(double v) { return v == 0.0 ? 0.0 : v; }

nlohmann::json VectorJson(const Eigen::Vector3d& v) { return nlohmann::json::array({Clean(v.x()), Clean(v.y()), Clean(v.z())}); }

nlohmann::json QuaternionJson(const Eigen::Quaterniond& q) {
  return nlohmann::json::array({Clean(q.w()), Clean(q.x()), Clean(q.y()), Clean(q.z())});
}

nlohmann::json TrajectoryJson(const core::Block& block, const core::ModelParameters& params,
                              const core::SimulationOptions& options, const core::Trajectory& trajectory) {
  nlohmann::json out;
  out["t_end"] = trajectory.t_end_s;
  out["end_reason"] = core::ToString(trajectory.end_reason);
  out["message"] = trajectory.message;
  out["block"] = {{"b1", block.b1()}, {"b2", block.b2()}, {"h", block.h()}, {"mass", block.mass()}};
  out["parameters"] = {{"alpha", params.alpha_rad},          {"lambda", params.lambda},
                       {"tau_edge", params.tau_edge},        {"lambda_lat", params.lambda_lat},
                       {"lambda_lon", params.lambda_lon},    {"facet_tau", core::ToString(params.facet_tau_rule)},
                       {"stop", core::ToString(options.stop)}};
  nlohmann::json impacts = nlohmann::json::array();
  for (const auto& impact : trajectory.impacts) {
    impacts.push_back({{"t", impact.t_s},
                       {"kind", core::ToString(impact.kind)},
                       {"contact_before", impact.contact_before.ToString()},
                       {"contact_after", impact.kind == core::ImpactKind::kRest ? std::string("base")
                                                                                : impact.contact_after.ToString()},
                       {"omega_minus_B", VectorJson(impact.w_minus_B)},
                       {"omega_plus_B", VectorJson(impact.w_plus_B)},
                       {"omega_minus_W", VectorJson(impact.w_minus_W)},
                       {"omega_plus_W", VectorJson(impact.w_plus_W)},
                       {"tau", Clean(impact.tau)},
                       {"delta_energy", Clean(impact.delta_energy_J)},
                       {"status", core::ToString(impact.status)}});
  }
  out["impacts"] = std::move(impacts);
  nlohmann::json samples;
  samples["t"] = trajectory.t_s;
  nlohmann::json w_B = nlohmann::json::array(), q_WB = nlohmann::json::array(), euler = nlohmann::json::array(),
                 mode = nlohmann::json::array();
  for (const auto& w : trajectory.w_B) w_B.push_back(VectorJson(w));
  for (const auto& q : trajectory.q_WB) q_WB.push_back(QuaternionJson(q));
  for (const auto& e : trajectory.euler_zyx) euler.push_back(VectorJson(e));
  for (const auto& m : trajectory.mode) mode.push_back(m.ToString());
  samples["w_B"] = std::move(w_B);
  samples["q_WB"] = std::move(q_WB);
  samples["euler_zyx"] = std::move(euler);
  samples["mode"] = std::move(mode);
  out["samples"] = std::move(samples);
  nlohmann::json segments = nlohmann::json::array();
  double min_normal = std::numeric_limits<double>::infinity();
  double max_friction = 0.0;
  double max_drift = 0.0;
  for (const auto& s : trajectory.segments) {
    segments.push_back({{"t_begin", s.t_begin_s},
                        {"t_end", s.t_end_s},
                        {"mode", s.mode.ToString()},
                        {"min_normal_force", s.min_normal_force_N},
                        {"max_friction_ratio", s.max_friction_ratio},
                        {"energy_drift_rel", s.energy_drift_rel}});
    min_normal = std::min(min_normal, s.min_normal_force_N);
    max_friction = std::max(max_friction, s.max_friction_ratio);
    max_drift = std::max(max_drift, s.energy_drift_rel);
  }
  out["diagnostics"] = {{"wall_time_s", trajectory.wall_time_s},
                        {"num_steps", trajectory.num_steps},
                        {"num_evaluations", trajectory.num_evaluations},
                        {"min_normal_force", std::isfinite(min_normal) ? nlohmann::json(min_normal) : nlohmann::json()},
                        {"max_friction_ratio", max_friction},
                        {"max_energy_drift_rel", max_drift},
                        {"segments", std::move(segments)}};
  return out;
}

std::string TrajectoryCsv(const core::Trajectory& trajectory) {
  std::string csv =
      "t_s,w_x_B_rad_s,w_y_B_rad_s,w_z_B_rad_s,q_WB_w,q_WB_x,q_WB_y,q_WB_z,phi_z_rad,phi_y_rad,phi_x_rad,mode\n";
  for (std::size_t k = 0; k < trajectory.t_s.size(); ++k) {
    const Eigen::Vector3d& w = trajectory.w_B[k];
    const Eigen::Quaterniond& q = trajectory.q_WB[k];
    const Eigen::Vector3d& e = trajectory.euler_zyx[k];
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", Clean(trajectory.t_s[k]), Clean(w.x()), Clean(w.y()),
                       Clean(w.z()), Clean(q.w()), Clean(q.x()), Clean(q.y()), Clean(q.z()), Clean(e[0]), Clean(e[1]),
                       Clean(e[2]), trajectory.mode[k].ToString());
  }
  return csv;
}

int RunSimulate(SimulateCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  if (cmd.json) cmd.format = "json";
  cmd.params.facet_tau_rule = ParseFacetTauRule(cmd.facet_tau);
  const auto [first, second] = ParseEdge(cmd.release_edge);
  cmd.options.release_edge_first = first;
  cmd.options.release_edge_second = second;
  cmd.options.stop = ParseStop(cmd.stop);
  if (cmd.format == "hdf5" && cmd.output.empty()) {
    throw InvalidArgument("--format hdf5 writes a file: give it with -o FILE");
  }
  if (cmd.options.sample_times_s.empty()) {
    RequireTrajectorySamplesWithinLimit(cmd.options.t_max_s, cmd.options.rate_hz, "--t-max and --rate");
  }
  const Activity activity("simulating the motion and keeping its samples");
  const core::Trajectory trajectory = core::Simulate(block, cmd.params, cmd.options);

  if (cmd.format == "hdf5") {
    io::WriteTrajectoryHdf5(cmd.output, block, cmd.params, cmd.options, trajectory);
  } else {
    const std::string text = cmd.format == "csv" ? TrajectoryCsv(trajectory)
                                                 : TrajectoryJson(block, cmd.params, cmd.options, trajectory).dump(2) + "\n";
    if (cmd.output.empty()) {
      std::cout << text << std::flush;
    } else {
      io::WriteFileAtomically(cmd.output, [&text](std::ostream& out) { out << text; });
    }
  }
  if (trajectory.end_reason == core::EndReason::kFailed) {
    const bool too_many = trajectory.message.find("max_impacts") != std::string::npos;
    std::cerr << "rockfit: the simulation failed at t = " << trajectory.t_end_s << " s: " << trajectory.message
              << "\nThe output holds the trajectory up to the failure. "
              << (too_many ? "Raise --max-impacts, lower --t-max, or check the impact parameters."
                           : "Check the impact parameters against the bounds (25) and (27) of the paper.")
              << std::endl;
    return kExitNumerical;
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<SimulateCommand>();
  CLI::App* app = root.add_subcommand(
      "simulate",
      "Simulate the free 3D rocking of the block released from rest on a base edge (Várkonyi, Kocsis & Ther 2021):\n"
      "edge and vertex rocking joined by facet and edge impacts, Zeno handling, rest and overturning.\n"
      "Prints the sampled trajectory (w_B, q_WB, Euler ZYX, mode), the impact log and diagnostics.");
  AddBlockOptions(*app, cmd->block);
  auto& p = cmd->params;
  auto& o = cmd->options;
  app->add_option("--alpha", p.alpha_rad, "Release tilt α [rad] (the +x side lifted for the default edge)")
      ->capture_default_str()->group("Model");
  app->add_option("--lambda", p.lambda, "λ of edge impacts (19); (25) is −1 ≤ λ ≤ 1")->capture_default_str()->group("Model");
  app->add_option("--tau-edge", p.tau_edge, "Vertical angular impulse τ of edge impacts [N·m·s]")
      ->capture_default_str()->group("Model");
  app->add_option("--lambda-lat", p.lambda_lat, "λ_lat of facet impacts (21); (27) is −1 ≤ λ_lat ≤ 1")
      ->capture_default_str()->group("Model");
  app->add_option("--lambda-lon", p.lambda_lon, "λ_lon of facet impacts (21); (27) is −1 ≤ λ_lon ≤ 1")
      ->capture_default_str()->group("Model");
  app->add_option("--facet-tau", cmd->facet_tau, "τ of facet impacts: no-spin (postulate (24)) or fixed (τ = 0, Sect. 5; also zero)")
      ->check(CLI::IsMember({"no-spin", "fixed", "zero"}))->capture_default_str()->group("Model");
  app->add_option("--release-edge", cmd->release_edge, "Release edge I,J (neighbouring base vertices)")
      ->capture_default_str()->group("Model");
  app->add_option("--rate", o.rate_hz, "Output sample rate [Hz]; samples at t_k = k/rate")
      ->capture_default_str()->group("Simulation");
  app->add_option("--stop", cmd->stop,
                  "Stop at: phase4 (first impact on the release side after the first facet impact), rest, "
                  "overturned, t_max")
      ->check(CLI::IsMember({"phase4", "rest", "overturned", "t_max"}))->capture_default_str()->group("Simulation");
  app->add_option("--t-max", o.t_max_s, "Longest simulated time [s]")->capture_default_str()->group("Simulation");
  app->add_option("--zeno-dt", o.zeno_dt_s,
                  "Edge impacts on one edge closer than this [s] (and shrinking) switch to edge rocking; facet "
                  "impacts likewise end in rest")
      ->capture_default_str()->group("Simulation");
  app->add_option("--rest-height", o.rest_energy_height_m,
                  "Rest when the kinetic energy after a facet impact is below m·g·this [m]")
      ->capture_default_str()->group("Simulation");
  app->add_option("--gravity", o.gravity_m_s2, "Gravitational acceleration [m/s²]")->capture_default_str()->group("Simulation");
  app->add_option("--max-impacts", o.max_impacts, "A run with more impacts ends as failed")
      ->capture_default_str()->group("Simulation");
  app->add_option("--rel-tol", o.rel_tol, "Integrator relative tolerance")->capture_default_str()->group("Tolerances");
  app->add_option("--abs-tol", o.abs_tol, "Integrator absolute tolerance")->capture_default_str()->group("Tolerances");
  app->add_option("--event-tol", o.event_time_tol_s,
                  "Location tolerance of a guard's extremum [s] (crossings are located to round-off)")
      ->capture_default_str()->group("Tolerances");
  app->add_option("--max-step", o.max_step_s, "Largest integrator step [s]")->capture_default_str()->group("Tolerances");
  app->add_option("--format", cmd->format, "Output format: json, csv (one row per sample) or hdf5 (needs -o)")
      ->check(CLI::IsMember({"json", "csv", "hdf5"}))->capture_default_str()->group("Output");
  app->add_flag("--json", cmd->json, "Same as --format json")->group("Output");
  app->add_option("-o,--output", cmd->output, "Output file (default: stdout for json and csv)")->group("Output");
  app->footer(LimitsHelp());
  app->callback([cmd] { SetExitCode(RunSimulate(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
