#include "rockfit/core/conservative_edge_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_mode.h>
#include <gsl/gsl_sf_ellint.h>
#include <gsl/gsl_sf_elljac.h>

#include "rockfit/core/gsl_setup.hpp"

namespace rockfit::core {
namespace {
constexpr double kHalfPi_rad = 1.57079632679489661923;
}  // namespace

std::optional<ConservativeEdgePhase> ConservativeEdgePhase::Make(double K_1_s2, double theta_c_rad, double psi0_rad,
                                                                 double psi_dot0_rad_s) {
  if (!(std::isfinite(K_1_s2) && K_1_s2 > 0.0 && std::isfinite(theta_c_rad) && theta_c_rad > 0.0 &&
        theta_c_rad < kHalfPi_rad && std::isfinite(psi0_rad) && std::isfinite(psi_dot0_rad_s))) {
    return std::nullopt;
  }
  if (!(psi0_rad >= 0.0 && psi0_rad < theta_c_rad)) return std::nullopt;
  if (psi0_rad == 0.0 && psi_dot0_rad_s <= 0.0) return std::nullopt;
  ConservativeEdgePhase phase;
  phase.theta_c_ = theta_c_rad;
  phase.K_ = K_1_s2;
  phase.omega_ = std::sqrt(0.5 * K_1_s2);
  // Energy at the start: x0² − k² = ψ̇0² / (2K).
  const double phi0 = theta_c_rad - psi0_rad;
  const double x0 = std::sin(0.5 * phi0);
  const double c0 = std::cos(0.5 * phi0);
  // A swing from the ground (after a landing, the usual case) starts at φ0 = θ_c.
  phase.sin_half_theta_c_ = psi0_rad == 0.0 ? x0 : std::sin(0.5 * theta_c_rad);
  phase.cos_half_theta_c_ = psi0_rad == 0.0 ? c0 : std::cos(0.5 * theta_c_rad);
  const double rate_term = psi_dot0_rad_s * psi_dot0_rad_s / (2.0 * K_1_s2);
  const double k2 = x0 * x0 - rate_term;
  if (!(k2 > kMinApexK2)) return std::nullopt;
  phase.k_ = std::sqrt(k2);
  phase.m_ = 1.0 - k2;
  phase.k_prime_ = std::sqrt(phase.m_);
  EnsureGslErrorHandlerOff();
  // Time between the apex and the start.
  const double tau0 = psi_dot0_rad_s == 0.0 ? 0.0 : phase.TimeFromApex(x0, c0, rate_term);
  phase.apex_time_s_ = psi_dot0_rad_s > 0.0 ? tau0 : -tau0;
  // Time from the apex to flat (φ = θ_c): x_c² − k² = (x_c² − x0²) + ψ̇0²/(2K), with
  // x_c² − x0² = sin((θ_c − φ0)/2) sin((θ_c + φ0)/2) = sin(ψ0/2) sin(θ_c − ψ0/2).
  const double flat_term =
      psi0_rad == 0.0 ? rate_term : std::sin(0.5 * psi0_rad) * std::sin(theta_c_rad - 0.5 * psi0_rad) + rate_term;
  const double tau_flat = psi0_rad == 0.0 ? tau0
                                          : phase.TimeFromApex(phase.sin_half_theta_c_, phase.cos_half_theta_c_, flat_term);
  phase.time_to_flat_s_ = phase.apex_time_s_ + tau_flat;
  phase.landing_rate_rad_s_ = psi0_rad == 0.0 ? psi_dot0_rad_s : std::sqrt(2.0 * K_1_s2 * flat_term);
  if (!(std::isfinite(phase.time_to_flat_s_) && phase.time_to_flat_s_ > 0.0)) return std::nullopt;
  phase.rate_scale_ = -2.0 * phase.omega_ * phase.k_ * phase.k_prime_;
  // The start's triple from its state: dn = k/x0; 1 − dn² = (x0² − k²)/x0² = m sn², so |sn| = √(x0² − k²)/(x0 k'),
  // with the sign opposite to ψ̇ (ψ̇ = −2ωkk' sn/dn); cn² = (dn² − k²)/m = k² cos²(φ0/2)/(x0² m), and cn > 0
  // (a bounded swing stays within |u| < K(m)).
  const double x0_k_prime = x0 * phase.k_prime_;
  const double sn_magnitude = std::sqrt(rate_term) / x0_k_prime;
  phase.start_.sn = psi_dot0_rad_s > 0.0 ? -sn_magnitude : sn_magnitude;
  phase.start_.cn = phase.k_ * c0 / x0_k_prime;
  phase.start_.dn = phase.k_ / x0;
  // Maclaurin coefficients (DLMF 22.10.1–22.10.3, extended to u⁹ and u⁸), in u² from the u² term on.
  const double m = phase.m_;
  const double m2 = m * m;
  const double m3 = m2 * m;
  phase.sn_series_ = {-(1.0 + m) / 6.0, (1.0 + 14.0 * m + m2) / 120.0, -(1.0 + 135.0 * m + 135.0 * m2 + m3) / 5040.0,
                      (1.0 + 1228.0 * m + 5478.0 * m2 + 1228.0 * m3 + m2 * m2) / 362880.0};
  phase.cn_series_ = {-0.5, (1.0 + 4.0 * m) / 24.0, -(1.0 + 44.0 * m + 16.0 * m2) / 720.0,
                      (1.0 + 408.0 * m + 912.0 * m2 + 64.0 * m3) / 40320.0};
  phase.dn_series_ = {-0.5 * m, m * (4.0 + m) / 24.0, -m * (16.0 + 44.0 * m + m2) / 720.0,
                      m * (64.0 + 912.0 * m + 408.0 * m2 + m3) / 40320.0};
  return phase;
}

double ConservativeEdgePhase::TimeFromApex(double x, double c, double x2_minus_k2) const {
  const double k2 = k_ * k_;
  const double rf = gsl_sf_ellint_RF(k2 * c * c, k2 * m_, x * x * m_, GSL_PREC_DOUBLE);
  return std::sqrt(x2_minus_k2) * rf / omega_;
}

JacobiTriple ConservativeEdgePhase::JacobiSeries(double u) const {
  const double s = u * u;
  const auto poly = [s](const std::array<double, 4>& c) {
    return 1.0 + s * (c[0] + s * (c[1] + s * (c[2] + s * c[3])));
  };
  return {u * poly(sn_series_), poly(cn_series_), poly(dn_series_)};
}

JacobiTriple ConservativeEdgePhase::JacobiOf(double u) const {
  if (std::abs(u) <= kSeriesMaxArg) return JacobiSeries(u);
  JacobiTriple j;
  gsl_sf_elljac_e(u, m_, &j.sn, &j.cn, &j.dn);
  return j;
}

JacobiTriple ConservativeEdgePhase::JacobiAt(double t_s) const {
  const double u = omega_ * t_s;
  if (std::abs(u) <= kSeriesMaxArg) return Advance(start_, JacobiSeries(u));
  JacobiTriple j;
  gsl_sf_elljac_e(omega_ * (t_s - apex_time_s_), m_, &j.sn, &j.cn, &j.dn);
  return j;
}

EdgeLoadPerMass ConservativeEdgePhase::LoadPerMass(double cos_phi, double arm_m, double gravity_m_s2) const {
  const double sin2_phi = std::max(0.0, 1.0 - cos_phi * cos_phi);
  const double cos_apex = cos_apex_angle();
  const double KR = K_ * arm_m;
  EdgeLoadPerMass load;
  load.normal_m_s2 = gravity_m_s2 - 0.5 * KR * sin2_phi - KR * cos_phi * (cos_apex - cos_phi);
  load.tangential_m_s2 = KR * std::sqrt(sin2_phi) * std::abs(1.5 * cos_phi - cos_apex);
  return load;
}

JacobiTriple SwingSamples::Restart(double t_s, double dt, double round_off_s) {
  const bool first = since_exact_ < 0;
  now_ = phase_.JacobiAt(t_s);
  since_exact_ = 0;
  // A new spacing: the step for the next sample, if it keeps it (one more evaluation only when it does).
  if (!first && std::abs(dt - dt_s_) > round_off_s) {
    dt_s_ = dt;
    step_ = phase_.JacobiStep(dt);
  }
  return now_;
}

}  // namespace rockfit::core
