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
  phase.sin_half_theta_c_ = std::sin(0.5 * theta_c_rad);
  phase.cos_half_theta_c_ = std::cos(0.5 * theta_c_rad);
  phase.K_ = K_1_s2;
  phase.omega_ = std::sqrt(0.5 * K_1_s2);
  // Energy at the start: x0² − k² = ψ̇0² / (2K).
  const double phi0 = theta_c_rad - psi0_rad;
  const double x0 = std::sin(0.5 * phi0);
  const double rate_term = psi_dot0_rad_s * psi_dot0_rad_s / (2.0 * K_1_s2);
  const double k2 = x0 * x0 - rate_term;
  if (!(k2 > kMinApexK2)) return std::nullopt;
  phase.k_ = std::sqrt(k2);
  phase.m_ = 1.0 - k2;
  phase.k_prime_ = std::sqrt(phase.m_);
  EnsureGslErrorHandlerOff();
  // Time between the apex and the start.
  const double tau0 = psi_dot0_rad_s == 0.0 ? 0.0 : phase.TimeFromApex(x0, std::cos(0.5 * phi0), rate_term);
  phase.apex_time_s_ = psi_dot0_rad_s > 0.0 ? tau0 : -tau0;
  // Time from the apex to flat (φ = θ_c): x_c² − k² = (x_c² − x0²) + ψ̇0²/(2K), with
  // x_c² − x0² = sin((θ_c − φ0)/2) sin((θ_c + φ0)/2) = sin(ψ0/2) sin(θ_c − ψ0/2).
  const double flat_term = std::sin(0.5 * psi0_rad) * std::sin(theta_c_rad - 0.5 * psi0_rad) + rate_term;
  const double tau_flat = psi0_rad == 0.0 ? tau0
                                          : phase.TimeFromApex(phase.sin_half_theta_c_, phase.cos_half_theta_c_, flat_term);
  phase.time_to_flat_s_ = phase.apex_time_s_ + tau_flat;
  phase.landing_rate_rad_s_ = psi0_rad == 0.0 ? psi_dot0_rad_s : std::sqrt(2.0 * K_1_s2 * flat_term);
  if (!(std::isfinite(phase.time_to_flat_s_) && phase.time_to_flat_s_ > 0.0)) return std::nullopt;
  return phase;
}

double ConservativeEdgePhase::TimeFromApex(double x, double c, double x2_minus_k2) const {
  const double k2 = k_ * k_;
  const double rf = gsl_sf_ellint_RF(k2 * c * c, k2 * m_, x * x * m_, GSL_PREC_DOUBLE);
  return std::sqrt(x2_minus_k2) * rf / omega_;
}

JacobiTriple ConservativeEdgePhase::JacobiOf(double u) const {
  JacobiTriple j;
  gsl_sf_elljac_e(u, m_, &j.sn, &j.cn, &j.dn);
  return j;
}

JacobiTriple ConservativeEdgePhase::JacobiAt(double t_s) const { return JacobiOf(omega_ * (t_s - apex_time_s_)); }

JacobiTriple ConservativeEdgePhase::Advance(const JacobiTriple& a, const JacobiTriple& b) const {
  // sn(u+v), cn(u+v), dn(u+v) from the triples of u and v (parameter m).
  const double inv = 1.0 / (1.0 - m_ * a.sn * a.sn * b.sn * b.sn);
  return {(a.sn * b.cn * b.dn + b.sn * a.cn * a.dn) * inv, (a.cn * b.cn - a.sn * b.sn * a.dn * b.dn) * inv,
          (a.dn * b.dn - m_ * a.sn * b.sn * a.cn * b.cn) * inv};
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

JacobiTriple SwingSamples::At(double t_s) {
  const double dt = t_s - t_previous_s_;
  const double round_off_s =
      kSameSpacingUlps * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_s));
  const bool first = since_exact_ < 0;
  if (!first && since_exact_ < kExactEvery && dt_s_ >= 0.0 && std::abs(dt - dt_s_) <= round_off_s) {
    now_ = phase_.Advance(now_, step_);
    ++since_exact_;
  } else {
    now_ = phase_.JacobiAt(t_s);
    since_exact_ = 0;
    // A new spacing: the step for the next sample, if it keeps it (one more evaluation only when it does).
    if (!first && std::abs(dt - dt_s_) > round_off_s) {
      dt_s_ = dt;
      step_ = phase_.JacobiStep(dt);
    }
  }
  t_previous_s_ = t_s;
  return now_;
}

}  // namespace rockfit::core
