#include "rockfit/app/impact_evaluation.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include <fmt/format.h>

#include "rockfit/app/json_values.hpp"
#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::app {

const ImpactArgumentNames kProgramImpactNames{"--pivot", "--landing", "--tilt", "--lambda", "--tau", "--lambda-lat",
                                              "--lambda-lon"};
const ImpactArgumentNames kPythonImpactNames{"pivot", "landing", "tilt", "lambda_", "tau", "lambda_lat", "lambda_lon"};

namespace {

// The warnings about ω⁻ (not falling, not along the pivot edge) compare velocities with this fraction of |ω⁻|·L.
// Dimensionless; only decides whether a hint is given.
constexpr double kWarningRelTol = 1e-9;

// The option's name and what it stands for, for the shared checks (rockfit/core/checks.hpp).
std::string Described(const std::string& name, const char* what) { return fmt::format("{} ({})", name, what); }

void RequireVertex(int k, const std::string& name) {
  if (k < 1 || k > 4) {
    throw InvalidArgument(fmt::format("{} must be a base vertex 1, 2, 3 or 4 (V1=(−b1,−b2), V2=(−b1,+b2), "
                                      "V3=(+b1,+b2), V4=(+b1,−b2)), got {}", name, k));
  }
}

nlohmann::json OkOrNull(bool ok, nlohmann::json value) { return ok ? std::move(value) : nlohmann::json(nullptr); }

// Keys shared by both kinds; ω⁺ and energies after are null unless the status is ok.
nlohmann::json OutcomeJson(const char* kind, const ImpactEvaluation& result) {
  const core::ImpactOutcome& out = result.outcome;
  const bool ok = out.status == core::ImpactStatus::kOk;
  nlohmann::json j;
  j["kind"] = kind;
  j["status"] = core::ToString(out.status);
  j["contact_before"] = out.contact_before.ToString();
  j["omega_minus"] = ToJson(out.w_minus_W);
  j["omega_plus"] = OkOrNull(ok, ToJson(out.w_plus_W));
  j["omega_plus_body"] = OkOrNull(ok, ToJson(out.w_plus_B));
  j["tau"] = OkOrNull(ok, out.tau);
  j["contact_after"] = ContactAfterJson(out);
  j["energy_before"] = out.energy_before_J;
  j["energy_after"] = OkOrNull(ok, out.energy_after_J);
  j["delta_energy"] = OkOrNull(ok, out.delta_energy_J);
  j["within_bounds"] = out.within_geometric_bounds;
  j["energy_nonincreasing"] = OkOrNull(ok, out.energy_nonincreasing);
  j["units"] = {{"omega", "rad/s"}, {"tau", "N*m*s"}, {"energy", "J"}, {"tilt", "rad"}};
  j["warnings"] = result.warnings;
  return j;
}

}  // namespace

ImpactEvaluation EvaluateEdgeImpact(const core::Block& block, const EdgeImpactArgs& a, const ImpactArgumentNames& n) {
  RequireVertex(a.pivot, n.pivot);
  RequireVertex(a.landing, n.landing);
  if (!core::Block::AreNeighbours(a.pivot, a.landing)) {
    throw InvalidArgument(fmt::format("{} must be a neighbour of {} V{} (V{} or V{}), got {}", n.landing, n.pivot,
                                      a.pivot, core::Block::WrapVertex(a.pivot - 1),
                                      core::Block::WrapVertex(a.pivot + 1), a.landing));
  }
  RequireFinite(a.tilt_rad, Described(n.tilt, "rad, in [0, π/2]"));
  if (a.tilt_rad < 0.0 || a.tilt_rad > core::kMaxEdgeImpactTilt) {
    throw InvalidArgument(fmt::format("{} must be in [0, π/2] rad (0: flat base), got {}", n.tilt, a.tilt_rad));
  }
  RequireFinite(a.lambda, Described(n.lambda, "position of the resultant along the edge, (19)"));
  RequireFinite(a.tau, Described(n.tau, "N·m·s"));

  const Eigen::Matrix3d R_WB = core::EdgeImpactAttitude(block, a.pivot, a.landing, a.tilt_rad);
  ImpactEvaluation result;
  result.outcome = core::EdgeImpact(block, R_WB, a.pivot, a.landing, a.w_minus_W, {a.lambda, a.tau});
  result.singular_lambdas = core::EdgeImpactSingularLambdas(block, R_WB, a.pivot, a.landing);
  const Eigen::Vector3d p_ba_W = R_WB * (block.p_BV_B(a.landing) - block.p_BV_B(a.pivot));
  if (a.w_minus_W.cross(p_ba_W).z() >= -kWarningRelTol * a.w_minus_W.norm() * p_ba_W.norm()) {
    result.warnings.push_back(fmt::format("with this ω⁻ the landing vertex V{} does not move down (rotation about "
                                          "V{}), so the edge does not hit the ground",
                                          a.landing, a.pivot));
  }
  return result;
}

ImpactEvaluation EvaluateFacetImpact(const core::Block& block, const FacetImpactArgs& a, const ImpactArgumentNames& n) {
  RequireFinite(a.lambda_lat, Described(n.lambda_lat, "(21)"));
  RequireFinite(a.lambda_lon, Described(n.lambda_lon, "(21)"));
  if (a.tau) RequireFinite(*a.tau, Described(n.tau, "N·m·s"));
  core::FacetImpactParameters params;
  params.lambda_lat = a.lambda_lat;
  params.lambda_lon = a.lambda_lon;
  params.tau_rule = a.tau ? core::FacetTauRule::kFixed : core::FacetTauRule::kNoSpin;
  params.tau = a.tau.value_or(0.0);
  const int b = a.b;
  const Eigen::Vector3d& w_minus_B = a.w_minus_B;
  ImpactEvaluation result;
  result.outcome = core::FacetImpact(block, b, w_minus_B, params);

  const Eigen::Vector3d falling_B = (block.p_BV_B(b) - block.p_BV_B(b - 1)).normalized();
  const double velocity_scale = w_minus_B.norm() * (block.p_BC_B() - block.p_BV_B(b)).norm();
  if (w_minus_B.cross(block.p_BV_B(b + 1) - block.p_BV_B(b)).z() >= -kWarningRelTol * velocity_scale) {
    result.warnings.push_back(fmt::format(
        "with this ω⁻ the base does not fall onto the ground about V{}V{}; in rockfit's frame a falling block has "
        "ω⁻ = +ω·({:+.3g}, {:+.3g}, {:+.3g}), ω > 0 (the paper's Fig. 11 writes [0, −1, 0] for V1V2 in its own axes)",
        core::Block::WrapVertex(b - 1), b, falling_B.x(), falling_B.y(), falling_B.z()));
  }
  if ((w_minus_B - w_minus_B.dot(falling_B) * falling_B).norm() > kWarningRelTol * w_minus_B.norm()) {
    result.warnings.push_back(fmt::format("ω⁻ is not along the pivot edge V{}V{}, as rocking about that edge "
                                          "requires; the part off the edge is mapped as given, with V{} as pre-impact "
                                          "pivot",
                                          core::Block::WrapVertex(b - 1), b, b));
  }
  return result;
}

nlohmann::json ContactAfterJson(const core::ImpactOutcome& out) {
  if (out.status != core::ImpactStatus::kOk) return nullptr;
  return out.contact_after.first == 0 ? std::string("facet") : out.contact_after.ToString();
}

nlohmann::json EdgeImpactJson(const EdgeImpactArgs& a, const ImpactEvaluation& result) {
  nlohmann::json j = OutcomeJson("edge", result);
  j["pivot"] = a.pivot;
  j["landing"] = a.landing;
  j["tilt"] = a.tilt_rad;
  j["lambda"] = a.lambda;
  j["singular_lambdas"] = result.singular_lambdas;
  return j;
}

nlohmann::json FacetImpactJson(const FacetImpactArgs& a, const ImpactEvaluation& result) {
  const core::ImpactOutcome& out = result.outcome;
  nlohmann::json j = OutcomeJson("facet", result);
  const core::FacetTauRule rule = a.tau ? core::FacetTauRule::kFixed : core::FacetTauRule::kNoSpin;
  j["pivot_edge"] = out.contact_before.ToString();
  j["b"] = a.b;
  j["lambda_lat"] = a.lambda_lat;
  j["lambda_lon"] = a.lambda_lon;
  j["tau_rule"] = core::ToString(rule);
  if (a.tau) j["tau"] = *a.tau;  // the τ used, whatever the status
  nlohmann::json candidates = nlohmann::json::array();
  for (const core::FacetCandidate& c : out.candidates) {
    const bool solved = c.status == core::ImpactStatus::kOk;
    candidates.push_back({{"contact", c.contact.ToString()},
                          {"status", core::ToString(c.status)},
                          {"feasible", c.feasible},
                          {"impulse_lifts_22", OkOrNull(solved, c.impulse_lifts)},
                          {"no_penetration_23", OkOrNull(solved, c.no_penetration)},
                          {"omega_plus", OkOrNull(solved, ToJson(c.w_plus))},
                          {"tau", OkOrNull(solved, c.tau)}});
  }
  j["candidates"] = candidates;
  return j;
}

}  // namespace rockfit::app
