// The planar fall that the starting point fits to the samples before the first impact (initial_guess.hpp): the
// block rocks about the release edge from rest at the tilt α until its base lands flat (core/planar_rocking.hpp),
// and the gyro sees ω(τ) = −ψ̇ ≥ 0 at the time τ since the release.
//
// The phase-1 fit's model of ω is a table: nodes every kStepS from the release up to the first node at or after the
// landing (the motion continued past flat for that last node), linear between the nodes, the last node's value
// after it. The nodes come either from RK4 at kStepS (4 sines a node; the default of the starting point) or from
// the closed form of the swing (core/conservative_edge_phase.hpp: sn, cn, dn stepped by their addition theorem with
// an exact evaluation every 1000 nodes; a few flops and one division a node, no trigonometric call), exact to
// round-off. RK4's error (~h⁴) is near round-off too: the two tables agree to ~1e-12 rad/s.
#pragma once

#include <cstddef>
#include <vector>

#include "rockfit/core/planar_rocking.hpp"

namespace rockfit::fitting {

class PlanarFallTable {
 public:
  // Spacing of the nodes [s]: linear interpolation between them is within h²/8·|ω̈| of the fall, below 1e-7 rad/s
  // for the sample blocks (|ω̈| ≲ 50 rad/s³), four orders below the gyro noise (0.1 °/s).
  static constexpr double kStepS = 1e-4;

  enum class Nodes { kIntegrated, kClosedForm };

  // The fall from rest at α ∈ (0, θ_c) about the edge of `rocker`; throws InvalidArgument otherwise. Within
  // core::ConservativeEdgePhase::kMinApexK2 of the separatrix (α within ~2e-4 rad of θ_c) the closed form is not set
  // up and the nodes are integrated whatever `nodes` asks.
  PlanarFallTable(const core::PlanarRocker& rocker, double alpha_rad, Nodes nodes = Nodes::kClosedForm);

  // T(α): from the release to landing flat, exact to round-off (the closed form, or QAWS for integrated nodes).
  double fall_time_s() const;
  bool closed_form() const { return closed_form_; }  // false: the nodes were integrated
  std::size_t nodes() const { return rates_.size(); }
  double node_rate_rad_s(std::size_t i) const { return rates_[i]; }
  // The last node's time, (nodes − 1)·kStepS: the first node at or after T(α).
  double table_end_s() const { return static_cast<double>(rates_.size() - 1) * kStepS; }

  // ω(τ): 0 before the release (τ ≤ 0), linear between the nodes, the last node's value after it.
  double Rate(double tau_s) const {
    if (tau_s <= 0.0) return 0.0;
    const double u = tau_s / kStepS;
    const std::size_t i = static_cast<std::size_t>(u);
    if (i + 1 >= rates_.size()) return rates_.back();
    const double f = u - static_cast<double>(i);
    return rates_[i] + f * (rates_[i + 1] - rates_[i]);
  }

 private:
  core::PlanarRocker rocker_;
  double alpha_rad_ = 0.0;
  double fall_time_s_ = 0.0;  // of the closed form
  bool closed_form_ = true;
  std::vector<double> rates_;  // ω at the nodes i·kStepS [rad/s]
};

}  // namespace rockfit::fitting
