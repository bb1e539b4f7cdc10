// Exact derivatives of the sampled angular velocity of a planar free run with respect to the release tilt α, the
// impact parameters (λ, λ_lat, λ_lon) and the sample time (docs/design.md §4, "Forward sensitivities").
//
// A run released from rest about a base edge with λ_lat = 0 stays planar: swings about one base edge, and facet
// impacts that equal the planar map (6) with λ = λ_lon (design §3), ω⁺ = r ω⁻, r = (J0 − λ_lon m b²)/(J0 + λ_lon m b²).
// Along each swing the state (ψ, ψ̇) and its derivatives (δψ, δψ̇) with respect to the parameters obey
//   ψ̈ = −(K/2) sin(θ_c − ψ),   δψ̈ = (K/2) cos(θ_c − ψ) δψ        (edge_dynamics.hpp, K = 2 m g R / J_e),
// integrated together (DOP853). At the landing ψ = 0 the event time moves by dT = −δψ/ψ̇⁻, and the post-impact
// state has the saltation
//   δψ̇⁺ = −r (δψ̇⁻ + ψ̈⁻ dT) − ψ̇⁻ ∂r/∂p − ψ̈(0)·dT,    δψ⁺ = −ψ̇⁺ dT,
// (the derivative of the impact map at the moved event, carried back to the fixed time of the event). The
// derivative with respect to a sample time is ω̇ there (what a shift of the release time t0 needs).
//
// The simulator decides where the run goes (its impact log gives the landings and the rest); this computes the
// derivatives along that run and checks that its own ω agrees with the simulator's samples. It is a separate
// pass, so it costs nothing unless called.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core {

// Columns of one sample's derivative matrix ∂w_B/∂(·) [rad/s per unit of the parameter].
enum class SensitivityColumn : int { kTime = 0, kAlpha, kLambda, kLambdaLat, kLambdaLon };
inline constexpr int kNumSensitivityColumns = 5;
using SampleSensitivity = Eigen::Matrix<double, 3, kNumSensitivityColumns>;

struct PlanarSensitivityOptions {
  // The integration of the variational equations (DOP853).
  double rel_tol = 1e-10;
  double abs_tol = 1e-12;
  // The computed ω must match the simulator's samples to this [rad/s] (plus this times |ω|), otherwise the run
  // was not the planar motion this describes and no derivatives are given. Well above the 1e-12 tolerances of
  // both integrations, well below any real disagreement (a swing about another edge differs by O(1)).
  double agreement_tol_rad_s = 1e-8;
  void Validate() const;  // throws InvalidArgument
};

struct PlanarSensitivitySummary {
  bool available = false;
  std::string reason;  // why not available (empty when available)
  // One per sample of the trajectory. Columns as SensitivityColumn. λ (edge impacts) does not enter a planar
  // run: its column is 0. λ_lat at 0 is where the post-impact vertex changes (V_{b+2} for λ_lat > 0, V_{b+1}
  // below): the one-sided derivatives differ, and its column is NaN.
  std::vector<SampleSensitivity> dw_B;
  double max_disagreement_rad_s = 0.0;  // largest |ω computed here − ω of the simulator| over the samples
  int swings = 0;                       // swings integrated (the release swing and one per facet impact)
};

// Derivatives of trajectory.w_B (the run of Simulate(block, params, options), a free run from the release at α
// about options' release edge) at its samples. Not available (with the reason) for runs that are not planar:
// λ_lat ≠ 0, an initial state, an impact other than a facet impact or the rest after one, a facet map with
// r ≤ 0 (λ_lon at or beyond J0/(m b²)), or samples that disagree with the swings computed here.
PlanarSensitivitySummary PlanarSampleSensitivities(const Block& block, const ModelParameters& params,
                                                   const SimulationOptions& options, const Trajectory& trajectory,
                                                   const PlanarSensitivityOptions& sensitivity_options = {});

}  // namespace rockfit::core
