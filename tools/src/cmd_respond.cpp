// `rockfit respond`: the earthquake response of a block with fitted impact parameters (core/response.hpp) —
// summary on stdout, trajectory as JSON, CSV or HDF5.

#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "rockfit/app/activity.hpp"
#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/fitted_parameters.hpp"
#include "rockfit/app/ground_motion_args.hpp"
#include "rockfit/app/run_limits.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/response.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "rockfit/io/trajectory_hdf5.hpp"

namespace rockfit::tools {
namespace {

struct RespondCommand {
  BlockArgs block;
  core::ModelParameters params;
  std::string fits;
  std::string trial;
  std::string group;
  GroundMotionArgs ground;
  core::ResponseOptions options;
  std::string start = "flat";
  std::string until = "rest";
  std::string overturn = "support";
  int round_off_runs = 0;
  std::string facet_tau = "no-spin";
  std::string format;
  bool json = false;
  std::string output;
};

double Clean(double v) { return v == 0.0 ? 0.0 : v; }
double Tilt(const Eigen::Quaterniond& q) { return std::acos(std::clamp(q.toRotationMatrix()(2, 2), -1.0, 1.0)); }

nlohmann::json SummaryJson(const core::ResponseSummary& s) {
  return {{"end_reason", core::ToString(s.end_reason)},
          {"message", s.message},
          {"t_end", s.t_end_s},
          {"overturned", s.overturned},
          {"t_overturn", OrNull(s.t_overturn_s)},
          {"overturn_rule", core::ToString(s.overturn_rule)},
          {"peak_tilt_rad", s.peak_tilt_rad},
          {"t_peak_tilt", s.t_peak_tilt_s},
          {"critical_tilt_rad", s.critical_tilt_rad},
          {"peak_rotation_rad", s.peak_rotation_rad},
          {"peak_rate_rad_s", s.peak_rate_rad_s},
          {"num_impacts", s.num_impacts},
          {"uplift_times", s.uplift_times_s},
          {"max_discarded_rate_rad_s", s.max_discarded_rate_rad_s},
          {"max_friction_ratio", s.max_friction_ratio},
          {"min_normal_force", s.min_normal_force_N},
          {"pga_horizontal_m_s2", s.peak_ground_horizontal_m_s2},
          {"pga_vertical_m_s2", s.peak_ground_vertical_m_s2},
          {"wall_time_s", s.wall_time_s}};
}

nlohmann::json ResponseJson(const core::Block& block, const core::ModelParameters& params, const std::string& source,
                            const LoadedGroundMotion& ground, const core::Response& r,
                            const std::optional<core::RoundOffSpread>& spread) {
  nlohmann::json out;
  out["summary"] = SummaryJson(r.summary);
  out["block"] = {{"b1", block.b1()}, {"b2", block.b2()}, {"h", block.h()}, {"mass", block.mass()}};
  out["parameters"] = {{"alpha", params.alpha_rad},   {"lambda", params.lambda},         {"tau_edge", params.tau_edge},
                       {"lambda_lat", params.lambda_lat}, {"lambda_lon", params.lambda_lon},
                       {"facet_tau", core::ToString(params.facet_tau_rule)}, {"source", source}};
  const core::GroundMotion& g = ground.assembled.ground;
  out["ground_motion"] = {{"sources", ground.sources},    {"dt_s", g.dt_s()},   {"npts", g.size()},
                          {"duration_s", g.t_end_s()},    {"scale", ground.assembled.scale},
                          {"pga_horizontal_m_s2", g.PeakHorizontal()}, {"pga_vertical_m_s2", g.PeakVertical()},
                          {"notes", ground.assembled.notes}};
  nlohmann::json impacts = nlohmann::json::array();
  for (const auto& i : r.trajectory.impacts) {
    impacts.push_back({{"t", i.t_s},
                       {"kind", core::ToString(i.kind)},
                       {"contact_before", i.kind == core::ImpactKind::kUplift && i.contact_before.first == 0
                                              ? std::string("base")
                                              : i.contact_before.ToString()},
                       {"contact_after",
                        i.kind == core::ImpactKind::kRest ? std::string("base") : i.contact_after.ToString()},
                       {"omega_minus_B", ToJson(i.w_minus_B)},
                       {"omega_plus_B", ToJson(i.w_plus_B)},
                       {"delta_energy", Clean(i.delta_energy_J)},
                       {"status", core::ToString(i.status)}});
  }
  out["impacts"] = std::move(impacts);
  const core::Trajectory& tr = r.trajectory;
  nlohmann::json a_g = nlohmann::json::array(), w_B = nlohmann::json::array(), q_WB = nlohmann::json::array(),
                 tilt = nlohmann::json::array(), mode = nlohmann::json::array();
  for (std::size_t k = 0; k < tr.t_s.size(); ++k) {
    a_g.push_back(ToJson(g.Acceleration_W(tr.t_s[k])));
    w_B.push_back(ToJson(tr.w_B[k]));
    const Eigen::Quaterniond& q = tr.q_WB[k];
    q_WB.push_back({Clean(q.w()), Clean(q.x()), Clean(q.y()), Clean(q.z())});
    tilt.push_back(Tilt(q));
    mode.push_back(tr.mode[k].ToString());
  }
  out["samples"] = {{"t", tr.t_s}, {"a_g_W", a_g}, {"w_B", w_B}, {"q_WB", q_WB}, {"tilt", tilt}, {"mode", mode}};
  if (spread) {
    out["round_off"] = {{"runs", spread->runs},
                        {"overturned", spread->overturned},
                        {"failed", spread->failed},
                        {"relative_step", core::RoundOffSpread::kRoundOffStep},
                        {"peak_tilt_min_rad", spread->peak_tilt_min_rad},
                        {"peak_tilt_max_rad", spread->peak_tilt_max_rad}};
  }
  return out;
}

std::string ResponseCsv(const core::GroundMotion& g, const core::Trajectory& tr) {
  std::string csv =
      "t_s,a_g_x_m_s2,a_g_y_m_s2,a_g_z_m_s2,tilt_rad,w_x_B_rad_s,w_y_B_rad_s,w_z_B_rad_s,q_WB_w,q_WB_x,q_WB_y,q_WB_z,mode\n";
  for (std::size_t k = 0; k < tr.t_s.size(); ++k) {
    const Eigen::Vector3d a = g.Acceleration_W(tr.t_s[k]);
    const Eigen::Vector3d& w = tr.w_B[k];
    const Eigen::Quaterniond& q = tr.q_WB[k];
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", Clean(tr.t_s[k]), Clean(a.x()), Clean(a.y()),
                       Clean(a.z()), Clean(Tilt(q)), Clean(w.x()), Clean(w.y()), Clean(w.z()), Clean(q.w()), Clean(q.x()),
                       Clean(q.y()), Clean(q.z()), tr.mode[k].ToString());
  }
  return csv;
}

void PrintSummary(const core::Block& block, const core::ModelParameters& p, const std::string& source,
                  const LoadedGroundMotion& ground, const core::Response& r,
                  const std::optional<core::RoundOffSpread>& spread) {
  const core::ResponseSummary& s = r.summary;
  const core::GroundMotion& g = ground.assembled.ground;
  std::cout << fmt::format("block           b1 = {} m, b2 = {} m, h = {} m, m = {:.4g} kg\n", block.b1(), block.b2(),
                           block.h(), block.mass());
  std::cout << fmt::format("parameters      λ = {:.4g}, λ_lat = {:.4g}, λ_lon = {:.4g} ({})\n", p.lambda, p.lambda_lat,
                           p.lambda_lon, source);
  for (const std::string& line : ground.sources) std::cout << "record          " << line << "\n";
  for (const std::string& line : ground.assembled.notes) std::cout << "note            " << line << "\n";
  std::cout << fmt::format("ground motion   {} samples at {} s, scale {:.6g}, PGA {:.4f} g horizontal, {:.4f} g vertical\n",
                           g.size(), g.dt_s(), ground.assembled.scale, g.PeakHorizontal() / core::kRecordGravity,
                           g.PeakVertical() / core::kRecordGravity);
  std::cout << fmt::format("status          {} at {:.4f} s{}\n", core::ToString(s.end_reason), s.t_end_s,
                           s.message.empty() ? "" : " (" + s.message + ")");
  const char* how = s.overturn_rule == core::OverturnRule::kFallsOnSide ? "lies on a side" : "COM over the support";
  std::cout << fmt::format("overturned      {}\n",
                           s.overturned ? fmt::format("yes, at {:.4f} s ({})", *s.t_overturn_s, how) : "no");
  std::cout << fmt::format("peak tilt       {:.5f} rad at {:.3f} s ({:.1f} % of the critical {:.5f} rad)\n",
                           s.peak_tilt_rad, s.t_peak_tilt_s, 100.0 * s.peak_tilt_rad / s.critical_tilt_rad,
                           s.critical_tilt_rad);
  std::cout << fmt::format("peak rotation   {:.5f} rad (tilt and twist), peak |ω| {:.4f} rad/s\n", s.peak_rotation_rad,
                           s.peak_rate_rad_s);
  std::string uplifts;
  for (std::size_t k = 0; k < s.uplift_times_s.size() && k < 10; ++k) uplifts += fmt::format(" {:.4f}", s.uplift_times_s[k]);
  if (s.uplift_times_s.size() > 10) uplifts += fmt::format(" … ({} in all)", s.uplift_times_s.size());
  std::cout << fmt::format("uplifts         {}{}\n", s.uplift_times_s.size(), s.uplift_times_s.empty() ? "" : " at" + uplifts + " s");
  std::cout << fmt::format("impacts         {}\n", s.num_impacts);
  std::cout << fmt::format("rests           largest |ω| set to zero {:.3g} rad/s\n", s.max_discarded_rate_rad_s);
  std::cout << fmt::format("friction ratio  {:.4f} (largest |F_t|/F_n needed; sliding is not modelled)\n",
                           s.max_friction_ratio);
  if (spread) {
    const int k_max = spread->runs / 2;
    std::cout << fmt::format("round-off       overturned in {} of {} runs of the record scaled by 1 + k·{:g} (|k| ≤ {}); peak "
                             "tilt {:.5f} … {:.5f} rad{}{}\n",
                             spread->overturned, spread->runs, core::RoundOffSpread::kRoundOffStep, k_max,
                             spread->peak_tilt_min_rad, spread->peak_tilt_max_rad,
                             spread->failed > 0 ? fmt::format(", {} failed", spread->failed) : "",
                             spread->overturned > 0 && spread->overturned < spread->runs
                                 ? " — the verdict depends on round-off: ask `rockfit fragility` for its probability"
                                 : "");
  }
  std::cout << fmt::format("wall time       {:.2f} ms\n", 1e3 * s.wall_time_s);
}

int RunRespond(RespondCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  std::string source = "command line";
  if (!cmd.fits.empty()) {
    if (cmd.trial.empty() == cmd.group.empty()) {
      throw InvalidArgument("with --fits give exactly one of --trial ID or --group BLOCK,POSITION");
    }
    FittedParameters fitted;
    if (!cmd.trial.empty()) {
      fitted = ReadFittedTrial(cmd.fits, cmd.trial);
    } else {
      const std::size_t comma = cmd.group.find(',');
      if (comma == std::string::npos) throw InvalidArgument("--group expects BLOCK,POSITION such as block2,A");
      const std::string block = cmd.group.substr(0, comma), position = cmd.group.substr(comma + 1);
      fitted = ReadFittedGroupMean(cmd.fits, block, position);
      // A file of `rockfit batch` carries the group's pooled estimates (/summary/fits/per_group): they weigh
      // each trial by its interval, where the plain mean does not. A file of `fit -o` has only the mean.
      try {
        const FittedGroupRanges ranges = ReadFittedGroupRanges(cmd.fits, block, position);
        fitted.params.lambda = ranges.lambda.value;
        fitted.params.lambda_lat = ranges.lambda_lat.value;
        fitted.params.lambda_lon = ranges.lambda_lon.value;
        fitted.params.tau_edge = ranges.tau_edge.value;
        fitted.description = ranges.description;
      } catch (const BadInput&) {
        // No per-group table: keep the mean.
      }
    }
    const double alpha = cmd.params.alpha_rad;
    cmd.params = fitted.params;
    if (cmd.start == "flat") cmd.params.alpha_rad = alpha;
    source = fitted.description + " in " + cmd.fits;
  } else if (!cmd.trial.empty() || !cmd.group.empty()) {
    throw InvalidArgument("--trial and --group need --fits FILE");
  }
  core::FromString(cmd.facet_tau, &cmd.params.facet_tau_rule);  // one of the names the option accepts
  cmd.options.start = cmd.start == "flat" ? core::GroundStart::kFlatAtRest : core::GroundStart::kAsOptions;
  cmd.options.end_at_rest = cmd.until == "rest";
  core::FromString(cmd.overturn, &cmd.options.simulation.overturn);  // (checked by the option)
  if (cmd.json && cmd.format.empty()) cmd.format = "json";
  if (cmd.format == "hdf5" && cmd.output.empty()) throw InvalidArgument("--format hdf5 writes a file: give it with -o FILE");
  if (!cmd.output.empty() && cmd.format.empty()) cmd.format = "json";

  const LoadedGroundMotion ground = LoadGroundMotion(cmd.ground);
  CheckResponseLength(ground.assembled.ground, cmd.ground.record, !cmd.ground.synthetic_seed, cmd.options.tail_s,
                      cmd.options.simulation.rate_hz);
  const Activity activity("simulating the response and keeping its samples");
  const core::Response response = core::Respond(block, cmd.params, ground.assembled.ground, cmd.options);
  std::optional<core::RoundOffSpread> spread;
  if (cmd.round_off_runs > 0) {
    spread = core::RespondUnderRoundOff(block, cmd.params, ground.assembled.ground, cmd.options, response.summary,
                                        cmd.round_off_runs);
  }

  if (cmd.format == "hdf5") {
    core::SimulationOptions written = cmd.options.simulation;
    written.t_max_s = ground.assembled.ground.t_end_s() + cmd.options.tail_s;
    written.stop = cmd.options.end_at_rest ? core::StopCondition::kRest : core::StopCondition::kTMax;
    io::WriteResponseHdf5(cmd.output, block, cmd.params, written, response, ground.assembled.ground, ground.sources);
  } else if (!cmd.format.empty()) {
    const std::string text = cmd.format == "csv" ? ResponseCsv(ground.assembled.ground, response.trajectory)
                                                 : ResponseJson(block, cmd.params, source, ground, response, spread).dump(2) + "\n";
    if (cmd.output.empty()) {
      std::cout << text << std::flush;
    } else {
      io::WriteFileAtomically(cmd.output, [&text](std::ostream& out) { out << text; });
    }
  }
  if (cmd.format.empty() || !cmd.output.empty()) {
    if (!(cmd.format == "json" && cmd.output.empty())) PrintSummary(block, cmd.params, source, ground, response, spread);
    if (!cmd.output.empty()) std::cout << "written         " << cmd.output << "\n";
  }
  if (response.summary.end_reason == core::EndReason::kFailed) {
    std::cerr << "rockfit: the simulation failed at t = " << response.summary.t_end_s << " s: " << response.summary.message
              << "\nCheck the impact parameters against the bounds (25) and (27) of the paper." << std::endl;
    return kExitNumerical;
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<RespondCommand>();
  CLI::App* app = root.add_subcommand(
      "respond",
      "Earthquake response of a block with (fitted) 3D impact parameters: the block stands flat on a table that moves\n"
      "with a recorded or generated ground acceleration (inertial force −m·a_g at the COM, impacts on velocities\n"
      "relative to the table). Prints peak tilt and rotation, overturning, impacts, uplift times and the friction\n"
      "ratio needed for no slip; the trajectory goes out as JSON, CSV or HDF5 (-o). Sliding and free flight are not\n"
      "modelled: a table accelerating downward faster than g ends the run with status lift_off.");
  AddBlockOptions(*app, cmd->block);
  auto& p = cmd->params;
  app->add_option("--lambda", p.lambda, "λ of edge impacts (19)")->capture_default_str()->group("Model");
  app->add_option("--lambda-lat", p.lambda_lat, "λ_lat of facet impacts (21)")->capture_default_str()->group("Model");
  app->add_option("--lambda-lon", p.lambda_lon, "λ_lon of facet impacts (21)")->capture_default_str()->group("Model");
  app->add_option("--tau-edge", p.tau_edge, "τ of edge impacts [N·m·s]")->capture_default_str()->group("Model");
  app->add_option("--facet-tau", cmd->facet_tau, "τ of facet impacts: no-spin (24) or fixed (τ = 0, Sect. 5; also zero)")
      ->check(CLI::IsMember({"no-spin", "fixed", "zero"}))->capture_default_str()->group("Model");
  app->add_option("--fits", cmd->fits, "Take λ, λ_lat, λ_lon, τ_edge from this fit file (rockfit fit -o / batch)")
      ->group("Model");
  app->add_option("--trial", cmd->trial, "With --fits: the fitted values of this trial")->group("Model");
  app->add_option("--group", cmd->group,
                  "With --fits: BLOCK,POSITION — the group's pooled estimates of λ, λ_lat, λ_lon from a file of "
                  "`rockfit batch` (the mean where no trial determined a parameter), else the mean of its fits")
      ->group("Model");
  app->add_option("--start", cmd->start,
                  "flat: at rest on the base (default); tilted: released from rest at --alpha on edge V1V2")
      ->check(CLI::IsMember({"flat", "tilted"}))->capture_default_str()->group("Model");
  app->add_option("--alpha", p.alpha_rad, "Release tilt [rad] for --start tilted")->capture_default_str()->group("Model");
  AddGroundMotionOptions(*app, cmd->ground);
  auto& o = cmd->options;
  app->add_option("--tail", o.tail_s, "Simulate this long after the end of the record [s]")
      ->capture_default_str()->group("Simulation");
  app->add_option("--until", cmd->until,
                  "rest: end when the block rests and cannot uplift again before the end; t_max: run to record end + tail")
      ->check(CLI::IsMember({"rest", "t_max"}))->capture_default_str()->group("Simulation");
  app->add_option("--overturn", cmd->overturn,
                  "When the block has overturned. support: its COM passes over the support edge or vertex; side: the\n"
                  "motion goes on past it (the table may pull the block back) until the block lies on a side — the\n"
                  "criterion of rocking spectra in the literature (core/README.md, \"Overturning under ground motion\")")
      ->check(CLI::IsMember({"support", "side"}))->capture_default_str()->group("Simulation");
  app->add_option("--round-off", cmd->round_off_runs,
                  "Also run the record N times scaled by 1 + k·1e-15 (k = 0, ±1, ±2, …) and report how many of the runs\n"
                  "overturn: near the overturning boundary a block that chatters along an edge can turn round-off into\n"
                  "either verdict (core/README.md, \"Sensitivity of a single response\")")
      ->check(CLI::NonNegativeNumber)->group("Simulation");
  app->add_option("--rate", o.simulation.rate_hz, "Output sample rate [Hz] (peaks are taken over the samples, and the end)")
      ->capture_default_str()->group("Simulation");
  app->add_option("--gravity", o.simulation.gravity_m_s2, "Gravitational acceleration of the simulation [m/s²]")
      ->capture_default_str()->group("Simulation");
  app->add_option("--max-impacts", o.simulation.max_impacts, "A run with more impacts ends as failed")
      ->capture_default_str()->group("Simulation");
  app->add_option("--format", cmd->format, "Trajectory output: json, csv or hdf5 (needs -o); default: the summary only")
      ->check(CLI::IsMember({"json", "csv", "hdf5"}))->group("Output");
  app->add_flag("--json", cmd->json, "Print the JSON (summary, ground motion, impacts, samples) instead of the table")
      ->group("Output");
  app->add_option("-o,--output", cmd->output, "Output file for the trajectory (json unless --format)")->group("Output");
  app->footer(LimitsHelp());
  app->callback([cmd] { SetExitCode(RunRespond(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
