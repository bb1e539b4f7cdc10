#include "rockfit/core/response.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {

void ResponseOptions::Validate() const {
  if (!(tail_s >= 0.0) || !std::isfinite(tail_s)) {
    throw InvalidArgument("the tail after the record must be a non-negative number of seconds, got " +
                          std::to_string(tail_s));
  }
  simulation.Validate();
}

ResponseSummary SummariseResponse(const Block& block, const GroundMotion& ground, const Trajectory& trajectory) {
  ResponseSummary s;
  s.end_reason = trajectory.end_reason;
  s.message = trajectory.message;
  s.t_end_s = trajectory.t_end_s;
  s.overturned = trajectory.end_reason == EndReason::kOverturned;
  if (s.overturned) s.t_overturn_s = trajectory.t_end_s;
  s.critical_tilt_rad = std::atan(std::min(block.b1(), block.b2()) / block.h());
  const auto add_state = [&s](double t, const Eigen::Quaterniond& q, const Eigen::Vector3d& w_B) {
    s.peak_rate_rad_s = std::max(s.peak_rate_rad_s, w_B.norm());
    const double tilt = std::acos(std::clamp(q.toRotationMatrix()(2, 2), -1.0, 1.0));
    if (tilt > s.peak_tilt_rad) {
      s.peak_tilt_rad = tilt;
      s.t_peak_tilt_s = t;
    }
    s.peak_rotation_rad = std::max(s.peak_rotation_rad, 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())));
  };
  for (std::size_t k = 0; k < trajectory.t_s.size(); ++k) {
    if (k < trajectory.q_WB.size()) {
      add_state(trajectory.t_s[k], trajectory.q_WB[k], trajectory.w_B[k]);
    } else {
      s.peak_rate_rad_s = std::max(s.peak_rate_rad_s, trajectory.w_B[k].norm());
    }
  }
  // The end state, between samples: where an overturning block was when the run stopped.
  if (!trajectory.q_WB.empty()) add_state(trajectory.t_end_s, trajectory.end_q_WB, trajectory.end_w_B);
  for (const ImpactRecord& impact : trajectory.impacts) {
    if (impact.kind == ImpactKind::kEdge || impact.kind == ImpactKind::kFacet) ++s.num_impacts;
    if (impact.kind == ImpactKind::kUplift && impact.contact_before.first == 0) s.uplift_times_s.push_back(impact.t_s);
    s.peak_rate_rad_s = std::max({s.peak_rate_rad_s, impact.w_minus_B.norm(), impact.w_plus_B.norm()});
  }
  s.min_normal_force_N = std::numeric_limits<double>::infinity();
  for (const SegmentDiagnostics& segment : trajectory.segments) {
    s.max_friction_ratio = std::max(s.max_friction_ratio, segment.max_friction_ratio);
    s.min_normal_force_N = std::min(s.min_normal_force_N, segment.min_normal_force_N);
  }
  // Never rocked: the block stood on its base, carrying its weight.
  if (trajectory.segments.empty()) s.min_normal_force_N = 0.0;
  s.peak_ground_horizontal_m_s2 = ground.PeakHorizontal();
  s.peak_ground_vertical_m_s2 = ground.PeakVertical();
  s.wall_time_s = trajectory.wall_time_s;
  s.max_discarded_rate_rad_s = trajectory.max_discarded_rate_rad_s;
  return s;
}

Response Respond(const Block& block, const ModelParameters& params, const GroundMotion& ground,
                 const ResponseOptions& options) {
  options.Validate();
  if (ground.empty()) throw InvalidArgument("the ground motion has no samples");
  SimulationOptions simulation = options.simulation;
  simulation.t_max_s = ground.t_end_s() + options.tail_s;
  simulation.stop = options.end_at_rest ? StopCondition::kRest : StopCondition::kTMax;
  Response response;
  response.trajectory = Simulate(block, params, simulation, ground, options.start);
  response.summary = SummariseResponse(block, ground, response.trajectory);
  response.summary.overturn_rule = simulation.overturn;
  return response;
}

RoundOffSpread RespondUnderRoundOff(const Block& block, const ModelParameters& params, const GroundMotion& ground,
                                    const ResponseOptions& options, const ResponseSummary& at_record, int runs) {
  if (runs < 1) throw InvalidArgument("a round-off study needs at least one run, got " + std::to_string(runs));
  RoundOffSpread spread;
  spread.peak_tilt_min_rad = std::numeric_limits<double>::infinity();
  const auto add = [&spread](const ResponseSummary& s) {
    ++spread.runs;
    if (s.overturned) ++spread.overturned;
    if (s.end_reason == EndReason::kFailed) ++spread.failed;
    spread.peak_tilt_min_rad = std::min(spread.peak_tilt_min_rad, s.peak_tilt_rad);
    spread.peak_tilt_max_rad = std::max(spread.peak_tilt_max_rad, s.peak_tilt_rad);
  };
  add(at_record);
  for (int i = 1; i < runs; ++i) {
    const int k = (i + 1) / 2 * (i % 2 == 1 ? 1 : -1);  // 1, −1, 2, −2, …
    add(Respond(block, params, ground.Scaled(1.0 + k * RoundOffSpread::kRoundOffStep), options).summary);
  }
  return spread;
}

}  // namespace rockfit::core
