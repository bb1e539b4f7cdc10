// A free Edge segment without an integrator: the swing about the edge in closed form (conservative_edge_phase.hpp),
// its landing time exact to round-off and its samples from Jacobi elliptic functions (docs/design.md §4, "Analytic
// edge phases"). Internal to the simulator; the outcome is that of RunSegment for the same mode.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "detail/contact_modes.hpp"
#include "detail/hybrid_segment.hpp"
#include "detail/trajectory_sampler.hpp"
#include "rockfit/core/conservative_edge_phase.hpp"

namespace rockfit::core::detail {

// Interior points (evenly spaced in cos φ) at which the contact force is evaluated besides the ends and the apex.
constexpr int kSwingLoadPoints = 8;

// Runs the free Edge `mode` from (t_start, y_start) up to its landing (guard EdgeMode::kFlat) or settings.t_limit_s.
// Empty when the swing is not bounded (it may overturn or starts landing): the caller integrates it.
inline std::optional<SegmentOutcome<EdgeMode>> RunAnalyticEdgeSegment(const EdgeMode& mode, double t_start,
                                                                      const EdgeMode::State& y_start,
                                                                      const SegmentSettings& settings,
                                                                      double step_hint_s, TrajectorySampler& sampler,
                                                                      SegmentDiagnostics* diagnostics) {
  const EdgeDynamics& dynamics = mode.dynamics();
  const double theta_c = dynamics.critical_angle_rad();
  const std::optional<ConservativeEdgePhase> phase =
      ConservativeEdgePhase::Make(dynamics.swing_constant_1_s2(), theta_c, y_start[0], y_start[1]);
  if (!phase) return std::nullopt;

  SegmentOutcome<EdgeMode> outcome;
  outcome.next_step_hint_s = step_hint_s;
  const double t_land = t_start + phase->time_to_flat_s();
  const bool lands = t_land < settings.t_limit_s;
  outcome.end = lands ? SegmentEnd::kEvent : SegmentEnd::kTimeLimit;
  outcome.guard = lands ? static_cast<int>(EdgeMode::kFlat) : -1;
  outcome.t_s = lands ? t_land : settings.t_limit_s;
  outcome.y = lands ? phase->AtFlat() : phase->At(settings.t_limit_s - t_start);

  const Mode mode_label = mode.mode();
  const auto emit = [&](const EdgeMode::State& y) {
    sampler.Emit(mode_label, mode.AngularVelocity_B(y), [&] { return mode.Attitude(y); },
                 [&](const Eigen::Quaterniond& q_WB) { return mode.EulerZyx(q_WB, y); });
  };
  while (sampler.pending() && sampler.next_time() <= t_start) emit(y_start);
  // Samples strictly before the end (one at the landing instant belongs to the next segment, as in RunSegment).
  // The rate comes from sn and dn alone; the tilt (an arcsine) only when the attitude is sampled.
  const auto emit_jacobi = [&](const JacobiTriple& j) {
    const double rate = phase->RateFromJacobi(j);
    EdgeMode::State y(0.0, rate);
    sampler.Emit(
        mode_label, rate * dynamics.axis_B(),
        [&] {
          y[0] = phase->TiltFromJacobi(j);
          const Eigen::Vector2d half = phase->HalfTiltCosSinFromJacobi(j);
          const Eigen::Vector3d v = half[1] * dynamics.axis_B();
          return mode.q_yaw() * Eigen::Quaterniond(half[0], v.x(), v.y(), v.z());  // q_yaw · Tilt(ψ)
        },
        [&](const Eigen::Quaterniond& q_WB) { return mode.EulerZyx(q_WB, y); });
  };
  SwingSamples samples(*phase);
  while (sampler.pending() && sampler.next_time() < outcome.t_s) {
    emit_jacobi(samples.At(sampler.next_time() - t_start));
  }

  // Diagnostics: the force is a function of cos φ along the swing; the normal force is a convex quadratic in it
  // (minimum at cos φ_m / 3), the friction ratio is evaluated at the ends, the apex and kSwingLoadPoints between.
  diagnostics->t_begin_s = t_start;
  diagnostics->t_end_s = outcome.t_s;
  diagnostics->mode = mode_label;
  const double cos_start = std::cos(theta_c - y_start[0]);
  const double cos_end = std::cos(theta_c - outcome.y[0]);
  const double apex_t = phase->apex_time_s();
  const bool apex_inside = apex_t > 0.0 && apex_t < outcome.t_s - t_start;
  const double cos_apex = phase->cos_apex_angle();
  const double cos_lo = std::min(cos_start, cos_end);
  const double cos_hi = apex_inside ? cos_apex : std::max(cos_start, cos_end);
  const double arm = dynamics.arm_m();
  const double g = dynamics.gravity_m_s2();
  double min_normal = std::numeric_limits<double>::infinity();
  double max_ratio = 0.0;
  const auto consider = [&](double c) {
    const EdgeLoadPerMass load = phase->LoadPerMass(c, arm, g);
    min_normal = std::min(min_normal, load.normal_m_s2);
    if (load.normal_m_s2 > 0.0) max_ratio = std::max(max_ratio, load.tangential_m_s2 / load.normal_m_s2);
  };
  for (int i = 0; i <= kSwingLoadPoints + 1; ++i) {
    consider(cos_lo + (cos_hi - cos_lo) * static_cast<double>(i) / (kSwingLoadPoints + 1));
  }
  if (cos_apex / 3.0 > cos_lo && cos_apex / 3.0 < cos_hi) consider(cos_apex / 3.0);
  diagnostics->min_normal_force_N = dynamics.mass_kg() * min_normal;
  diagnostics->max_friction_ratio = max_ratio;
  const double energy_start = mode.Energy(y_start);
  diagnostics->energy_drift_rel =
      energy_start != 0.0 ? std::abs(mode.Energy(outcome.y) - energy_start) / std::abs(energy_start) : 0.0;
  return outcome;
}

}  // namespace rockfit::core::detail
