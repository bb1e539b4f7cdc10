// Exact derivatives of the sampled angular velocity of a free 3D run (edge and vertex rocking, edge and facet
// impacts) with respect to the release tilt α, the impact parameters (λ, λ_lat, λ_lon) and the sample time
// (docs/design.md §4, "Forward sensitivities"; the planar case is planar_sensitivity.hpp).
//
// The state is the attitude R_WB and w_B. A perturbation is (δθ, δw): δθ the body-frame rotation with
// R_WB → R_WB(I + [δθ]×), δw the change of w_B, both at a fixed time. Along a phase they obey the variational
// equations of the phase's motion (vertex_dynamics.hpp, edge_dynamics.hpp):
//   Vertex(k):  δθ̇ = δw − w × δθ,
//               J_P δẇ = −δw × J_P w − w × J_P δw − m g c × (u × δθ),   u = R_WBᵀ e_z, c = p_PC_B,
//   Edge(i,j):  w = ψ̇ a_B, δθ = δψ a_B, δψ̈ = (K/2) cos(θ_c − ψ) δψ,
// integrated beside the state (DOP853). A rotation about the world vertical (a yaw) changes nothing that is
// sampled (gravity and the ground are invariant under it), so δθ is carried modulo the vertical.
// At an event at T with guard g (the height of the landing vertex, or ψ for a flat landing) the event moves by
// dT = −(∂g/∂x·δx)/ġ; the state along the moved event is Dθ = δθ⁻ + w⁻ dT, Dw⁻ = δw⁻ + ẇ⁻ dT; the impact map
// (impact_map_derivatives.hpp) gives Dw⁺ = (∂ω⁺/∂ω⁻) Dw⁻ + (∂ω⁺/∂θ) Dθ + ∂ω⁺/∂p; and the fixed-time
// derivatives after it are δθ⁺ = Dθ − w⁺ dT, δw⁺ = Dw⁺ − ẇ⁺ dT (the saltation). After an edge impact that
// leaves edge contact, ψ̇ = a·(J_a ω⁺)/J_e (EdgeDynamics::ProjectAngularVelocity) and δψ = a·Dθ.
//
// As for the planar case, the simulator decides where the run goes (its impact log gives the events, contacts
// and post-impact rates); this pass re-integrates each phase with its sensitivities from the logged events
// and checks its own ω against the simulator's samples. The derivatives hold where no event changes its kind or
// contact under a small change of the parameters (not at grazing events, nor where a threshold such as the
// rest energy is crossed).
#pragma once

#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/core/planar_sensitivity.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core {

struct SpatialSensitivityOptions {
  // The integration of the state and the variational equations (DOP853).
  double rel_tol = 1e-11;
  double abs_tol = 1e-13;
  // The computed ω must match the simulator's samples (and the maps' ω⁺ the logged ones) to this [rad/s] plus
  // this times |ω|, otherwise the run is not the motion the log describes and no derivatives are given. Above
  // the drift of two integrations at 1e-11–1e-12 over a few seconds of 3D rocking (≲ 1e-9 rad/s), far below
  // any real disagreement (another contact differs by O(1)).
  double agreement_tol_rad_s = 1e-7;
  void Validate() const;  // throws InvalidArgument
};

struct SpatialSensitivitySummary {
  bool available = false;
  std::string reason;  // why not available (empty when available)
  // One per sample of the trajectory, columns as SensitivityColumn (time, α, λ, λ_lat, λ_lon).
  std::vector<SampleSensitivity> dw_B;
  double max_disagreement_rad_s = 0.0;  // largest |ω computed here − ω of the simulator| over samples and impacts
  int edge_phases = 0;                  // phases integrated about an edge
  int vertex_phases = 0;                // phases integrated about a vertex
};

// Derivatives of trajectory.w_B (the run of Simulate(block, params, options), a free run from the release at α
// about options' release edge). Not available (with the reason) for: an initial state, a failed or overturned
// run, the fixed-τ facet rule, a facet impact that leaves edge contact, or samples
// and impacts that disagree with the phases computed here. After a rest the derivatives are zero.
SpatialSensitivitySummary SpatialSampleSensitivities(const Block& block, const ModelParameters& params,
                                                     const SimulationOptions& options, const Trajectory& trajectory,
                                                     const SpatialSensitivityOptions& sensitivity_options = {});

}  // namespace rockfit::core
