// `impact edge|facet` for both front ends: one impact map of the paper (Sect. 4.4–4.7) evaluated from checked
// arguments, the hints about ω⁻ that a user may have got wrong, and the JSON document of the result
// (`rockfit impact … --json`, the Record of `rockfit.edge_impact` / `rockfit.facet_impact`).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "rockfit/core/block.hpp"
#include "rockfit/core/impact_maps.hpp"

namespace rockfit::app {

// How the front end spells each argument in its messages ("--lambda-lat" or "lambda_lat").
struct ImpactArgumentNames {
  std::string pivot, landing, tilt, lambda, tau, lambda_lat, lambda_lon;
};
extern const ImpactArgumentNames kProgramImpactNames;
extern const ImpactArgumentNames kPythonImpactNames;

struct EdgeImpactArgs {
  int pivot = 0;    // V_b, 1..4
  int landing = 0;  // V_a, a neighbour of V_b
  double tilt_rad = 0.0;
  Eigen::Vector3d w_minus_W = Eigen::Vector3d::Zero();
  double lambda = 1.0;
  double tau = 0.0;  // [N·m·s]
};

struct FacetImpactArgs {
  int b = 2;  // pivot edge V_{b−1}V_b
  Eigen::Vector3d w_minus_B = Eigen::Vector3d::Zero();
  double lambda_lat = 0.0;
  double lambda_lon = 1.0;
  std::optional<double> tau;  // none: the no-spin rule (24)
};

struct ImpactEvaluation {
  core::ImpactOutcome outcome;
  std::vector<double> singular_lambdas;  // edge only: the λ where (18) is singular
  std::vector<std::string> warnings;
};

// Both throw InvalidArgument naming the argument (with `names`) for a vertex, tilt or value out of range.
ImpactEvaluation EvaluateEdgeImpact(const core::Block& block, const EdgeImpactArgs& args, const ImpactArgumentNames& names);
ImpactEvaluation EvaluateFacetImpact(const core::Block& block, const FacetImpactArgs& args,
                                     const ImpactArgumentNames& names);

// "V4", "V3V4", "facet" (rest on the whole base), or null unless the status is ok.
nlohmann::json ContactAfterJson(const core::ImpactOutcome& out);
nlohmann::json EdgeImpactJson(const EdgeImpactArgs& args, const ImpactEvaluation& result);
nlohmann::json FacetImpactJson(const FacetImpactArgs& args, const ImpactEvaluation& result);

}  // namespace rockfit::app
