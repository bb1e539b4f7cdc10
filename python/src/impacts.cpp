// rockfit.edge_impact and rockfit.facet_impact: one impact map of the paper (Sect. 4.4–4.7) with the fields of
// `rockfit impact edge|facet --json`.
#include <cmath>

#include <fmt/format.h>

#include "bindings.hpp"
#include "rockfit/app/impact_evaluation.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/impact_maps.hpp"

namespace rockfit::python {
namespace {

// The Record of the program's JSON document, with arrays for the vectors.
py::object ImpactRecord(const char* name, const nlohmann::json& document) {
  py::dict d = FromJson(document);
  for (const char* key : {"omega_minus", "omega_plus", "omega_plus_body"}) {
    if (!d[key].is_none()) d[key] = Vector3Array(ToVector3(d[key], key));
  }
  if (d.contains("candidates")) {
    py::list candidates;
    for (py::handle c : d["candidates"]) {
      py::dict cd = py::reinterpret_borrow<py::dict>(c);
      if (!cd["omega_plus"].is_none()) cd["omega_plus"] = Vector3Array(ToVector3(cd["omega_plus"], "omega_plus"));
      candidates.append(MakeRecord("FacetCandidate", cd));
    }
    d["candidates"] = candidates;
  }
  return MakeRecord(name, d);
}

py::object EdgeImpact(const core::Block& block, int pivot, int landing, const py::object& omega_minus, double tilt,
                      double lambda, double tau) {
  app::EdgeImpactArgs args;
  args.pivot = pivot;
  args.landing = landing;
  args.tilt_rad = tilt;
  args.w_minus_W = ToVector3(omega_minus, "omega_minus");
  args.lambda = lambda;
  args.tau = tau;
  const app::ImpactEvaluation result = app::EvaluateEdgeImpact(block, args, app::kPythonImpactNames);
  return ImpactRecord("EdgeImpact", app::EdgeImpactJson(args, result));
}

py::object FacetImpact(const core::Block& block, const py::object& omega_minus, std::pair<int, int> pivot_edge,
                       double lambda_lat, double lambda_lon, std::optional<double> tau) {
  app::FacetImpactArgs args;
  args.b = app::ParsePivotEdge(fmt::format("{},{}", pivot_edge.first, pivot_edge.second));
  args.w_minus_B = ToVector3(omega_minus, "omega_minus");
  args.lambda_lat = lambda_lat;
  args.lambda_lon = lambda_lon;
  args.tau = tau;
  const app::ImpactEvaluation result = app::EvaluateFacetImpact(block, args, app::kPythonImpactNames);
  return ImpactRecord("FacetImpact", app::FacetImpactJson(args, result));
}

constexpr const char* kCommonFields =
    "Returns a Record with the keys of the program's JSON: kind, status ('ok', 'singular', 'infeasible',\n"
    "'ambiguous'), contact_before, contact_after ('V4', 'V3V4', 'facet' = rest on the base; None unless ok),\n"
    "omega_minus, omega_plus (W), omega_plus_body (B) [rad/s, arrays of 3; None unless ok], tau [N·m·s],\n"
    "energy_before, energy_after, delta_energy (26) [J], within_bounds, energy_nonincreasing, units, warnings.\n"
    "A status other than 'ok' is returned, not raised.";

}  // namespace

void RegisterImpacts(py::module_& m) {
  const core::EdgeImpactParameters edge;
  m.def("edge_impact", &EdgeImpact, py::arg("block"), py::kw_only(), py::arg("pivot"), py::arg("landing"),
        py::arg("omega_minus"), py::arg("tilt") = 0.0, py::arg("lambda_") = edge.lambda, py::arg("tau") = edge.tau,
        (std::string("Edge impact (19)–(20), as `rockfit impact edge --json`: the block rocks about base vertex\n"
                     "V_pivot until the base edge V_pivot V_landing hits the ground.\n\n"
                     "pivot, landing: neighbouring base vertices 1..4. omega_minus: pre-impact angular velocity in W\n"
                     "[rad/s] at the impact attitude (the block turned about that edge by tilt [rad], in [0, π/2]).\n"
                     "lambda_: λ of (19), the resultant at (r_a+r_b)/2 + λ(r_a−r_b)/2; tau: vertical angular impulse\n"
                     "[N·m·s].\n\n") +
         kCommonFields + "\nEdge only: pivot, landing, tilt, lambda, singular_lambdas (the λ where (18) is singular).")
            .c_str());
  const core::FacetImpactParameters facet;
  m.def("facet_impact", &FacetImpact, py::arg("block"), py::kw_only(), py::arg("omega_minus"),
        py::arg("pivot_edge") = std::make_pair(1, 2), py::arg("lambda_lat") = facet.lambda_lat,
        py::arg("lambda_lon") = facet.lambda_lon, py::arg("tau") = py::none(),
        (std::string("Facet impact (18)+(21), as `rockfit impact facet --json`: the flat block, rocking about the\n"
                     "base edge pivot_edge = (i, j) (neighbours, either order), lands on its base. Every base vertex is\n"
                     "a candidate post-impact contact, tested against (22)–(23).\n\n"
                     "omega_minus: pre-impact angular velocity [rad/s] (W = B; falling about V1V2 is (0, +ω, 0)).\n"
                     "lambda_lat, lambda_lon: (21). tau: None for the no-spin rule (24), or a fixed τ [N·m·s].\n\n") +
         kCommonFields +
         "\nFacet only: pivot_edge, b, lambda_lat, lambda_lon, tau_rule, candidates (Records contact, status, feasible,\n"
         "impulse_lifts_22, no_penetration_23, omega_plus, tau).")
            .c_str());
}

}  // namespace rockfit::python
