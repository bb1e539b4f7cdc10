// One continuous segment of the hybrid simulation: integrate a mode with DOP853 until the first guard event
// or the time limit, emitting output samples from the dense output and collecting the segment diagnostics.
// Internal to the simulator.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "dop853.hpp"
#include "detail/trajectory_sampler.hpp"
#include "rockfit/core/event_location.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core::detail {

struct SegmentSettings {
  Dop853Options integrator;
  double event_time_tol_s = 1e-12;
  double t_limit_s = 0.0;
};

enum class SegmentEnd {
  kEvent,        // guard `guard` crossed zero at t_s
  kTimeLimit,    // reached t_limit_s
  kStepFailure,  // the integrator could not take a step (or the state became non-finite)
};

template <class ModeT>
struct SegmentOutcome {
  SegmentEnd end = SegmentEnd::kTimeLimit;
  int guard = -1;
  double t_s = 0.0;
  typename ModeT::State y = ModeT::State::Zero();  // state at t_s
  double next_step_hint_s = 0.0;
  long num_steps = 0;        // accepted integrator steps
  long num_evaluations = 0;  // right-hand-side evaluations
  long num_guard_evaluations = 0;  // guards evaluated on the dense output while locating events
};

// All guards of `mode` at (t, y): by its Guards() where it has one (one evaluation of what the guards share), else
// guard by guard.
template <class ModeT, class = void>
struct HasGuards : std::false_type {};
template <class ModeT>
struct HasGuards<ModeT, std::void_t<decltype(std::declval<const ModeT&>().Guards(
                            0.0, std::declval<const typename ModeT::State&>()))>> : std::true_type {};

// Modes whose AngularVelocity_B(y) is the state's components [kAngularVelocityFirst, +3).
template <class ModeT, class = void>
struct HasStateAngularVelocity : std::false_type {};
template <class ModeT>
struct HasStateAngularVelocity<ModeT, std::void_t<decltype(ModeT::kAngularVelocityFirst)>> : std::true_type {};

template <class ModeT>
std::array<GuardValue, ModeT::kNumGuards> EvaluateGuards(const ModeT& mode, double t, const typename ModeT::State& y) {
  if constexpr (HasGuards<ModeT>::value) {
    return mode.Guards(t, y);
  } else {
    std::array<GuardValue, ModeT::kNumGuards> g;
    for (int i = 0; i < ModeT::kNumGuards; ++i) g[i] = mode.Guard(i, t, y);
    return g;
  }
}

// Runs `mode` from (t_start, y_start). Guards flagged in `starts_on_surface` (vertices that have just left
// the ground) count as zero at the start, so that round-off of the impact location cannot fire them again.
template <class ModeT>
SegmentOutcome<ModeT> RunSegment(const ModeT& mode, double t_start, const typename ModeT::State& y_start,
                                 const std::array<bool, ModeT::kNumGuards>& starts_on_surface,
                                 const SegmentSettings& settings, double step_hint_s, RootPolisher& polisher,
                                 TrajectorySampler& sampler, SegmentDiagnostics* diagnostics) {
  using State = typename ModeT::State;
  constexpr int kGuards = ModeT::kNumGuards;
  const Mode mode_label = mode.mode();
  SegmentOutcome<ModeT> outcome;
  outcome.next_step_hint_s = step_hint_s;
  Dop853Options integrator_options = settings.integrator;
  // The step bound only serves the event test of modes whose guards can dip below zero and back inside a step.
  if (!ModeT::kGuardsNeedStepBound) integrator_options.max_step = std::numeric_limits<double>::infinity();
  Dop853<ModeT::kStateSize> integrator(integrator_options);

  diagnostics->t_begin_s = t_start;
  diagnostics->mode = mode_label;
  diagnostics->min_normal_force_N = std::numeric_limits<double>::infinity();
  diagnostics->max_friction_ratio = 0.0;
  const auto record_force = [&](double t, const State& y, const State& dydt) {
    const ContactForce force = mode.Load(t, y, dydt);
    diagnostics->min_normal_force_N = std::min(diagnostics->min_normal_force_N, force.normal_N);
    if (force.normal_N > 0.0) {
      diagnostics->max_friction_ratio = std::max(diagnostics->max_friction_ratio, force.tangential_N / force.normal_N);
    }
  };
  const double energy_start = mode.Energy(y_start);
  long guard_evaluations = 0;
  const auto finish = [&](SegmentEnd end, int guard, double t, const State& y) {
    outcome.end = end;
    outcome.guard = guard;
    outcome.t_s = t;
    outcome.y = y;
    outcome.num_steps = integrator.num_accepted();
    outcome.num_evaluations = integrator.num_evaluations();
    outcome.num_guard_evaluations = guard_evaluations;
    State dydt;
    mode(t, y, dydt);
    record_force(t, y, dydt);
    diagnostics->t_end_s = t;
    diagnostics->energy_drift_rel =
        energy_start != 0.0 ? std::abs(mode.Energy(y) - energy_start) / std::abs(energy_start) : 0.0;
    return outcome;
  };
  const auto emit = [&](const State& y) {
    if constexpr (ModeT::kEulerFromQuaternion) {
      sampler.Emit(mode_label, mode.AngularVelocity_B(y), [&] { return mode.SampleAttitude(y); });
    } else {
      sampler.Emit(mode_label, mode.AngularVelocity_B(y), [&] { return mode.Attitude(y); },
                   [&](const Eigen::Quaterniond& q_WB) { return mode.EulerZyx(q_WB, y); });
    }
  };

  // Guards at the start; a guard already past zero (or on zero and moving down) fires at once.
  std::array<GuardValue, kGuards> g0 = EvaluateGuards(mode, t_start, y_start);
  for (int i = 0; i < kGuards; ++i) {
    if (starts_on_surface[i]) g0[i].value = 0.0;
  }
  for (int i = 0; i < kGuards; ++i) {
    if (g0[i].value < 0.0 || (g0[i].value == 0.0 && g0[i].rate < 0.0)) return finish(SegmentEnd::kEvent, i, t_start, y_start);
  }
  while (sampler.pending() && sampler.next_time() <= t_start) emit(y_start);

  integrator.Reset(mode, t_start, y_start, step_hint_s);
  State y_dense;
  const auto interpolate = [&](double t) -> const State& {
    integrator.PrepareDense(mode);
    integrator.Interpolate(t, &y_dense);
    return y_dense;
  };

  // The sample at t in the current step: without attitudes, where ω is part of the state, only ω's three
  // components of the dense output (the same values bit for bit), else the whole state.
  const auto emit_at = [&](double t) {
    if constexpr (HasStateAngularVelocity<ModeT>::value) {
      if (!sampler.with_attitude()) {
        integrator.PrepareDense(mode);
        Eigen::Vector3d w_B;
        integrator.template InterpolateComponents<ModeT::kAngularVelocityFirst, 3>(t, &w_B);
        sampler.EmitRate(mode_label, w_B);
        return;
      }
    }
    emit(interpolate(t));
  };

  for (;;) {
    // Round-off floor of the time variable: closer to the limit than this counts as reaching it.
    const double t_floor = 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(integrator.t()));
    if (integrator.t() >= settings.t_limit_s - t_floor) {
      outcome.next_step_hint_s = integrator.suggested_step();
      return finish(SegmentEnd::kTimeLimit, -1, integrator.t(), integrator.y());
    }
    const double t_step_end =
        std::min(mode.StepLimit(integrator.t(), settings.t_limit_s), integrator.t() + ModeT::StepBound(integrator.y()));
    if (integrator.Step(mode, t_step_end) != StepStatus::kOk || !integrator.y().allFinite()) {
      const State y_last = integrator.y().allFinite() ? integrator.y() : y_start;
      return finish(SegmentEnd::kStepFailure, -1, integrator.t(), y_last);
    }
    const double t0 = integrator.t_previous();
    const double t1 = integrator.t();
    const State& y1 = integrator.y();
    const std::array<GuardValue, kGuards> g1 = EvaluateGuards(mode, t1, y1);

    double t_event = std::numeric_limits<double>::infinity();
    int fired = -1;
    for (int i = 0; i < kGuards; ++i) {
      const auto eval = [&](double t) {
        ++guard_evaluations;
        return mode.Guard(i, t, interpolate(t));
      };
      const std::optional<double> root = FindFirstDescent(eval, t0, g0[i], t1, g1[i], polisher, settings.event_time_tol_s);
      if (root && *root < t_event) {
        t_event = *root;
        fired = i;
      }
    }
    const double t_stop = fired >= 0 ? t_event : t1;
    while (sampler.pending() && sampler.next_time() < t_stop) emit_at(sampler.next_time());
    if (fired >= 0) {
      outcome.next_step_hint_s = integrator.suggested_step();
      const State y_event = t_event >= t1 ? y1 : interpolate(t_event);
      return finish(SegmentEnd::kEvent, fired, t_event, y_event);
    }
    record_force(t1, y1, integrator.dydt());
    g0 = g1;
    ModeT::Project(&integrator.mutable_y());
  }
}

}  // namespace rockfit::core::detail
