// rockfit.edge_impact and rockfit.facet_impact: one impact map of the paper (Sect. 4.4–4.7) with the fields of
// `rockfit impact edge|facet --json`.
#include <cmath>

#include <fmt/format.h>

#include "bindings.hpp"
#include "rockfit/app/block_args.hpp"
#include "rockfit/app/json_values.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/impact_maps.hpp"

namespace rockfit::python {
namespace {

// The warnings about ω⁻ compare velocities with this fraction of |ω⁻|·L, as the program does. Dimensionless;
// only decides whether a hint is given.
constexpr double kWarningRelTol = 1e-9;

void RequireFinite(double value, const char* name, const char* what) {
  if (!std::isfinite(value)) throw InvalidArgument(fmt::format("{} must be a finite number ({})", name, what));
}

void RequireVertex(int k, const char* name) {
  if (k < 1 || k > 4) {
    throw InvalidArgument(fmt::format("{} must be a base vertex 1, 2, 3 or 4 (V1=(−b1,−b2), V2=(−b1,+b2), "
                                      "V3=(+b1,+b2), V4=(+b1,−b2)), got {}", name, k));
  }
}

py::object OkOrNone(bool ok, py::object value) { return ok ? std::move(value) : py::none(); }

// The keys both kinds share (`OutcomeJson` of the program); ω⁺ and energies after are None unless ok.
py::dict OutcomeFields(const char* kind, const core::ImpactOutcome& out) {
  const bool ok = out.status == core::ImpactStatus::kOk;
  py::dict d;
  d["kind"] = kind;
  d["status"] = core::ToString(out.status);
  d["contact_before"] = out.contact_before.ToString();
  d["omega_minus"] = Vector3Array(out.w_minus_W);
  d["omega_plus"] = OkOrNone(ok, Vector3Array(out.w_plus_W));
  d["omega_plus_body"] = OkOrNone(ok, Vector3Array(out.w_plus_B));
  d["tau"] = OkOrNone(ok, py::float_(out.tau));
  d["contact_after"] = ok ? py::object(py::str(out.contact_after.first == 0 ? std::string("facet")
                                                                            : out.contact_after.ToString()))
                          : py::none();
  d["energy_before"] = out.energy_before_J;
  d["energy_after"] = OkOrNone(ok, py::float_(out.energy_after_J));
  d["delta_energy"] = OkOrNone(ok, py::float_(out.delta_energy_J));
  d["within_bounds"] = out.within_geometric_bounds;
  d["energy_nonincreasing"] = OkOrNone(ok, py::bool_(out.energy_nonincreasing));
  d["units"] = py::dict(py::arg("omega") = "rad/s", py::arg("tau") = "N*m*s", py::arg("energy") = "J",
                        py::arg("tilt") = "rad");
  return d;
}

py::object EdgeImpact(const core::Block& block, int pivot, int landing, const py::object& omega_minus, double tilt,
                      double lambda, double tau) {
  RequireVertex(pivot, "pivot");
  RequireVertex(landing, "landing");
  if (!core::Block::AreNeighbours(pivot, landing)) {
    throw InvalidArgument(fmt::format("landing must be a neighbour of pivot V{} (V{} or V{}), got {}", pivot,
                                      core::Block::WrapVertex(pivot - 1), core::Block::WrapVertex(pivot + 1), landing));
  }
  RequireFinite(tilt, "tilt", "rad, in [0, π/2]");
  if (tilt < 0.0 || tilt > core::kMaxEdgeImpactTilt) {
    throw InvalidArgument(fmt::format("tilt must be in [0, π/2] rad (0: flat base), got {}", tilt));
  }
  RequireFinite(lambda, "lambda_", "position of the resultant along the edge, (19)");
  RequireFinite(tau, "tau", "N·m·s");
  const Eigen::Vector3d w_minus_W = ToVector3(omega_minus, "omega_minus");

  const Eigen::Matrix3d R_WB = core::EdgeImpactAttitude(block, pivot, landing, tilt);
  const core::ImpactOutcome out = core::EdgeImpact(block, R_WB, pivot, landing, w_minus_W, {lambda, tau});
  const std::vector<double> singular = core::EdgeImpactSingularLambdas(block, R_WB, pivot, landing);
  std::vector<std::string> warnings;
  const Eigen::Vector3d p_ba_W = R_WB * (block.p_BV_B(landing) - block.p_BV_B(pivot));
  if (w_minus_W.cross(p_ba_W).z() >= -kWarningRelTol * w_minus_W.norm() * p_ba_W.norm()) {
    warnings.push_back(fmt::format("with this ω⁻ the landing vertex V{} does not move down (rotation about V{}), so "
                                   "the edge does not hit the ground",
                                   landing, pivot));
  }
  py::dict d = OutcomeFields("edge", out);
  d["pivot"] = pivot;
  d["landing"] = landing;
  d["tilt"] = tilt;
  d["lambda"] = lambda;
  d["singular_lambdas"] = singular;
  d["warnings"] = warnings;
  return MakeRecord("EdgeImpact", d);
}

py::object FacetImpact(const core::Block& block, const py::object& omega_minus, std::pair<int, int> pivot_edge,
                       double lambda_lat, double lambda_lon, std::optional<double> tau) {
  const int b = app::ParsePivotEdge(fmt::format("{},{}", pivot_edge.first, pivot_edge.second));
  RequireFinite(lambda_lat, "lambda_lat", "(21)");
  RequireFinite(lambda_lon, "lambda_lon", "(21)");
  if (tau) RequireFinite(*tau, "tau", "N·m·s");
  const Eigen::Vector3d w_minus_B = ToVector3(omega_minus, "omega_minus");
  core::FacetImpactParameters params;
  params.lambda_lat = lambda_lat;
  params.lambda_lon = lambda_lon;
  params.tau_rule = tau ? core::FacetTauRule::kFixed : core::FacetTauRule::kNoSpin;
  params.tau = tau.value_or(0.0);
  const core::ImpactOutcome out = core::FacetImpact(block, b, w_minus_B, params);

  std::vector<std::string> warnings;
  const Eigen::Vector3d falling_B = (block.p_BV_B(b) - block.p_BV_B(b - 1)).normalized();
  const double velocity_scale = w_minus_B.norm() * (block.p_BC_B() - block.p_BV_B(b)).norm();
  if (w_minus_B.cross(block.p_BV_B(b + 1) - block.p_BV_B(b)).z() >= -kWarningRelTol * velocity_scale) {
    warnings.push_back(fmt::format("with this ω⁻ the base does not fall onto the ground about V{}V{}; in rockfit's "
                                   "frame a falling block has ω⁻ = +ω·({:+.3g}, {:+.3g}, {:+.3g}), ω > 0 (the paper's "
                                   "Fig. 11 writes [0, −1, 0] for V1V2 in its own axes)",
                                   core::Block::WrapVertex(b - 1), b, falling_B.x(), falling_B.y(), falling_B.z()));
  }
  if ((w_minus_B - w_minus_B.dot(falling_B) * falling_B).norm() > kWarningRelTol * w_minus_B.norm()) {
    warnings.push_back(fmt::format("ω⁻ is not along the pivot edge V{}V{}, as rocking about that edge requires; the "
                                   "part off the edge is mapped as given, with V{} as pre-impact pivot",
                                   core::Block::WrapVertex(b - 1), b, b));
  }
  py::dict d = OutcomeFields("facet", out);
  d["pivot_edge"] = out.contact_before.ToString();
  d["b"] = b;
  d["lambda_lat"] = lambda_lat;
  d["lambda_lon"] = lambda_lon;
  d["tau_rule"] = core::ToString(params.tau_rule);
  if (params.tau_rule == core::FacetTauRule::kFixed) d["tau"] = params.tau;  // the τ used, whatever the status
  py::list candidates;
  for (const core::FacetCandidate& c : out.candidates) {
    const bool solved = c.status == core::ImpactStatus::kOk;
    py::dict cd;
    cd["contact"] = c.contact.ToString();
    cd["status"] = core::ToString(c.status);
    cd["feasible"] = c.feasible;
    cd["impulse_lifts_22"] = OkOrNone(solved, py::bool_(c.impulse_lifts));
    cd["no_penetration_23"] = OkOrNone(solved, py::bool_(c.no_penetration));
    cd["omega_plus"] = OkOrNone(solved, Vector3Array(c.w_plus));
    cd["tau"] = OkOrNone(solved, py::float_(c.tau));
    candidates.append(MakeRecord("FacetCandidate", cd));
  }
  d["candidates"] = candidates;
  d["warnings"] = warnings;
  return MakeRecord("FacetImpact", d);
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
