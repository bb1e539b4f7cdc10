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
#include "rockfit/app/respond_run.hpp"
#include "rockfit/app/run_limits.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/response.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "rockfit/io/trajectory_hdf5.hpp"

namespace rockfit::tools {
namespace {

struct RespondCommand {
  BlockArgs block;
  RespondArgs args;
  std::string format;
  bool json = false;
  std::string output;
};

std::string ResponseCsv(const core::GroundMotion& g, const core::Trajectory& tr) {
  std::string csv =
      "t_s,a_g_x_m_s2,a_g_y_m_s2,a_g_z_m_s2,tilt_rad,w_x_B_rad_s,w_y_B_rad_s,w_z_B_rad_s,q_WB_w,q_WB_x,q_WB_y,q_WB_z,mode\n";
  for (std::size_t k = 0; k < tr.t_s.size(); ++k) {
    const Eigen::Vector3d a = g.Acceleration_W(tr.t_s[k]);
    const Eigen::Vector3d& w = tr.w_B[k];
    const Eigen::Quaterniond& q = tr.q_WB[k];
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", CleanZero(tr.t_s[k]), CleanZero(a.x()), CleanZero(a.y()),
                       CleanZero(a.z()), CleanZero(BaseTilt(q)), CleanZero(w.x()), CleanZero(w.y()), CleanZero(w.z()), CleanZero(q.w()), CleanZero(q.x()),
                       CleanZero(q.y()), CleanZero(q.z()), tr.mode[k].ToString());
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

int RunRespondCommand(RespondCommand& cmd) {
  const core::Block block = MakeBlock(cmd.block);
  if (cmd.json && cmd.format.empty()) cmd.format = "json";
  if (cmd.format == "hdf5" && cmd.output.empty()) throw InvalidArgument("--format hdf5 writes a file: give it with -o FILE");
  if (!cmd.output.empty() && cmd.format.empty()) cmd.format = "json";
  const RespondRun run = RunRespond(block, cmd.args);
  const LoadedGroundMotion& ground = run.ground;
  const core::Response& response = run.response;
  if (cmd.format == "hdf5") {
    core::SimulationOptions written = run.options.simulation;
    written.t_max_s = ground.assembled.ground.t_end_s() + run.options.tail_s;
    written.stop = run.options.end_at_rest ? core::StopCondition::kRest : core::StopCondition::kTMax;
    io::WriteResponseHdf5(cmd.output, block, run.params, written, response, ground.assembled.ground, ground.sources);
  } else if (!cmd.format.empty()) {
    const std::string text = cmd.format == "csv" ? ResponseCsv(ground.assembled.ground, response.trajectory)
                                                 : ResponseJson(block, run).dump(2) + "\n";
    if (cmd.output.empty()) {
      std::cout << text << std::flush;
    } else {
      io::WriteFileAtomically(cmd.output, [&text](std::ostream& out) { out << text; });
    }
  }
  if (cmd.format.empty() || !cmd.output.empty()) {
    if (!(cmd.format == "json" && cmd.output.empty())) PrintSummary(block, run.params, run.source, ground, response, run.spread);
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
  auto& p = cmd->args.params;
  app->add_option("--lambda", p.lambda, "λ of edge impacts (19)")->capture_default_str()->group("Model");
  app->add_option("--lambda-lat", p.lambda_lat, "λ_lat of facet impacts (21)")->capture_default_str()->group("Model");
  app->add_option("--lambda-lon", p.lambda_lon, "λ_lon of facet impacts (21)")->capture_default_str()->group("Model");
  app->add_option("--tau-edge", p.tau_edge, "τ of edge impacts [N·m·s]")->capture_default_str()->group("Model");
  app->add_option("--facet-tau", cmd->args.facet_tau, "τ of facet impacts: no-spin (24) or fixed (τ = 0, Sect. 5; also zero)")
      ->check(CLI::IsMember({"no-spin", "fixed", "zero"}))->capture_default_str()->group("Model");
  app->add_option("--fits", cmd->args.fits, "Take λ, λ_lat, λ_lon, τ_edge from this fit file (rockfit fit -o / batch)")
      ->group("Model");
  app->add_option("--trial", cmd->args.trial, "With --fits: the fitted values of this trial")->group("Model");
  app->add_option("--group", cmd->args.group,
                  "With --fits: BLOCK,POSITION — the group's pooled estimates of λ, λ_lat, λ_lon from a file of "
                  "`rockfit batch` (the mean where no trial determined a parameter), else the mean of its fits")
      ->group("Model");
  app->add_option("--start", cmd->args.start,
                  "flat: at rest on the base (default); tilted: released from rest at --alpha on edge V1V2")
      ->check(CLI::IsMember({"flat", "tilted"}))->capture_default_str()->group("Model");
  app->add_option("--alpha", p.alpha_rad, "Release tilt [rad] for --start tilted")->capture_default_str()->group("Model");
  AddGroundMotionOptions(*app, cmd->args.ground);
  auto& o = cmd->args.options;
  app->add_option("--tail", o.tail_s, "Simulate this long after the end of the record [s]")
      ->capture_default_str()->group("Simulation");
  app->add_option("--until", cmd->args.until,
                  "rest: end when the block rests and cannot uplift again before the end; t_max: run to record end + tail")
      ->check(CLI::IsMember({"rest", "t_max"}))->capture_default_str()->group("Simulation");
  app->add_option("--overturn", cmd->args.overturn,
                  "When the block has overturned. support: its COM passes over the support edge or vertex; side: the\n"
                  "motion goes on past it (the table may pull the block back) until the block lies on a side — the\n"
                  "criterion of rocking spectra in the literature (core/README.md, \"Overturning under ground motion\")")
      ->check(CLI::IsMember({"support", "side"}))->capture_default_str()->group("Simulation");
  app->add_option("--round-off", cmd->args.round_off_runs,
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
  app->callback([cmd] { SetExitCode(RunRespondCommand(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
