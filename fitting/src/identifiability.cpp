#include "rockfit/fitting/identifiability.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace rockfit::fitting {

IdentifiabilityReport CheckIdentifiability(const Objective& objective, const ParameterSet& at,
                                           const IdentifiabilityOptions& options) {
  IdentifiabilityReport report;
  report.identifiable.fill(true);
  ErrorNodes nodes;
  ModelOutput output;
  const Evaluation centre = objective.EvaluateDetailed(at, &nodes, &output);
  if (centre.feasible) {
    const double window_s = objective.t_end_s() - at.value(ParameterId::kT0);
    for (const ModelEvent& e : output.events) {
      if (e.t_s > window_s) break;
      if (e.kind == core::ImpactKind::kEdge) ++report.edge_impacts_in_window;
      if (e.kind == core::ImpactKind::kFacet) ++report.facet_impacts_in_window;
    }
  }
  const double tolerance = options.relative_tolerance * std::abs(centre.epsilon_rad_s);
  for (ParameterId id : objective.free_ids()) {
    const std::size_t k = static_cast<std::size_t>(id);
    const Parameter& p = objective.parameters()[id];
    double change = 0.0;
    for (double direction : {+1.0, -1.0}) {
      ParameterSet probe = at;
      probe[id].value = std::clamp(at.value(id) + direction * options.probe_step[k], p.lower, p.upper);
      if (probe[id].value == at.value(id)) continue;
      const Evaluation e = objective.Evaluate(probe);
      // A probe where the model fails shows that the parameter matters.
      change = std::max(change, e.feasible == centre.feasible ? std::abs(e.epsilon_rad_s - centre.epsilon_rad_s)
                                                              : std::abs(objective.options().failure_penalty_rad_s));
    }
    report.max_abs_change_rad_s[k] = change;
    if (change > tolerance) continue;
    report.identifiable[k] = false;
    std::string why;
    if (id == ParameterId::kLambda && report.edge_impacts_in_window == 0) {
      why = "no edge impact happened in the fitting window";
    } else if ((id == ParameterId::kLambdaLat || id == ParameterId::kLambdaLon) && report.facet_impacts_in_window == 0) {
      why = "no facet impact happened in the fitting window";
    } else {
      why = "the model does not depend on it here";
    }
    report.reason[k] = fmt::format("{} is not identifiable: {} (ε changes by {:.3g} rad/s when it moves by ±{:g} {})",
                                   Name(id), why, change, options.probe_step[k], Unit(id));
  }
  return report;
}

}  // namespace rockfit::fitting
