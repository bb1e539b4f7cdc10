// Facet impacts (18)+(21) of Sects. 4.5–4.7: the block rocking about the base edge V_{b−1}V_b lands flat.
// With a given τ every candidate post-impact vertex is tested against (22)–(23); the unified map (default)
// takes τ from the no-spin postulate (24). The errata of docs/design.md §3 apply.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/core/impact_outcome.hpp"

namespace rockfit::core {

enum class FacetTauRule { kNoSpin, kFixed };
// "no-spin" or "fixed".
const char* ToString(FacetTauRule rule);
// The names of ToString, and "zero" for kFixed (τ = 0, the spelling of earlier command lines); false for any other.
bool FromString(const std::string& text, FacetTauRule* rule);

struct FacetImpactParameters {
  double lambda_lat = 0.0;  // (21)
  double lambda_lon = 1.0;  // (21)
  FacetTauRule tau_rule = FacetTauRule::kNoSpin;  // kNoSpin: τ from (24); kFixed: τ below
  double tau = 0.0;         // [N·m·s], used with kFixed
  // Throws InvalidArgument if λ_lat, λ_lon or τ is not finite.
  void Validate() const;
};

// The point R of (21) in B: centroid + λ_lon(r_{b+1} − r_b)/2 + λ_lat(r_b − r_{b−1})/2.
// For b = 2: (λ_lon·b1, λ_lat·b2, 0).
Eigen::Vector3d FacetResultantPoint(const Block& block, int pivot_b, double lambda_lat, double lambda_lon);

// Facet impact (18)+(21) of the flat block after rocking about the edge V_{b−1}V_b, b = `pivot_b` (any
// integer, taken cyclically). w_minus_B is in the body frame (W and B coincide up to a yaw, to which the map
// is invariant). The block falls onto the facet when ω⁻ is a positive multiple of r_b − r_{b−1}.
// kNoSpin solves (18) with (24) for (ω⁺_x, ω⁺_y, τ); kFixed uses the given τ. Every candidate vertex is
// tested against (22)–(23) and listed; the outcome is the unique feasible one (status kOk, contact V_a), two
// neighbouring feasible candidates with the same ω⁺ (the edge between them, e.g. λ_lat = 0), or all
// feasible candidates at ω⁺ = 0 (rest, empty contact). Otherwise kAmbiguous (several feasible),
// kInfeasible (none), or kSingular (none feasible and some candidate singular).
// Throws InvalidArgument if ω⁻ or a parameter is not finite.
ImpactOutcome FacetImpact(const Block& block, int pivot_b, const Eigen::Vector3d& w_minus_B,
                          const FacetImpactParameters& params);

// Under the no-spin rule (24) every candidate of (18) is linear in ω⁻: x_a = (ω⁺_x, ω⁺_y, τ) = M_a ω⁻, with M_a and
// the conditioning test of its system independent of ω⁻. A simulation computes them once per pivot edge.
struct FacetNoSpinOperators {
  int pivot_b = 0;                              // wrapped to 1..4
  std::array<Eigen::Matrix3d, 4> x_from_w_minus;  // candidate a = 1..4 at index a − 1
  std::array<bool, 4> solvable{};               // false: the candidate's system is singular
};
// Throws InvalidArgument unless params.tau_rule is kNoSpin (and for non-finite parameters).
FacetNoSpinOperators MakeFacetNoSpinOperators(const Block& block, int pivot_b, const FacetImpactParameters& params);
// FacetImpact with the candidates from `operators` (made for this block, pivot and parameters): the same outcome
// to round-off.
ImpactOutcome FacetImpact(const Block& block, const FacetNoSpinOperators& operators, const Eigen::Vector3d& w_minus_B,
                          const FacetImpactParameters& params);

// Under the no-spin rule every quantity the outcome is decided by — the candidates' ω⁺ and τ, the velocities of
// (22)–(23) and the tolerances they are compared with (proportional to |ω⁻| + |ω⁺|) — is linear in ω⁻. So the
// outcome for ω⁻ = r·e, r > 0, is that for the direction e with ω⁺ and τ times r and the energies times r²: a
// rotation about a base edge lands with ω⁻ along the edge axis, and one outcome per edge and sense of rotation
// serves every facet impact of a run. Returns `unit` (the outcome for e) scaled so, to round-off the outcome of
// FacetImpact for r·e; its candidates are left out. Throws InvalidArgument unless r is finite and positive.
ImpactOutcome ScaledFacetOutcome(const ImpactOutcome& unit, double r);

bool WithinFacetBounds(double lambda_lat, double lambda_lon);  // (27): |λ_lat| ≤ 1, |λ_lon| ≤ 1

}  // namespace rockfit::core
