// Exact derivatives of the edge map (19)–(20) and of the no-spin facet map (18)+(21)+(24) for a given
// post-impact contact, in the body frame: what the forward sensitivities need at an impact
// (spatial_sensitivity.hpp, docs/design.md §4 "Forward sensitivities").
//
// For a given contact both maps are linear in ω⁻ and their matrices are rational in the parameters:
//   edge (18)+(19):   L ω⁺ = N ω⁻ + τ u_B,   L = Θ − m R_R R_a,  N = Θ − m R_R R_b,  u_B = R_WBᵀ e_z,
//   facet (18)+(24):  S x = N ω⁻,            x = (ω⁺_x, ω⁺_y, τ), S = [L e_x, L e_y, −e_z],
// with R_R = [p_R − p_C]× affine in λ (edge) or in (λ_lat, λ_lon) (facet, (21)). Differentiating the system,
//   ∂ω⁺/∂ω⁻ = L⁻¹N (edge) or the first two rows of S⁻¹N (facet),
//   ∂ω⁺/∂λ_k = L⁻¹ (or S⁻¹) · m [∂p_R/∂λ_k]× (R_a ω⁺ − R_b ω⁻),
// and for the edge map with τ ≠ 0 the attitude enters through u_B: a body-frame rotation δθ of the attitude
// moves u_B by u_B × δθ, so ∂ω⁺/∂δθ = τ L⁻¹ [u_B]×.
// Which contact follows an impact is decided elsewhere (EdgeImpact, FacetImpact); these derivatives hold
// while that decision does not change.
#pragma once

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/core/edge_impact.hpp"
#include "rockfit/core/facet_impact.hpp"

namespace rockfit::core {

struct ImpactMapDerivatives {
  bool ok = false;  // false: the system of the map is singular (as the map's own kSingular)
  Eigen::Vector3d w_plus_B = Eigen::Vector3d::Zero();
  Eigen::Matrix3d dw_plus_dw_minus = Eigen::Matrix3d::Zero();  // ∂ω⁺_B/∂ω⁻_B
  Eigen::Matrix3d dw_plus_dtheta = Eigen::Matrix3d::Zero();    // ∂ω⁺_B/∂δθ_B (edge map with τ ≠ 0 only)
  Eigen::Vector3d dw_plus_dlambda = Eigen::Vector3d::Zero();      // edge map: λ of (19)
  Eigen::Vector3d dw_plus_dlambda_lat = Eigen::Vector3d::Zero();  // facet map: λ_lat of (21)
  Eigen::Vector3d dw_plus_dlambda_lon = Eigen::Vector3d::Zero();  // facet map: λ_lon of (21)
};

// The edge map of a block rocking about V_`pivot` that lands on the edge to V_`landing`, with the world vertical
// up_B in B (R_WBᵀ e_z) and ω⁻ in B: ω⁺ in B as EdgeImpact gives it (the map's rotation about V_a), and its
// derivatives. Throws InvalidArgument if the vertices are not neighbours or an input is not finite.
ImpactMapDerivatives EdgeImpactDerivatives(const Block& block, const Eigen::Vector3d& up_B, int pivot, int landing,
                                           const Eigen::Vector3d& w_minus_B, const EdgeImpactParameters& params);

// The no-spin facet map of the flat block after rocking about V_{b−1}V_b (b = `pivot_b`) for the post-impact
// vertex V_`landing_a`: the candidate FacetImpact lists for that vertex, and its derivatives. Throws
// InvalidArgument unless params.tau_rule is kNoSpin, or for an input that is not finite.
ImpactMapDerivatives FacetImpactDerivatives(const Block& block, int pivot_b, int landing_a,
                                            const Eigen::Vector3d& w_minus_B, const FacetImpactParameters& params);

}  // namespace rockfit::core
