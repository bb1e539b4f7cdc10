#include "rockfit/core/facet_impact.hpp"

#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "detail/conditioned_solve.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

// One candidate post-impact vertex a: ω⁺ and τ from (18), either with the given τ or with the no-spin
// postulate (24).
// (18) with (24): the system for x = (ω⁺_x, ω⁺_y, τ), (Θ − m R_R R_a) ω⁺ − τ u_z = (Θ − m R_R R_b) ω⁻.
void NoSpinSystem(const ImpactGeometry& g, Eigen::Matrix3d* system, Eigen::Matrix3d* rhs_of_w_minus) {
  const Eigen::Matrix3d R_R = SkewOf(g.p_R, g.p_C);
  const Eigen::Matrix3d M = g.inertia_C - g.mass_kg * R_R * SkewOf(g.p_a, g.p_C);
  *rhs_of_w_minus = g.inertia_C - g.mass_kg * R_R * SkewOf(g.p_b, g.p_C);
  system->col(0) = M.col(0);
  system->col(1) = M.col(1);
  system->col(2) = -Eigen::Vector3d::UnitZ();
}

// The candidate from a precomputed operator of the no-spin rule.
FacetCandidate CandidateFromOperator(const FacetNoSpinOperators& operators, int a, const Eigen::Vector3d& w_minus) {
  FacetCandidate c;
  const Eigen::Vector3d x = operators.x_from_w_minus[a - 1] * w_minus;
  if (!operators.solvable[a - 1] || !x.allFinite()) {
    c.status = ImpactStatus::kSingular;
    return c;
  }
  c.w_plus = Eigen::Vector3d(x(0), x(1), 0.0);
  c.tau = x(2);
  return c;
}

FacetCandidate SolveCandidate(const ImpactGeometry& g, const Eigen::Vector3d& w_minus, const FacetImpactParameters& params) {
  FacetCandidate c;
  if (params.tau_rule == FacetTauRule::kFixed) {
    const MapResult map = GeneralImpactMap(g, w_minus, params.tau);  // (18)
    c.status = map.status;
    c.w_plus = map.w_plus;
    c.tau = params.tau;
    return c;
  }
  // (18) with (24) u_zᵀω⁺ = 0.
  Eigen::Matrix3d system;
  Eigen::Matrix3d rhs_of_w_minus;
  NoSpinSystem(g, &system, &rhs_of_w_minus);
  const Eigen::Vector3d rhs = rhs_of_w_minus * w_minus;
  Eigen::Vector3d x;
  if (!detail::SolveConditioned3(system, rhs, kImpactMinReciprocalCondition, &x)) {
    c.status = ImpactStatus::kSingular;
    return c;
  }
  c.w_plus = Eigen::Vector3d(x(0), x(1), 0.0);
  c.tau = x(2);
  return c;
}

// (22) and (23) for a solved candidate. v_tol is the velocity below which a vertical velocity counts as zero.
void TestFeasibility(const Block& block, const ImpactGeometry& g, const Eigen::Vector3d& v_minus, double v_tol,
                     FacetCandidate& c) {
  const Eigen::Vector3d v_plus = c.w_plus.cross(g.p_C - g.p_a);  // (12)
  c.impulse_lifts = v_plus.z() - v_minus.z() > v_tol;             // (22)
  c.no_penetration = true;
  for (int i = 1; i <= 4; ++i) {
    // (23) with the errata of docs/design.md §3: the velocity of V_i is v⁺ + ω⁺ × (r_i − r_c).
    const double v_i_up = (v_plus + c.w_plus.cross(block.p_BV_B(i) - g.p_C)).z();
    if (v_i_up < -v_tol) c.no_penetration = false;
  }
  c.feasible = c.impulse_lifts && c.no_penetration;
}

}  // namespace

const char* ToString(FacetTauRule rule) {
  switch (rule) {
    case FacetTauRule::kNoSpin: return "no-spin";
    case FacetTauRule::kFixed: return "fixed";
  }
  return "unknown";
}

bool FromString(const std::string& text, FacetTauRule* rule) {
  for (const FacetTauRule r : {FacetTauRule::kNoSpin, FacetTauRule::kFixed}) {
    if (text == ToString(r)) {
      *rule = r;
      return true;
    }
  }
  if (text != "zero") return false;
  *rule = FacetTauRule::kFixed;
  return true;
}

void FacetImpactParameters::Validate() const {
  if (!std::isfinite(lambda_lat)) throw InvalidArgument("facet impact: λ_lat must be finite, got " + std::to_string(lambda_lat));
  if (!std::isfinite(lambda_lon)) throw InvalidArgument("facet impact: λ_lon must be finite, got " + std::to_string(lambda_lon));
  if (!std::isfinite(tau)) throw InvalidArgument("facet impact: τ must be finite [N·m·s], got " + std::to_string(tau));
}

bool WithinFacetBounds(double lambda_lat, double lambda_lon) {  // (27)
  return lambda_lat >= -1.0 && lambda_lat <= 1.0 && lambda_lon >= -1.0 && lambda_lon <= 1.0;
}

Eigen::Vector3d FacetResultantPoint(const Block& block, int pivot_b, double lambda_lat, double lambda_lon) {
  const Eigen::Vector3d centroid =
      0.25 * (block.p_BV_B(1) + block.p_BV_B(2) + block.p_BV_B(3) + block.p_BV_B(4));
  return centroid + 0.5 * lambda_lon * (block.p_BV_B(pivot_b + 1) - block.p_BV_B(pivot_b)) +
         0.5 * lambda_lat * (block.p_BV_B(pivot_b) - block.p_BV_B(pivot_b - 1));  // (21)
}

namespace {

ImpactGeometry FacetGeometry(const Block& block, int b, const FacetImpactParameters& params) {
  ImpactGeometry g;
  g.mass_kg = block.mass();
  g.inertia_C = block.inertia_C_B();  // the block is flat: W and B coincide (up to a yaw)
  g.p_C = block.p_BC_B();
  g.p_b = block.p_BV_B(b);
  g.p_R = FacetResultantPoint(block, b, params.lambda_lat, params.lambda_lon);
  return g;
}

template <class CandidateFn>
ImpactOutcome FacetImpactWith(const Block& block, int pivot_b, const Eigen::Vector3d& w_minus_B,
                              const FacetImpactParameters& params, const CandidateFn& solve_candidate) {
  params.Validate();
  if (!w_minus_B.allFinite()) throw InvalidArgument("facet impact: ω⁻ must be finite");
  const int b = Block::WrapVertex(pivot_b);

  ImpactGeometry g = FacetGeometry(block, b, params);
  const Eigen::Vector3d v_minus = w_minus_B.cross(g.p_C - g.p_b);  // (11)
  // L: the distance from the COM to any base vertex.
  const double length_m = (g.p_C - g.p_b).norm();

  ImpactOutcome out;
  out.w_minus_W = w_minus_B;
  out.contact_before = Contact::Edge(b - 1, b);
  out.energy_before_J = KineticEnergyAbout(g, g.p_b, w_minus_B);
  out.within_geometric_bounds = WithinFacetBounds(params.lambda_lat, params.lambda_lon);
  out.tau = params.tau_rule == FacetTauRule::kFixed ? params.tau : 0.0;

  out.candidates.reserve(4);
  bool any_singular = false;
  for (int a = 1; a <= 4; ++a) {
    g.p_a = block.p_BV_B(a);
    FacetCandidate c = solve_candidate(g, a);
    c.contact = Contact::Vertex(a);
    if (c.status == ImpactStatus::kOk) {
      const double v_tol = kContactVelocityRelTol * (w_minus_B.norm() + c.w_plus.norm()) * length_m;
      TestFeasibility(block, g, v_minus, v_tol, c);
    } else {
      any_singular = true;
    }
    out.candidates.push_back(c);
  }

  // Decide among the feasible candidates.
  int feasible[4];
  int n_feasible = 0;
  for (int i = 0; i < 4; ++i) {
    if (out.candidates[i].feasible) feasible[n_feasible++] = i;
  }
  if (n_feasible == 0) {
    out.status = any_singular ? ImpactStatus::kSingular : ImpactStatus::kInfeasible;
    return out;
  }
  // Feasible candidates describe the same motion when their ω⁺ agree within the velocity tolerance.
  const FacetCandidate& first = out.candidates[feasible[0]];
  bool all_same = true;
  Eigen::Vector3d w_sum = Eigen::Vector3d::Zero();
  double tau_sum = 0.0;
  for (int k = 0; k < n_feasible; ++k) {
    const FacetCandidate& c = out.candidates[feasible[k]];
    const double w_tol = kContactVelocityRelTol * (w_minus_B.norm() + first.w_plus.norm());
    if ((c.w_plus - first.w_plus).norm() > w_tol) all_same = false;
    w_sum += c.w_plus;
    tau_sum += c.tau;
  }
  const Eigen::Vector3d w_plus = w_sum / n_feasible;
  const double rest_tol = kContactVelocityRelTol * w_minus_B.norm();
  if (n_feasible == 1) {
    out.contact_after = first.contact;
  } else if (all_same && w_plus.norm() <= rest_tol) {
    out.contact_after = Contact{};  // ω⁺ = 0: every vertex stays down, the block is at rest on its base
  } else if (all_same && n_feasible == 2 &&
             Block::AreNeighbours(out.candidates[feasible[0]].contact.first, out.candidates[feasible[1]].contact.first)) {
    // Both end points of an edge stay on the ground: edge contact (Sect. 4.6; λ_lat = 0 under (24)).
    out.contact_after = Contact::Edge(out.candidates[feasible[0]].contact.first, out.candidates[feasible[1]].contact.first);
  } else {
    out.status = ImpactStatus::kAmbiguous;
    return out;
  }
  out.status = ImpactStatus::kOk;
  out.w_plus_W = w_plus;
  out.w_plus_B = w_plus;
  out.tau = tau_sum / n_feasible;
  // Energy about the post-impact support: the vertex, or a point of the edge / base (all give the same
  // value because ω⁺ leaves them at rest).
  g.p_a = block.p_BV_B(first.contact.first);
  out.energy_after_J = KineticEnergyAbout(g, g.p_a, w_plus);
  out.delta_energy_J = out.energy_after_J - out.energy_before_J;  // (26)
  out.energy_nonincreasing = out.delta_energy_J <= kEnergyRelTol * out.energy_before_J;
  return out;
}

}  // namespace

ImpactOutcome FacetImpact(const Block& block, int pivot_b, const Eigen::Vector3d& w_minus_B,
                          const FacetImpactParameters& params) {
  return FacetImpactWith(block, pivot_b, w_minus_B, params,
                         [&](const ImpactGeometry& g, int /*a*/) { return SolveCandidate(g, w_minus_B, params); });
}

FacetNoSpinOperators MakeFacetNoSpinOperators(const Block& block, int pivot_b, const FacetImpactParameters& params) {
  params.Validate();
  if (params.tau_rule != FacetTauRule::kNoSpin) {
    throw InvalidArgument("facet impact operators exist for the no-spin rule (24) only");
  }
  FacetNoSpinOperators operators;
  operators.pivot_b = Block::WrapVertex(pivot_b);
  ImpactGeometry g = FacetGeometry(block, operators.pivot_b, params);
  for (int a = 1; a <= 4; ++a) {
    g.p_a = block.p_BV_B(a);
    Eigen::Matrix3d system;
    Eigen::Matrix3d rhs_of_w_minus;
    NoSpinSystem(g, &system, &rhs_of_w_minus);
    // Column by column, the conditioned solve of (18)+(24) for each unit ω⁻: the same test as for one ω⁻, made
    // once (one inverse for the three columns).
    Eigen::Matrix3d system_inv;
    bool solvable = detail::InvertConditioned3(system, kImpactMinReciprocalCondition, &system_inv);
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3 && solvable; ++k) {
      const Eigen::Vector3d column = system_inv * rhs_of_w_minus.col(k);
      solvable = column.allFinite();
      M.col(k) = column;
    }
    operators.x_from_w_minus[a - 1] = solvable ? M : Eigen::Matrix3d::Zero();
    operators.solvable[a - 1] = solvable;
  }
  return operators;
}

ImpactOutcome FacetImpact(const Block& block, const FacetNoSpinOperators& operators, const Eigen::Vector3d& w_minus_B,
                          const FacetImpactParameters& params) {
  return FacetImpactWith(block, operators.pivot_b, w_minus_B, params, [&](const ImpactGeometry& /*g*/, int a) {
    return CandidateFromOperator(operators, a, w_minus_B);
  });
}

ImpactOutcome ScaledFacetOutcome(const ImpactOutcome& unit, double r) {
  if (!(std::isfinite(r) && r > 0.0)) {
    throw InvalidArgument("facet impact: the scale of ω⁻ must be finite and positive, got " + std::to_string(r));
  }
  ImpactOutcome out;
  out.status = unit.status;
  out.w_minus_W = r * unit.w_minus_W;
  out.w_plus_W = r * unit.w_plus_W;
  out.w_plus_B = r * unit.w_plus_B;
  out.tau = r * unit.tau;
  out.contact_before = unit.contact_before;
  out.contact_after = unit.contact_after;
  const double r2 = r * r;
  out.energy_before_J = r2 * unit.energy_before_J;
  out.energy_after_J = r2 * unit.energy_after_J;
  out.delta_energy_J = r2 * unit.delta_energy_J;
  out.within_geometric_bounds = unit.within_geometric_bounds;
  out.energy_nonincreasing = unit.energy_nonincreasing;
  return out;
}

}  // namespace rockfit::core
