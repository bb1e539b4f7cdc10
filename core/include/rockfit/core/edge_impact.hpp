// Edge impacts (19)–(20) of Sect. 4.4: a block rocking about the base vertex V_b lands on the base edge
// V_bV_a. Parameters λ (position of the resultant along the edge) and τ (vertical angular impulse).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/core/impact_outcome.hpp"

namespace rockfit::core {

struct EdgeImpactParameters {
  double lambda = 1.0;  // position of R along V_bV_a, (19)
  double tau = 0.0;     // vertical angular impulse [N·m·s]
  // Throws InvalidArgument if λ or τ is not finite.
  void Validate() const;
};

// Largest tilt accepted by EdgeImpactAttitude [rad]: beyond a quarter turn the block lies on its side.
inline constexpr double kMaxEdgeImpactTilt = 1.5707963267948966;

// R_WB of a block standing on the edge V_bV_a with the rest of its base lifted by `tilt_rad` ∈ [0, π/2]
// (rotation about that edge), yaw chosen so that the edge keeps its body direction in the ground plane.
// Tilt 0 is the flat block. For the edge V1V2 this is R_y(−tilt), the release attitude of docs/design.md §2.
// Throws InvalidArgument if pivot and landing are not neighbours or the tilt is outside [0, π/2].
Eigen::Matrix3d EdgeImpactAttitude(const Block& block, int pivot, int landing, double tilt_rad);

// Edge impact (19)–(20): rocking about V_b = `pivot` until the edge V_bV_a (a = `landing`, a neighbour of b)
// hits the ground. R_WB is the attitude at the impact, w_minus_W the pre-impact angular velocity in W.
// After the impact the block rocks about V_a if the vertical velocity of V_b is positive (beyond
// kContactVelocityRelTol·|ω⁺|·|V_aV_b|), otherwise it keeps edge contact V_aV_b. A singular (18) gives
// status kSingular. Allocation-free. Throws InvalidArgument if pivot and landing are not neighbours, if
// R_WB is not a rotation, or if ω⁻, λ or τ is not finite.
ImpactOutcome EdgeImpact(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing,
                         const Eigen::Vector3d& w_minus_W, const EdgeImpactParameters& params);

// The edge map (18)–(20) in the body frame, for one pivot, landing vertex and (λ, τ). Θ and the lever arms of V_b,
// V_a and R (19) are fixed in B, so both matrices of (18) are too: with A = Θ − m R_R R_a and N = Θ − m R_R R_b in B,
// ω⁺_B = A⁻¹N ω⁻_B + τ A⁻¹ up_B, where up_B = R_WBᵀ u_z. (18) in W is the same system turned by R_WB, so an impact
// costs two products with 3×3 matrices made once per edge of a run instead of building and solving the system in W.
struct EdgeImpactOperators {
  int pivot = 0;    // V_b, wrapped to 1..4
  int landing = 0;  // V_a, wrapped to 1..4
  EdgeImpactParameters params;
  // False: A is singular to working precision (kImpactMinReciprocalCondition, tested on A in B), and every impact
  // with these operators has status kSingular.
  bool solvable = false;
  Eigen::Matrix3d w_plus_from_w_minus_B = Eigen::Matrix3d::Zero();  // A⁻¹N
  Eigen::Matrix3d w_plus_from_up_B = Eigen::Matrix3d::Zero();       // A⁻¹ (times τ up_B)
  Eigen::Matrix3d inertia_b_B = Eigen::Matrix3d::Zero();  // Θ + m R_bᵀR_b: the kinetic energy about V_b (Sect. 4.8)
  Eigen::Matrix3d inertia_a_B = Eigen::Matrix3d::Zero();  // Θ + m R_aᵀR_a: about V_a
  Eigen::Vector3d p_ab_B = Eigen::Vector3d::Zero();       // from V_a to V_b
};
// Throws InvalidArgument if pivot and landing are not neighbours or λ or τ is not finite.
EdgeImpactOperators MakeEdgeImpactOperators(const Block& block, int pivot, int landing,
                                            const EdgeImpactParameters& params);
// EdgeImpact at attitude R_WB (a rotation: not checked here) with ω⁻ in B, from `operators`: the same outcome to
// round-off, except that the conditioning test of (18) reads A in B (the 1-norm is not invariant under rotation,
// so a matrix within a small factor of the threshold may be judged differently). Throws InvalidArgument if ω⁻ is
// not finite.
ImpactOutcome EdgeImpact(const EdgeImpactOperators& operators, const Eigen::Matrix3d& R_WB,
                         const Eigen::Vector3d& w_minus_B);

// The λ at which Θ − m R_R R_a of the edge map is singular: the real roots, ascending, of its determinant,
// a polynomial in λ of degree ≤ 3 (R_R is affine in λ; the cubic term vanishes because R_a − R_b has
// rank 2). The roots do not depend on the attitude (the determinant is invariant under rotations).
std::vector<double> EdgeImpactSingularLambdas(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing);

bool WithinEdgeBounds(double lambda);  // (25): −1 ≤ λ ≤ 1

}  // namespace rockfit::core
