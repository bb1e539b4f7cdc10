// Names, options and parameter validation of the simulator (simulator.hpp).
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::core {

std::string Mode::ToString() const {
  switch (kind) {
    case ModeKind::kEdge:
      return "V" + std::to_string(contact.first) + "V" + std::to_string(contact.second);
    case ModeKind::kVertex:
      return "V" + std::to_string(contact.first);
    case ModeKind::kRest:
      return "rest";
    case ModeKind::kOverturned:
      return "overturned";
    case ModeKind::kFailed:
      return "failed";
  }
  return "failed";
}

const char* ToString(StopCondition stop) {
  switch (stop) {
    case StopCondition::kPhase4: return "phase4";
    case StopCondition::kRest: return "rest";
    case StopCondition::kOverturned: return "overturned";
    case StopCondition::kTMax: return "t_max";
  }
  return "phase4";
}

bool FromString(std::string_view text, StopCondition* stop) {
  for (StopCondition s :
       {StopCondition::kPhase4, StopCondition::kRest, StopCondition::kOverturned, StopCondition::kTMax}) {
    if (text == ToString(s)) {
      *stop = s;
      return true;
    }
  }
  return false;
}

const char* ToString(OverturnRule rule) {
  switch (rule) {
    case OverturnRule::kComOverSupport: return "support";
    case OverturnRule::kFallsOnSide: return "side";
  }
  return "support";
}

bool FromString(std::string_view text, OverturnRule* rule) {
  for (OverturnRule r : {OverturnRule::kComOverSupport, OverturnRule::kFallsOnSide}) {
    if (text == ToString(r)) {
      *rule = r;
      return true;
    }
  }
  return false;
}

const char* ToString(ModeKind kind) {
  switch (kind) {
    case ModeKind::kEdge: return "edge";
    case ModeKind::kVertex: return "vertex";
    case ModeKind::kRest: return "rest";
    case ModeKind::kOverturned: return "overturned";
    case ModeKind::kFailed: return "failed";
  }
  return "failed";
}

bool FromString(std::string_view text, ModeKind* value) {
  static constexpr ModeKind kAll[] = {ModeKind::kEdge, ModeKind::kVertex, ModeKind::kRest, ModeKind::kOverturned,
                                      ModeKind::kFailed};
  return core::FromStringAmong(text, kAll, value);
}

const char* ToString(GroundStart start) {
  switch (start) {
    case GroundStart::kFlatAtRest: return "flat";
    case GroundStart::kAsOptions: return "tilted";
  }
  return "flat";
}

bool FromString(std::string_view text, GroundStart* value) {
  static constexpr GroundStart kAll[] = {GroundStart::kFlatAtRest, GroundStart::kAsOptions};
  return core::FromStringAmong(text, kAll, value);
}

const char* ToString(EndReason reason) {
  switch (reason) {
    case EndReason::kPhase4: return "phase4";
    case EndReason::kRest: return "rest";
    case EndReason::kOverturned: return "overturned";
    case EndReason::kTMax: return "t_max";
    case EndReason::kFailed: return "failed";
    case EndReason::kLiftOff: return "lift_off";
  }
  return "failed";
}

bool FromString(std::string_view text, EndReason* value) {
  static constexpr EndReason kAll[] = {EndReason::kPhase4, EndReason::kRest, EndReason::kOverturned, EndReason::kTMax, EndReason::kFailed, EndReason::kLiftOff};
  return core::FromStringAmong(text, kAll, value);
}

const char* ToString(ImpactKind kind) {
  switch (kind) {
    case ImpactKind::kFacet: return "facet";
    case ImpactKind::kEdge: return "edge";
    case ImpactKind::kZeno: return "zeno";
    case ImpactKind::kRest: return "rest";
    case ImpactKind::kUplift: return "uplift";
  }
  return "facet";
}

bool FromString(std::string_view text, ImpactKind* kind) {
  for (ImpactKind k :
       {ImpactKind::kFacet, ImpactKind::kEdge, ImpactKind::kZeno, ImpactKind::kRest, ImpactKind::kUplift}) {
    if (text == ToString(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

const char* ToString(FailureReason reason) {
  switch (reason) {
    case FailureReason::kNone: return "none";
    case FailureReason::kEdgeImpact: return "edge_impact";
    case FailureReason::kFacetImpact: return "facet_impact";
    case FailureReason::kIntegratorStep: return "integrator_step";
    case FailureReason::kImpactCascade: return "impact_cascade";
    case FailureReason::kMaxImpacts: return "max_impacts";
    case FailureReason::kEnergyBlowUp: return "energy_blow_up";
  }
  return "none";
}

bool FromString(std::string_view text, FailureReason* value) {
  static constexpr FailureReason kAll[] = {FailureReason::kNone, FailureReason::kEdgeImpact, FailureReason::kFacetImpact, FailureReason::kIntegratorStep, FailureReason::kImpactCascade, FailureReason::kMaxImpacts, FailureReason::kEnergyBlowUp};
  return core::FromStringAmong(text, kAll, value);
}

void ModelParameters::Validate(bool check_alpha) const {
  if (check_alpha) RequirePositive(alpha_rad, "the release tilt alpha", "radians");
  // A roll of π/4 or more would stand the block on a side edge rather than on a corner of its release edge.
  constexpr double kMaxReleaseRoll_rad = M_PI / 4.0;
  if (check_alpha && !(std::abs(release_roll_rad) < kMaxReleaseRoll_rad)) {
    throw InvalidArgument("the release roll must be finite and less than pi/4 rad in magnitude, got " +
                          std::to_string(release_roll_rad));
  }
  RequireFinite(lambda, "the edge-impact parameter lambda");
  RequireFinite(tau_edge, "the edge-impact parameter tau_edge");
  RequireFinite(lambda_lat, "the facet-impact parameter lambda_lat");
  RequireFinite(lambda_lon, "the facet-impact parameter lambda_lon");
}

void SimulationOptions::Validate() const {
  // More samples than this would exhaust memory long before the simulation finishes.
  constexpr double kMaxSamples = 1e8;
  if (sample_times_s.empty()) {
    RequirePositive(rate_hz, "the sample rate", "Hz");
  } else {
    // Checked on every run (a fit makes thousands, each with hundreds of times): first by one pass without
    // branches (|t| ≤ the largest double fails for NaN and ±∞, t_k ≥ t_{k−1} for NaN and a step back), which the
    // compiler vectorises; the loop that finds the bad time and builds the message runs only when it fails.
    const std::vector<double>& t = sample_times_s;
    bool all_good = std::abs(t[0]) <= std::numeric_limits<double>::max();
    for (std::size_t k = 1; k < t.size(); ++k) {
      all_good &= (std::abs(t[k]) <= std::numeric_limits<double>::max()) & (t[k] >= t[k - 1]);
    }
    for (std::size_t k = 0; !all_good && k < sample_times_s.size(); ++k) {
      if (!std::isfinite(sample_times_s[k])) RequireFinite(sample_times_s[k], "every sample time");
      if (k > 0 && sample_times_s[k] < sample_times_s[k - 1]) {
        throw InvalidArgument("sample times must be in ascending order; time " + std::to_string(k) + " (" +
                              std::to_string(sample_times_s[k]) + " s) comes before the previous one");
      }
    }
  }
  RequirePositive(t_max_s, "t_max", "seconds");
  if (sample_times_s.empty() && t_max_s * rate_hz > kMaxSamples) {
    throw InvalidArgument("t_max × rate asks for more than 1e8 samples; lower --t-max or --rate");
  }
  if (!Block::AreNeighbours(release_edge_first, release_edge_second) || release_edge_first < 1 ||
      release_edge_first > 4 || release_edge_second < 1 || release_edge_second > 4) {
    throw InvalidArgument("the release edge must be two neighbouring base vertices such as 1,2 or 3,4, got " +
                          std::to_string(release_edge_first) + "," + std::to_string(release_edge_second));
  }
  if (!std::isfinite(zeno_dt_s) || zeno_dt_s < 0.0) {
    throw InvalidArgument("zeno_dt must be a non-negative number of seconds, got " + std::to_string(zeno_dt_s));
  }
  if (!std::isfinite(rest_energy_height_m) || rest_energy_height_m < 0.0) {
    throw InvalidArgument("rest_energy_height must be a non-negative number of metres, got " +
                          std::to_string(rest_energy_height_m));
  }
  RequirePositive(gravity_m_s2, "gravity", "m/s²");
  // Tolerances: below 1e-15 the requested accuracy is beyond double precision.
  if (!std::isfinite(rel_tol) || rel_tol < 1e-15 || rel_tol >= 1.0) {
    throw InvalidArgument("rel_tol must lie in [1e-15, 1), got " + std::to_string(rel_tol));
  }
  RequirePositive(abs_tol, "abs_tol");
  if (!std::isfinite(event_time_tol_s) || event_time_tol_s < 1e-15 || event_time_tol_s > 1e-3) {
    throw InvalidArgument("event_time_tol must lie in [1e-15, 1e-3] s, got " + std::to_string(event_time_tol_s));
  }
  RequirePositive(max_step_s, "max_step", "seconds");
  if (max_impacts == 0) throw InvalidArgument("max_impacts must be at least 1");
  if (initial_state) {
    const InitialState& s = *initial_state;
    if (!(s.contact.is_vertex() || s.contact.is_edge()) || s.contact.first < 1 || s.contact.first > 4 ||
        s.contact.second < 0 || s.contact.second > 4 ||
        (s.contact.is_edge() && !Block::AreNeighbours(s.contact.first, s.contact.second))) {
      throw InvalidArgument("the initial contact must be a base vertex V1..V4 or a base edge such as V1V2");
    }
    if (!s.q_WB.coeffs().allFinite() || std::abs(s.q_WB.norm() - 1.0) > 1e-6) {
      throw InvalidArgument("the initial attitude q_WB must be a finite unit quaternion");
    }
    if (!s.w_B.allFinite()) throw InvalidArgument("the initial angular velocity w_B must be finite");
  }
}

}  // namespace rockfit::core
