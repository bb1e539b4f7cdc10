// Planar rocking about a base edge in closed form and by quadrature: the release phase of the experiments
// (docs/design.md §4) and the reference for the simulator's tests. Energy gives the rate at any tilt,
//   ½ J ψ̇² + m g R cos(θ_c − ψ) = m g R cos(θ_c − α)   (released from rest at tilt α),
// and the time to fall flat is the quadrature
//   T(α) = ∫₀^α dψ / √(K[cos(θ_c − α) − cos(θ_c − ψ)]),   K = 2 m g R / J,
// with R = √(d² + h²), θ_c = atan(d/h), J the inertia about the edge line (J = Θ_yy + m R² for V1V2, d = b1).
#pragma once

#include <optional>

#include "rockfit/core/block.hpp"

namespace rockfit::core {

struct PlanarRocker {
  double mass_kg = 0.0;
  double inertia_kg_m2 = 0.0;      // J about the edge line
  double arm_m = 0.0;              // R: distance from the edge to the COM
  double critical_angle_rad = 0.0; // θ_c = atan(d/h)
  double gravity_m_s2 = kStandardGravity;
  double K() const { return 2.0 * mass_kg * gravity_m_s2 * arm_m / inertia_kg_m2; }
};

// Rocking about the base edge V_iV_j (neighbours; throws InvalidArgument otherwise).
PlanarRocker PlanarRockerAboutEdge(const Block& block, int i, int j, double gravity_m_s2 = kStandardGravity);

// T(α) above, by GSL QAWS with the (α − ψ)^(−1/2) endpoint singularity taken into the weight.
// α must lie in [0, θ_c) (throws InvalidArgument); throws NumericalFailure if the quadrature fails.
double FallTime(const PlanarRocker& rocker, double alpha_rad);

// |ψ̇| on landing flat after a release from rest at α ∈ [0, θ_c]: √(K[cos(θ_c − α) − cos θ_c]).
double LandingRate(const PlanarRocker& rocker, double alpha_rad);

// The tilt at which a block leaving the flat position with |ψ̇| = rate stops (inverse of LandingRate);
// empty when the energy suffices to pass θ_c (the block overturns).
std::optional<double> AmplitudeFromLandingRate(const PlanarRocker& rocker, double rate_rad_s);

}  // namespace rockfit::core
