// `respond` for both front ends: the earthquake response of a block (core::Respond) from plain arguments —
// parameters given or read from a fit file (`--fits` with `--trial` or `--group`), a ground motion, the response
// options by name — and the JSON document of the result (`rockfit respond --json`, the Record of
// `rockfit.respond`).
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "rockfit/app/ground_motion_args.hpp"
#include "rockfit/core/block.hpp"
#include "rockfit/core/response.hpp"

namespace rockfit::app {

struct RespondArgs {
  core::ModelParameters params;  // λ, λ_lat, λ_lon, τ_edge given; α for start = "tilted"
  std::string fits;              // a fit file (rockfit fit -o / batch): parameters from it instead
  std::string trial;             // with fits: one trial's fitted values
  std::string group;             // with fits: BLOCK,POSITION — the group's pooled estimates (or mean)
  GroundMotionArgs ground;
  core::ResponseOptions options;
  std::string start = "flat";      // flat | tilted
  std::string until = "rest";      // rest | t_max
  std::string overturn = "support";  // support | side
  std::string facet_tau = "no-spin";
  int round_off_runs = 0;
};

struct RespondRun {
  core::ModelParameters params;  // as used
  std::string source;            // where the parameters come from
  core::ResponseOptions options; // as used
  LoadedGroundMotion ground;
  core::Response response;
  std::optional<core::RoundOffSpread> spread;  // with round_off_runs > 0
};

// Throws InvalidArgument for bad arguments, BadInput for unreadable records or fit files. A failed simulation is
// the end reason `failed` of the summary, not an exception.
RespondRun RunRespond(const core::Block& block, const RespondArgs& args);

nlohmann::json ResponseSummaryJson(const core::ResponseSummary& summary);
// summary, block, parameters, ground_motion, impacts, samples (t, a_g_W, w_B, q_WB, tilt, mode), round_off.
nlohmann::json ResponseJson(const core::Block& block, const RespondRun& run);

// The tilt of the base from the horizontal [rad] at attitude q_WB.
double BaseTilt(const Eigen::Quaterniond& q_WB);
// −0 written as 0 (for text output).
double CleanZero(double v);

}  // namespace rockfit::app
