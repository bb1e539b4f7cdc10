#include "rockfit/fitting/prefix_screen.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {
namespace {

// A point is screened out only when its bound exceeds the best ε by more than this (relative): the bound and the
// full run agree to the integrator's tolerance at the prefix's last node (the run that stops there clips its last
// step), and that must not decide a scan.
constexpr double kScreenMarginRelative = 1e-7;

}  // namespace

PrefixScreen::PrefixScreen(const Objective& window, double prefix_fraction)
    : window_(&window), prefix_fraction_(prefix_fraction) {
  if (!(prefix_fraction >= 0.0 && prefix_fraction < 1.0)) {
    throw InvalidArgument(fmt::format("prefix screen: the prefix fraction must lie in [0, 1), got {}", prefix_fraction));
  }
}

PrefixBound PrefixScreen::Bound(const ParameterSet& values) const {
  PrefixBound trivial;  // no prefix shorter than the window: nothing is known without the full run
  trivial.feasible = true;
  if (!enabled()) return trivial;
  const MeasuredSignal& signal = window_->signal();
  const double t0_s = values.value(ParameterId::kT0);
  const double t_end_s = window_->t_end_s();
  ErrorNodes full;
  if (!BuildErrorNodes(signal, t0_s, t_end_s, &full) || !(full.weighted_duration_s() > 0.0)) return trivial;
  // The prefix ends at a sample time strictly inside the window.
  const double t_wanted_s = t0_s + prefix_fraction_ * (t_end_s - t0_s);
  const auto it = std::lower_bound(signal.t_s.begin(), signal.t_s.end(), t_wanted_s);
  if (it == signal.t_s.end() || !(*it > t0_s) || !(*it < t_end_s)) return trivial;
  ErrorNodes prefix_nodes;
  if (!BuildErrorNodes(signal, t0_s, *it, &prefix_nodes) || !(prefix_nodes.weighted_duration_s() > 0.0)) return trivial;
  const Evaluation e = window_->WithWindowEnd(*it).Evaluate(values);
  PrefixBound bound;
  bound.feasible = e.feasible;
  if (!e.feasible) return bound;
  bound.epsilon_lower_rad_s = e.epsilon_rad_s * prefix_nodes.weighted_duration_s() / full.weighted_duration_s();
  return bound;
}

bool PrefixScreen::CannotBeat(const ParameterSet& values, double best_epsilon_rad_s) const {
  return CannotBeatWithBound(Bound(values), best_epsilon_rad_s);
}

bool PrefixScreen::CannotBeatWithBound(const PrefixBound& bound, double best_epsilon_rad_s) {
  if (!bound.feasible) return true;
  return bound.epsilon_lower_rad_s > best_epsilon_rad_s * (1.0 + kScreenMarginRelative);
}

}  // namespace rockfit::fitting
