#include "rockfit/core/impact_map_derivatives.hpp"

#include <Eigen/LU>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/general_impact_map.hpp"

namespace rockfit::core {
namespace {

Eigen::Matrix3d Cross(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),
       v.z(), 0.0, -v.x(),
       -v.y(), v.x(), 0.0;
  return m;
}

// The inverse of a map's system, with the maps' own conditioning test (kImpactMinReciprocalCondition).
bool ConditionedInverse(const Eigen::Matrix3d& A, Eigen::Matrix3d* A_inv) {
  const double det = A.determinant();
  if (!(det != 0.0) || !std::isfinite(det)) return false;
  *A_inv = A.inverse();
  const double norm_A = A.cwiseAbs().colwise().sum().maxCoeff();
  const double norm_A_inv = A_inv->cwiseAbs().colwise().sum().maxCoeff();
  return 1.0 / (norm_A * norm_A_inv) >= kImpactMinReciprocalCondition && A_inv->allFinite();
}

void RequireFinite(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite()) throw InvalidArgument(std::string("impact map derivatives: ") + what + " must be finite");
}

}  // namespace

ImpactMapDerivatives EdgeImpactDerivatives(const Block& block, const Eigen::Vector3d& up_B, int pivot, int landing,
                                           const Eigen::Vector3d& w_minus_B, const EdgeImpactParameters& params) {
  if (!Block::AreNeighbours(pivot, landing)) {
    throw InvalidArgument("impact map derivatives: the landing vertex of an edge impact must neighbour the pivot");
  }
  params.Validate();
  RequireFinite(up_B, "the vertical");
  RequireFinite(w_minus_B, "ω⁻");
  const double m = block.mass();
  const Eigen::Vector3d p_C = block.p_BC_B();
  const Eigen::Vector3d p_b = block.p_BV_B(pivot);
  const Eigen::Vector3d p_a = block.p_BV_B(landing);
  const Eigen::Vector3d p_R = 0.5 * (p_a + p_b) + 0.5 * params.lambda * (p_a - p_b);  // (19)
  const Eigen::Matrix3d R_R = Cross(p_R - p_C);
  const Eigen::Matrix3d R_a = Cross(p_a - p_C);  // (14)
  const Eigen::Matrix3d R_b = Cross(p_b - p_C);
  const Eigen::Matrix3d L = block.inertia_C_B() - m * R_R * R_a;
  const Eigen::Matrix3d N = block.inertia_C_B() - m * R_R * R_b;
  ImpactMapDerivatives d;
  Eigen::Matrix3d L_inv;
  if (!ConditionedInverse(L, &L_inv)) return d;
  d.w_plus_B = L_inv * (N * w_minus_B + params.tau * up_B);  // (18)
  d.dw_plus_dw_minus = L_inv * N;
  d.dw_plus_dtheta = params.tau * L_inv * Cross(up_B);
  const Eigen::Vector3d dp_R_dlambda = 0.5 * (p_a - p_b);
  d.dw_plus_dlambda = m * L_inv * Cross(dp_R_dlambda) * (R_a * d.w_plus_B - R_b * w_minus_B);
  d.ok = d.w_plus_B.allFinite();
  return d;
}

ImpactMapDerivatives FacetImpactDerivatives(const Block& block, int pivot_b, int landing_a,
                                            const Eigen::Vector3d& w_minus_B, const FacetImpactParameters& params) {
  params.Validate();
  if (params.tau_rule != FacetTauRule::kNoSpin) {
    throw InvalidArgument("impact map derivatives: the facet map's derivatives are for the no-spin rule (24)");
  }
  RequireFinite(w_minus_B, "ω⁻");
  const int b = Block::WrapVertex(pivot_b);
  const double m = block.mass();
  const Eigen::Vector3d p_C = block.p_BC_B();
  const Eigen::Vector3d p_b = block.p_BV_B(b);
  const Eigen::Vector3d p_a = block.p_BV_B(landing_a);
  const Eigen::Vector3d p_R = FacetResultantPoint(block, b, params.lambda_lat, params.lambda_lon);  // (21)
  const Eigen::Matrix3d R_R = Cross(p_R - p_C);
  const Eigen::Matrix3d R_a = Cross(p_a - p_C);
  const Eigen::Matrix3d R_b = Cross(p_b - p_C);
  const Eigen::Matrix3d L = block.inertia_C_B() - m * R_R * R_a;
  const Eigen::Matrix3d N = block.inertia_C_B() - m * R_R * R_b;
  Eigen::Matrix3d S;  // (18) with (24): the unknowns (ω⁺_x, ω⁺_y, τ)
  S.col(0) = L.col(0);
  S.col(1) = L.col(1);
  S.col(2) = -Eigen::Vector3d::UnitZ();
  ImpactMapDerivatives d;
  Eigen::Matrix3d S_inv;
  if (!ConditionedInverse(S, &S_inv)) return d;
  const Eigen::Matrix3d x_of_w_minus = S_inv * N;
  const Eigen::Vector3d x = x_of_w_minus * w_minus_B;
  d.w_plus_B = Eigen::Vector3d(x.x(), x.y(), 0.0);
  d.dw_plus_dw_minus.topRows<2>() = x_of_w_minus.topRows<2>();
  // (21): p_R moves by (r_{b+1} − r_b)/2 per unit λ_lon and by (r_b − r_{b−1})/2 per unit λ_lat.
  const Eigen::Vector3d momentum_jump = R_a * d.w_plus_B - R_b * w_minus_B;
  const Eigen::Vector3d dx_dlon = m * S_inv * Cross(0.5 * (block.p_BV_B(b + 1) - p_b)) * momentum_jump;
  const Eigen::Vector3d dx_dlat = m * S_inv * Cross(0.5 * (p_b - block.p_BV_B(b - 1))) * momentum_jump;
  d.dw_plus_dlambda_lon = Eigen::Vector3d(dx_dlon.x(), dx_dlon.y(), 0.0);
  d.dw_plus_dlambda_lat = Eigen::Vector3d(dx_dlat.x(), dx_dlat.y(), 0.0);
  d.ok = x.allFinite();
  return d;
}

}  // namespace rockfit::core
