// The result of an edge or a facet impact: status, ω⁺ in W and B, τ, contacts, energy (26), bounds.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "rockfit/core/contact.hpp"
#include "rockfit/core/general_impact_map.hpp"

namespace rockfit::core {

// A vertex velocity counts as zero when its magnitude is below this times the velocity scale
// (|ω⁻| + |ω⁺|)·L of the impact (L a block length, see core/README.md). Used by the feasibility tests
// (22)–(23), by "same ω⁺" comparisons of facet candidates and by the contact-after rule of edge impacts.
// Dimensionless; far above round-off (~1e-15), far below any physical velocity ratio.
inline constexpr double kContactVelocityRelTol = 1e-10;
// ΔE of (26) counts as non-increasing when ΔE ≤ this × the pre-impact kinetic energy (round-off of the
// two quadratic forms). Dimensionless.
inline constexpr double kEnergyRelTol = 1e-12;

// One candidate post-impact vertex of a facet impact.
struct FacetCandidate {
  Contact contact;
  ImpactStatus status = ImpactStatus::kOk;  // kOk or kSingular
  bool feasible = false;                    // (22) and (23) hold
  Eigen::Vector3d w_plus = Eigen::Vector3d::Zero();
  double tau = 0.0;
  bool impulse_lifts = false;    // (22): u_zᵀv⁺ > u_zᵀv⁻
  bool no_penetration = false;   // (23): no base vertex moves into the ground after the impact
};

struct ImpactOutcome {
  ImpactStatus status = ImpactStatus::kOk;
  Eigen::Vector3d w_minus_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_plus_W = Eigen::Vector3d::Zero();  // zero unless status is kOk
  Eigen::Vector3d w_plus_B = Eigen::Vector3d::Zero();
  double tau = 0.0;  // the τ used [N·m·s] (zero unless status is kOk, or the given τ of a fixed-τ map)
  Contact contact_before;
  // kOk: the vertex or edge in contact after the impact; empty when a facet impact brings the block to
  // rest (ω⁺ = 0, the whole base on the ground). Empty unless status is kOk.
  Contact contact_after;
  double energy_before_J = 0.0;          // ½ω⁻ᵀ(Θ + m R_bᵀR_b)ω⁻
  double energy_after_J = 0.0;           // zero unless status is kOk
  double delta_energy_J = 0.0;           // (26); zero unless status is kOk
  bool within_geometric_bounds = false;  // (25) for edge impacts, (27) for facet impacts
  bool energy_nonincreasing = false;     // (26): ΔE ≤ 0 (within kEnergyRelTol); false unless status is kOk
  std::vector<FacetCandidate> candidates;  // facet impacts: every candidate vertex (empty for edge impacts)
};

}  // namespace rockfit::core
