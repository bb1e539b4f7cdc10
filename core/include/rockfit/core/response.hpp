// Earthquake response of a block: one pure function (block, impact parameters, ground motion, options) →
// trajectory and summary, with the status in the summary (core/README.md, "Ground motion"). It is the
// entry point for `rockfit respond` and for studies that run many records (fragility curves).
//
//   rockfit::core::ResponseOptions options;                       // flat at rest, 200 Hz samples
//   const rockfit::core::Response r = rockfit::core::Respond(block, params, quake, options);
//   if (r.summary.overturned) { /* r.summary.t_overturn_s */ }
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core {

struct ResponseOptions {
  GroundStart start = GroundStart::kFlatAtRest;
  // The run goes on this long after the last record sample [s] (t_max = end of the record + tail).
  double tail_s = 5.0;
  // true: a block at rest that cannot uplift again before t_max ends the run (`rest`); false: it is sampled
  // at rest up to t_max (`t_max`).
  bool end_at_rest = true;
  // Output rate, gravity, tolerances, Zeno and rest thresholds, initial state (for GroundStart::kAsOptions).
  // Respond sets t_max_s and stop itself; release α comes from ModelParameters.
  SimulationOptions simulation = DefaultSimulation();
  static SimulationOptions DefaultSimulation() {
    SimulationOptions s;
    s.rate_hz = 200.0;
    s.stop = StopCondition::kRest;
    return s;
  }
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

struct ResponseSummary {
  EndReason end_reason = EndReason::kFailed;
  std::string message;  // why a failed or lifted-off run ended
  double t_end_s = 0.0;
  bool overturned = false;
  // When it overturned: the COM passed over the support, or (OverturnRule::kFallsOnSide) it came to lie on a side.
  std::optional<double> t_overturn_s;
  OverturnRule overturn_rule = OverturnRule::kComOverSupport;  // the rule of the run
  // Over the samples (and the end state): the tilt is the angle between the body's z axis and the vertical,
  // the rotation the angle of q_WB (tilt and twist about the vertical together).
  double peak_tilt_rad = 0.0;
  double t_peak_tilt_s = 0.0;
  double peak_rotation_rad = 0.0;
  double peak_rate_rad_s = 0.0;     // largest |w_B|
  // The tilt at which the COM is above a base edge, atan(min(b1, b2)/h): tilts beyond it overturn when at rest.
  double critical_tilt_rad = 0.0;
  std::size_t num_impacts = 0;         // edge and facet impacts
  std::vector<double> uplift_times_s;  // rest → rocking
  // The largest |w_B| that a rest set to zero (Trajectory::max_discarded_rate_rad_s): the rest tolerance at work.
  double max_discarded_rate_rad_s = 0.0;
  double max_friction_ratio = 0.0;     // largest |F_t|/F_n needed for no slip (sliding is not modelled)
  double min_normal_force_N = 0.0;     // smallest normal force while rocking (negative: the block would jump)
  double peak_ground_horizontal_m_s2 = 0.0;
  double peak_ground_vertical_m_s2 = 0.0;
  double wall_time_s = 0.0;
};

struct Response {
  Trajectory trajectory;
  ResponseSummary summary;
};

// Throws InvalidArgument for invalid options or parameters (an empty ground motion included); everything
// that happens during the run is a status in summary.end_reason, never an exception or a NaN.
Response Respond(const Block& block, const ModelParameters& params, const GroundMotion& ground,
                 const ResponseOptions& options);

// How a response depends on round-off (core/README.md, "Sensitivity of a single response"): `runs` runs of the
// record scaled by 1 + k·kRoundOffStep, k = 0, 1, −1, 2, −2, …, of which the first (k = 0) is `at_record`, the
// summary of Respond() on the record itself. A block that chatters along a base edge amplifies a difference of
// round-off a hundredfold every fifteen impacts; near the overturning boundary its verdict can then differ from
// one run to the next. Throws InvalidArgument for runs < 1 (and as Respond()).
struct RoundOffSpread {
  static constexpr double kRoundOffStep = 1e-15;  // relative; a few units in the last place of a sample
  int runs = 0;
  int overturned = 0;
  int failed = 0;
  double peak_tilt_min_rad = 0.0;
  double peak_tilt_max_rad = 0.0;
};
RoundOffSpread RespondUnderRoundOff(const Block& block, const ModelParameters& params, const GroundMotion& ground,
                                    const ResponseOptions& options, const ResponseSummary& at_record, int runs);

// The summary of a trajectory of a run under `ground` (Respond() calls it).
ResponseSummary SummariseResponse(const Block& block, const GroundMotion& ground, const Trajectory& trajectory);

}  // namespace rockfit::core
