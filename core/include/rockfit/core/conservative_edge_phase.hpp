// Rocking about one base edge under gravity alone, in closed form (docs/design.md §4, "Analytic edge phases").
//
// J_e ψ̈ = −m g R sin(θ_c − ψ) (edge_dynamics.hpp) is a conservative 1-DOF motion. With φ = θ_c − ψ the angle of
// the COM from the vertical through the edge, K = 2 m g R / J_e and φ_m the angle at the apex (ψ̇ = 0), energy gives
//   ψ̇² = K (cos φ_m − cos φ) = 2K (x² − k²),   x = sin(φ/2),  k = sin(φ_m/2).
// With ω = √(K/2), k' = √(1 − k²), m = k'² and s the time since the apex, the motion is
//   sin(φ/2) = k / dn(ω s | m),   ψ̇ = −2 ω k k' sn(ω s | m) / dn(ω s | m),
// and the time from the apex to the angle φ is an incomplete elliptic integral of the first kind, in Carlson's
// symmetric form (no cancellation anywhere, exact to round-off):
//   |s| = (1/ω) √(x² − k²) R_F(k² (1 − x²), k² k'², x² k'²).
// A swing is bounded (it returns to ψ = 0 without passing θ_c) when the energy leaves k > 0.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "rockfit/core/edge_dynamics.hpp"

namespace rockfit::core {

// sn, cn, dn of one argument and parameter.
struct JacobiTriple {
  double sn = 0.0;
  double cn = 1.0;
  double dn = 1.0;
};

// The ground force on the edge per unit mass at one point of a swing [m/s²] (the closed form of
// EdgeDynamics::Force for this motion).
struct EdgeLoadPerMass {
  double normal_m_s2 = 0.0;
  double tangential_m_s2 = 0.0;
};

class ConservativeEdgePhase {
 public:
  // The swing about an edge with K = 2 m g R / J_e [1/s²] and θ_c ∈ (0, π/2) from (ψ0, ψ̇0) at time 0. Empty unless it
  // is a bounded swing that has not yet landed: 0 ≤ ψ0 < θ_c, not on the ground moving down (ψ0 = 0, ψ̇0 ≤ 0), and
  // an apex at least kMinApexK2 away from the separatrix (k² above it).
  static std::optional<ConservativeEdgePhase> Make(double K_1_s2, double theta_c_rad, double psi0_rad,
                                                   double psi_dot0_rad_s);

  // Below this k² = sin²(φ_m/2) (the apex within ~2e-4 rad of θ_c) the swing counts as too close to the
  // separatrix: the time to land grows like log(1/k) and the integrator (which also decides overturning) takes it.
  static constexpr double kMinApexK2 = 1e-8;

  double time_to_flat_s() const { return time_to_flat_s_; }  // from the start to ψ = 0 (descending)
  double apex_time_s() const { return apex_time_s_; }          // ψ̇ = 0; negative when the start is past the apex
  double apex_tilt_rad() const { return theta_c_ - 2.0 * std::asin(k_); }
  double omega_1_s() const { return omega_; }    // ω = √(K/2): u = ω · (time since the apex)
  double parameter_m() const { return m_; }      // m = k'² of the Jacobi functions
  // The state when the base lands: (0, −|ψ̇|), the landing rate from energy.
  EdgeDynamics::State AtFlat() const { return EdgeDynamics::State(0.0, -landing_rate_rad_s_); }
  // The exact state at time t_s after the start (one Jacobi elliptic evaluation).
  EdgeDynamics::State At(double t_s) const { return FromJacobi(JacobiAt(t_s)); }

  // sn, cn, dn at t_s after the start: from the start's triple by the addition theorem and the Maclaurin series of
  // ω·t_s where that is below kSeriesMaxArg (no library call), else by GSL.
  JacobiTriple JacobiAt(double t_s) const;
  // sn, cn, dn of ω·dt: the step of Advance for samples dt apart.
  JacobiTriple JacobiStep(double dt_s) const { return JacobiOf(omega_ * dt_s); }
  // The addition theorem: the Jacobi triple dt later, from the one now and JacobiStep(dt) (a few flops).
  JacobiTriple Advance(const JacobiTriple& now, const JacobiTriple& step) const {
    const double inv = 1.0 / (1.0 - m_ * now.sn * now.sn * step.sn * step.sn);
    return {(now.sn * step.cn * step.dn + step.sn * now.cn * now.dn) * inv,
            (now.cn * step.cn - now.sn * step.sn * now.dn * step.dn) * inv,
            (now.dn * step.dn - m_ * now.sn * step.sn * now.cn * step.cn) * inv};
  }
  // sn, cn, dn at the start of the swing, from its state alone (exact to round-off, no elliptic function call).
  const JacobiTriple& start_jacobi() const { return start_; }
  // sn, cn, dn of u with parameter m = k'² by their Maclaurin series, for |u| ≤ kSeriesMaxArg.
  JacobiTriple JacobiSeries(double u) const;
  // Below this |u| the Maclaurin series of sn, cn, dn through u⁹ (sn) and u⁸ (cn, dn) is exact to round-off for
  // every m ∈ [0, 1]: their coefficients grow with m, and at m = 1 (tanh, sech) the first term left out is
  // ≤ 0.014 u¹⁰ relative, below 2⁻⁵³ for u ≤ 0.035. At 256 Hz that covers ω ≤ 8.9 1/s (rectangular blocks with
  // R ≥ 0.09 m); larger arguments go to GSL.
  static constexpr double kSeriesMaxArg = 0.035;
  EdgeDynamics::State FromJacobi(const JacobiTriple& j) const { return {TiltFromJacobi(j), RateFromJacobi(j)}; }
  double TiltFromJacobi(const JacobiTriple& j) const { return theta_c_ - 2.0 * std::asin(k_ / j.dn); }
  double RateFromJacobi(const JacobiTriple& j) const { return rate_scale_ * j.sn / j.dn; }
  // (cos(ψ/2), sin(ψ/2)) without trigonometric calls: ψ/2 = θ_c/2 − φ/2 with sin(φ/2) = k/dn.
  Eigen::Vector2d HalfTiltCosSinFromJacobi(const JacobiTriple& j) const {
    const double x = k_ / j.dn;
    const double c = std::sqrt((j.dn - k_) * (j.dn + k_)) / j.dn;
    return {cos_half_theta_c_ * c + sin_half_theta_c_ * x, sin_half_theta_c_ * c - cos_half_theta_c_ * x};
  }

  // The ground force per unit mass where the COM is at angle φ (cos φ = cos_phi) from the vertical, R the arm [m],
  // g [m/s²]: N = g − (K R/2) sin²φ − K R cos φ (cos φ_m − cos φ), |F_t| = K R sin φ |1.5 cos φ − cos φ_m|.
  EdgeLoadPerMass LoadPerMass(double cos_phi, double arm_m, double gravity_m_s2) const;
  double cos_apex_angle() const { return 1.0 - 2.0 * k_ * k_; }  // cos φ_m

 private:
  ConservativeEdgePhase() = default;
  JacobiTriple JacobiOf(double u) const;
  // Time from the apex to the angle φ with sin(φ/2) = x, cos(φ/2) = c, and x² − k² given without cancellation.
  double TimeFromApex(double x, double c, double x2_minus_k2) const;

  double theta_c_ = 0.0;
  double sin_half_theta_c_ = 0.0;
  double cos_half_theta_c_ = 1.0;
  double omega_ = 0.0;    // √(K/2) [1/s]
  double k_ = 0.0;        // sin(φ_m/2)
  double k_prime_ = 0.0;  // cos(φ_m/2)
  double m_ = 0.0;        // k'²
  double K_ = 0.0;
  double apex_time_s_ = 0.0;
  double time_to_flat_s_ = 0.0;
  double landing_rate_rad_s_ = 0.0;
  double rate_scale_ = 0.0;  // −2 ω k k' [rad/s]: ψ̇ = rate_scale_ · sn/dn
  JacobiTriple start_;       // at u = −ω · apex_time_s_
  // The Maclaurin coefficients (in u²) of sn/u, cn and dn for this m, from the u² term on.
  std::array<double, 4> sn_series_{};
  std::array<double, 4> cn_series_{};
  std::array<double, 4> dn_series_{};
};

// States of a swing at increasing times: where consecutive times are evenly spaced (to the round-off of the times),
// by the addition theorem from the previous one; exactly at the first time, every kExactEvery samples and wherever
// the spacing changes, so that round-off cannot accumulate.
class SwingSamples {
 public:
  static constexpr int kExactEvery = 64;
  // Two spacings count as one when they differ by at most this many units of round-off of the time.
  static constexpr double kSameSpacingUlps = 8.0;
  explicit SwingSamples(const ConservativeEdgePhase& phase) : phase_(phase) {}
  // sn, cn, dn at t_s (after the time of the previous call).
  JacobiTriple At(double t_s) {
    const double dt = t_s - t_previous_s_;
    const double round_off_s =
        kSameSpacingUlps * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_s));
    t_previous_s_ = t_s;
    if (since_exact_ >= 0 && since_exact_ < kExactEvery && dt_s_ >= 0.0 && std::abs(dt - dt_s_) <= round_off_s) {
      now_ = phase_.Advance(now_, step_);
      ++since_exact_;
      return now_;
    }
    return Restart(t_s, dt, round_off_s);
  }

 private:
  // The exact triple at t_s, and a new step when the spacing dt changed.
  JacobiTriple Restart(double t_s, double dt, double round_off_s);

  const ConservativeEdgePhase& phase_;
  double t_previous_s_ = 0.0;
  double dt_s_ = -1.0;  // the spacing of step_ (negative: none yet)
  JacobiTriple step_;
  JacobiTriple now_;
  int since_exact_ = -1;  // −1: no sample yet
};

}  // namespace rockfit::core
