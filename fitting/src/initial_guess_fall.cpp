#include "rockfit/fitting/initial_guess_fall.hpp"

#include <cmath>
#include <optional>
#include <string>

#include "rockfit/core/conservative_edge_phase.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

// The slope of the fall where the rate is ω: dω/dτ = −ψ̈ = (K/2)·sin φ with φ = θ_c − ψ (the edge's equation of
// motion), sin φ from energy without a trigonometric call: ω² = K(cos φ − cos φ_0) with φ_0 = θ_c − α gives
// 1 − cos φ = a = 2 sin²(φ_0/2) + ω²/K (a sum, no cancellation near the release), sin φ = √(a(2 − a)) for φ ∈ [0, π/2].
double SlopeAtRate(double K_1_s2, double sin2_half_phi0, double rate_rad_s) {
  const double a = 2.0 * sin2_half_phi0 + rate_rad_s * rate_rad_s / K_1_s2;
  return 0.5 * K_1_s2 * std::sqrt(a * (2.0 - a));
}

}  // namespace

PlanarFallTable::PlanarFallTable(const core::PlanarRocker& rocker, double alpha_rad) {
  const double theta_c = rocker.critical_angle_rad;
  if (!(std::isfinite(alpha_rad) && alpha_rad > 0.0 && alpha_rad < theta_c)) {
    throw InvalidArgument("the planar fall needs a release tilt 0 < α < θ_c = " + std::to_string(theta_c) + " rad, got " +
                          std::to_string(alpha_rad));
  }
  const double K = rocker.K();
  const double sin_half_phi0 = std::sin(0.5 * (theta_c - alpha_rad));
  const double sin2_half_phi0 = sin_half_phi0 * sin_half_phi0;
  const std::optional<core::ConservativeEdgePhase> phase = core::ConservativeEdgePhase::Make(K, theta_c, alpha_rad, 0.0);
  closed_form_ = phase.has_value();
  spacing_s_ = closed_form_ ? kSpacingS : kIntegratorStepS;
  inverse_spacing_1_s_ = 1.0 / spacing_s_;
  fall_time_s_ = closed_form_ ? phase->time_to_flat_s() : core::FallTime(rocker, alpha_rad);
  // Nodes at i·h for i = 0 … M with M·h < T, then T.
  std::size_t interior = static_cast<std::size_t>(std::ceil(fall_time_s_ * inverse_spacing_1_s_));
  while (interior > 1 && spacing_s_ * static_cast<double>(interior - 1) >= fall_time_s_) --interior;  // round-off
  rates_.reserve(interior + 1);
  slopes_.reserve(interior + 1);
  auto add = [&](double rate) {
    rates_.push_back(rate);
    slopes_.push_back(SlopeAtRate(K, sin2_half_phi0, rate));
  };
  if (closed_form_) {
    core::SwingSamples samples(*phase);
    for (std::size_t i = 0; i < interior; ++i) {
      add(-phase->RateFromJacobi(samples.At(spacing_s_ * static_cast<double>(i))));  // ω = −ψ̇
    }
    add(-phase->AtFlat()[1]);
  } else {
    // ψ̈ = −(K/2)·sin(θ_c − ψ) from rest at α, by RK4 (the edge's equation of motion, core/planar_rocking.hpp).
    const double half_k = 0.5 * K;
    auto accel = [&](double psi) { return -half_k * std::sin(theta_c - psi); };
    const double h = spacing_s_;
    double psi = alpha_rad, psi_dot = 0.0;
    add(0.0);
    for (std::size_t i = 1; i < interior; ++i) {
      const double k1p = psi_dot, k1v = accel(psi);
      const double k2p = psi_dot + 0.5 * h * k1v, k2v = accel(psi + 0.5 * h * k1p);
      const double k3p = psi_dot + 0.5 * h * k2v, k3v = accel(psi + 0.5 * h * k2p);
      const double k4p = psi_dot + h * k3v, k4v = accel(psi + h * k3p);
      psi += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
      psi_dot += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      add(-psi_dot);
    }
    add(core::LandingRate(rocker, alpha_rad));
  }
}

FallRate PlanarFallTable::RateAndSlope(double tau_s) const {
  if (tau_s < 0.0) return {0.0, 0.0};
  if (tau_s == 0.0) return {0.0, slopes_.front()};
  if (tau_s >= fall_time_s_) return {rates_.back(), tau_s == fall_time_s_ ? slopes_.back() : 0.0};
  const Interval in = IntervalOf(tau_s);
  const double s = (tau_s - in.start_s) / in.length_s;
  const double s2 = s * s;
  // Derivatives of the Hermite basis in s, divided by the interval's length for d/dτ.
  const double d00 = 6.0 * s2 - 6.0 * s, d01 = -d00, d10 = 3.0 * s2 - 4.0 * s + 1.0, d11 = 3.0 * s2 - 2.0 * s;
  return {Rate(tau_s), (d00 * rates_[in.i] + d01 * rates_[in.i + 1]) / in.length_s + d10 * slopes_[in.i] +
                           d11 * slopes_[in.i + 1]};
}

}  // namespace rockfit::fitting
