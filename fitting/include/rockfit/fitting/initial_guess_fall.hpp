// The planar fall that the starting point fits to the samples before the first impact (initial_guess.hpp): the
// block rocks about the release edge from rest at the tilt α until its base lands flat (core/planar_rocking.hpp),
// and the gyro sees ω(τ) = −ψ̇ ≥ 0 at the time τ since the release.
//
// The phase-1 fit asks for ω at some hundred sample times for each of a few thousand (t0, α), so the fall is
// tabulated once per α: nodes every kSpacingS from the closed form of the swing (core/conservative_edge_phase.hpp:
// sn, cn, dn stepped by their addition theorem, exact evaluations every 64 nodes; no integrator, no trigonometric
// call per node), each with its exact slope dω/dτ = (K/2)·sin(θ_c − ψ) from energy, and the cubic Hermite
// interpolant between them. The last node is the landing itself, at the fall time T(α) exact to round-off.
#pragma once

#include <cstddef>
#include <vector>

#include "rockfit/core/planar_rocking.hpp"

namespace rockfit::fitting {

// ω and dω/dτ of the fall at one time.
struct FallRate {
  double rate_rad_s = 0.0;
  double slope_rad_s2 = 0.0;
};

class PlanarFallTable {
 public:
  // Spacing of the nodes [s]. The Hermite interpolant's error is at most h⁴/384 · max|d⁴ω/dτ⁴|: for the sample
  // blocks ~1e-11 rad/s (5e-12 against a fine integration), eight orders below the gyro noise (0.1 °/s).
  static constexpr double kSpacingS = 1.0 / 1024.0;
  // Within core::ConservativeEdgePhase::kMinApexK2 of the separatrix (α within ~2e-4 rad of θ_c) the closed form is
  // not set up; the nodes then come from RK4 at this step (error ~h⁴, round-off level), with the same slopes.
  static constexpr double kIntegratorStepS = 1e-4;

  // The fall from rest at α ∈ (0, θ_c) about the edge of `rocker`; throws InvalidArgument otherwise.
  PlanarFallTable(const core::PlanarRocker& rocker, double alpha_rad);

  double fall_time_s() const { return fall_time_s_; }          // T(α): from the release to landing flat
  double landing_rate_rad_s() const { return rates_.back(); }  // ω at T(α)
  bool closed_form() const { return closed_form_; }            // false: the nodes were integrated
  std::size_t nodes() const { return rates_.size(); }
  double node_time_s(std::size_t i) const { return i + 1 < rates_.size() ? spacing_s_ * static_cast<double>(i) : fall_time_s_; }

  // ω(τ): 0 before the release (τ ≤ 0), the landing rate from the landing on (τ ≥ T).
  double Rate(double tau_s) const {
    if (tau_s <= 0.0) return 0.0;
    if (tau_s >= fall_time_s_) return rates_.back();
    const Interval in = IntervalOf(tau_s);
    const double s = (tau_s - in.start_s) / in.length_s;
    const double s2 = s * s, s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * rates_[in.i] + (3.0 * s2 - 2.0 * s3) * rates_[in.i + 1] +
           in.length_s * ((s3 - 2.0 * s2 + s) * slopes_[in.i] + (s3 - s2) * slopes_[in.i + 1]);
  }
  // ω(τ) and dω/dτ (at the kinks τ = 0 and τ = T, the slope inside the fall).
  FallRate RateAndSlope(double tau_s) const;

 private:
  struct Interval {
    std::size_t i = 0;  // the interval between nodes i and i + 1
    double start_s = 0.0;
    double length_s = 0.0;
  };
  // The interval holding τ ∈ (0, T): nodes every spacing_s_ up to the last before T, then T itself.
  Interval IntervalOf(double tau_s) const {
    std::size_t i = static_cast<std::size_t>(tau_s * inverse_spacing_1_s_);
    if (i + 2 > rates_.size()) i = rates_.size() - 2;  // round-off at the last interval
    const double start_s = spacing_s_ * static_cast<double>(i);
    return {i, start_s, i + 2 == rates_.size() ? fall_time_s_ - start_s : spacing_s_};
  }

  double fall_time_s_ = 0.0;
  double spacing_s_ = kSpacingS;
  double inverse_spacing_1_s_ = 1.0 / kSpacingS;
  bool closed_form_ = true;
  std::vector<double> rates_;   // ω at the nodes [rad/s]
  std::vector<double> slopes_;  // dω/dτ at the nodes [rad/s²]
};

}  // namespace rockfit::fitting
