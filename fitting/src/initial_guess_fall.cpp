#include "rockfit/fitting/initial_guess_fall.hpp"

#include <cmath>
#include <optional>
#include <string>

#include "rockfit/core/conservative_edge_phase.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

// Nodes beyond this many (a fall of 20 s, far past any release the fit searches) are not made.
constexpr std::size_t kMaxNodes = 200000;
// The addition theorem's round-off grows slowly with the steps: with an exact evaluation every this many nodes
// (0.1 s) the nodes stay within 1e-12 rad/s of a fine integration (tests/fitting/initial_guess_fall_test.cpp), as
// with one every 64 (core's SwingSamples), at a tenth of the elliptic-function calls.
constexpr std::size_t kExactEvery = 1000;

}  // namespace

PlanarFallTable::PlanarFallTable(const core::PlanarRocker& rocker, double alpha_rad, Nodes nodes)
    : rocker_(rocker), alpha_rad_(alpha_rad) {
  const double theta_c = rocker.critical_angle_rad;
  if (!(std::isfinite(alpha_rad) && alpha_rad > 0.0 && alpha_rad < theta_c)) {
    throw InvalidArgument("the planar fall needs a release tilt 0 < α < θ_c = " + std::to_string(theta_c) + " rad, got " +
                          std::to_string(alpha_rad));
  }
  const double K = rocker.K();
  const std::optional<core::ConservativeEdgePhase> phase =
      nodes == Nodes::kClosedForm ? core::ConservativeEdgePhase::Make(K, theta_c, alpha_rad, 0.0) : std::nullopt;
  closed_form_ = phase.has_value();
  rates_.push_back(0.0);
  if (closed_form_) {
    fall_time_s_ = phase->time_to_flat_s();
    // The nodes i·h up to the first at or after the landing (the swing's closed form continues past flat): sn, cn,
    // dn stepped by the addition theorem, exact every kExactEvery nodes.
    const core::JacobiTriple step = phase->JacobiStep(kStepS);
    core::JacobiTriple now = phase->start_jacobi();
    for (std::size_t i = 1; i < kMaxNodes; ++i) {
      const double tau = kStepS * static_cast<double>(i);
      now = i % kExactEvery == 0 ? phase->JacobiAt(tau) : phase->Advance(now, step);
      rates_.push_back(-phase->RateFromJacobi(now));  // ω = −ψ̇
      if (tau >= fall_time_s_) break;
    }
    return;
  }
  // ψ̈ = −(K/2)·sin(θ_c − ψ) from rest at α (the edge's equation of motion), by RK4 until ψ ≤ 0.
  const double half_k = 0.5 * K;
  auto accel = [&](double psi) { return -half_k * std::sin(theta_c - psi); };
  const double h = kStepS;
  double psi = alpha_rad, psi_dot = 0.0;
  while (psi > 0.0 && rates_.size() < kMaxNodes) {
    const double k1p = psi_dot, k1v = accel(psi);
    const double k2p = psi_dot + 0.5 * h * k1v, k2v = accel(psi + 0.5 * h * k1p);
    const double k3p = psi_dot + 0.5 * h * k2v, k3v = accel(psi + 0.5 * h * k2p);
    const double k4p = psi_dot + h * k3v, k4v = accel(psi + h * k3p);
    psi += h / 6.0 * (k1p + 2 * k2p + 2 * k3p + k4p);
    psi_dot += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    rates_.push_back(-psi_dot);
  }
}

double PlanarFallTable::fall_time_s() const {
  return closed_form_ ? fall_time_s_ : core::FallTime(rocker_, alpha_rad_);
}

}  // namespace rockfit::fitting
