#include "rockfit/app/respond_run.hpp"

#include <algorithm>
#include <cmath>

#include "rockfit/app/activity.hpp"
#include "rockfit/app/fitted_parameters.hpp"
#include "rockfit/app/json_values.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/app/run_limits.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::app {

double CleanZero(double v) { return v == 0.0 ? 0.0 : v; }
double BaseTilt(const Eigen::Quaterniond& q_WB) {
  return std::acos(std::clamp(q_WB.toRotationMatrix()(2, 2), -1.0, 1.0));
}

nlohmann::json ResponseSummaryJson(const core::ResponseSummary& s) {
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

nlohmann::json ResponseJson(const core::Block& block, const RespondRun& run) {
  const core::ModelParameters& params = run.params;
  const std::string& source = run.source;
  const LoadedGroundMotion& ground = run.ground;
  const core::Response& r = run.response;
  const std::optional<core::RoundOffSpread>& spread = run.spread;
  nlohmann::json out;
  out["summary"] = ResponseSummaryJson(r.summary);
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
                       {"delta_energy", CleanZero(i.delta_energy_J)},
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
    q_WB.push_back({CleanZero(q.w()), CleanZero(q.x()), CleanZero(q.y()), CleanZero(q.z())});
    tilt.push_back(BaseTilt(q));
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

RespondRun RunRespond(const core::Block& block, const RespondArgs& args) {
  RespondArgs cmd = args;
  std::string source = "command line";
  if (!core::FromString(cmd.start, &cmd.options.start)) {
    throw InvalidArgument("the start is flat or tilted, got '" + cmd.start + "'");
  }
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
    if (cmd.options.start == core::GroundStart::kFlatAtRest) cmd.params.alpha_rad = alpha;
    source = fitted.description + " in " + cmd.fits;
  } else if (!cmd.trial.empty() || !cmd.group.empty()) {
    throw InvalidArgument("--trial and --group need --fits FILE");
  }
  cmd.params.facet_tau_rule = ParseFacetTauRule(cmd.facet_tau);
  if (cmd.until != "rest" && cmd.until != "t_max") throw InvalidArgument("until is rest or t_max, got '" + cmd.until + "'");
  if (cmd.round_off_runs < 0) throw InvalidArgument("the round-off runs must be ≥ 0");
  cmd.options.end_at_rest = cmd.until == "rest";
  cmd.options.simulation.overturn = ParseOverturnRule(cmd.overturn);
  RespondRun run;
  run.ground = LoadGroundMotion(cmd.ground);
  const LoadedGroundMotion& ground = run.ground;
  RequireResponseWithinLimit(ground.assembled.ground, cmd.ground.record, !cmd.ground.synthetic_seed, cmd.options.tail_s,
                             cmd.options.simulation.rate_hz);
  const Activity activity("simulating the response and keeping its samples");
  run.response = core::Respond(block, cmd.params, ground.assembled.ground, cmd.options);
  if (cmd.round_off_runs > 0) {
    run.spread = core::RespondUnderRoundOff(block, cmd.params, ground.assembled.ground, cmd.options, run.response.summary,
                                        cmd.round_off_runs);
  }
  run.params = cmd.params;
  run.source = source;
  run.options = cmd.options;
  return run;
}

}  // namespace rockfit::app
