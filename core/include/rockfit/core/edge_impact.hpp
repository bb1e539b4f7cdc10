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

// The λ at which Θ − m R_R R_a of the edge map is singular: the real roots, ascending, of its determinant,
// a polynomial in λ of degree ≤ 3 (R_R is affine in λ; the cubic term vanishes because R_a − R_b has
// rank 2). The roots do not depend on the attitude (the determinant is invariant under rotations).
std::vector<double> EdgeImpactSingularLambdas(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing);

bool WithinEdgeBounds(double lambda);  // (25): −1 ≤ λ ≤ 1

}  // namespace rockfit::core
