#include "rockfit/fitting/prefix_screen.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "parallel_for.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {
namespace {

// A point is screened out only when its bound exceeds the best ε by more than this (relative): the bound and the
// full run agree to the integrator's tolerance at the prefix's last node (the run that stops there clips its last
// step), and that must not decide a scan.
constexpr double kScreenMarginRelative = 1e-7;

// Points of ScreenedArgmin run over the whole window in batches of this size (in parallel within a batch): small
// enough that few runs are wasted once the best is found, large enough to keep two threads busy.
constexpr std::size_t kScreenedBatchSize = 8;

// ErrorNodes::weighted_duration_s() of the nodes BuildErrorNodes makes for [t0, t_end] (into *scratch), or 0 when it
// makes none. Without excluded samples that is the window's length, (t_end − t0) − 0 exactly, known without nodes.
double WeightedWindowDuration(const MeasuredSignal& signal, double t0_s, double t_end_s, ErrorNodes* scratch) {
  if (signal.excluded.empty()) {
    if (!(t0_s >= signal.t_s.front()) || !(t_end_s <= signal.t_s.back()) || !(t0_s < t_end_s)) return 0.0;
    return t_end_s - t0_s;
  }
  return BuildErrorNodes(signal, t0_s, t_end_s, scratch) ? scratch->weighted_duration_s() : 0.0;
}

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
  // Scratch reused by each thread (a fit screens thousands of points): the nodes of the window and of the prefix.
  thread_local ErrorNodes full;
  thread_local ErrorNodes prefix_nodes;
  const double full_weighted_s = WeightedWindowDuration(signal, t0_s, t_end_s, &full);
  if (!(full_weighted_s > 0.0)) return trivial;
  // The prefix ends at a sample time strictly inside the window.
  const double t_wanted_s = t0_s + prefix_fraction_ * (t_end_s - t0_s);
  const auto it = std::lower_bound(signal.t_s.begin(), signal.t_s.end(), t_wanted_s);
  if (it == signal.t_s.end() || !(*it > t0_s) || !(*it < t_end_s)) return trivial;
  if (!BuildErrorNodes(signal, t0_s, *it, &prefix_nodes) || !(prefix_nodes.weighted_duration_s() > 0.0)) return trivial;
  const Evaluation e = window_->EvaluateOnNodes(values, prefix_nodes);  // (28) on the prefix [t0, *it]
  PrefixBound bound;
  bound.feasible = e.feasible;
  if (!e.feasible) return bound;
  bound.epsilon_lower_rad_s = e.epsilon_rad_s * prefix_nodes.weighted_duration_s() / full_weighted_s;
  return bound;
}

bool PrefixScreen::CannotBeat(const ParameterSet& values, double best_epsilon_rad_s) const {
  return CannotBeatWithBound(Bound(values), best_epsilon_rad_s);
}

bool PrefixScreen::CannotBeatWithBound(const PrefixBound& bound, double best_epsilon_rad_s) {
  if (!bound.feasible) return true;
  return bound.epsilon_lower_rad_s > best_epsilon_rad_s * (1.0 + kScreenMarginRelative);
}

std::optional<std::size_t> ScreenedArgmin(const Objective& objective, const std::vector<ParameterSet>& grid,
                                          double prefix_fraction, int num_threads, double* best_epsilon_rad_s) {
  const PrefixScreen screen(objective, prefix_fraction);
  std::vector<PrefixBound> bounds(grid.size());
  ParallelFor(grid.size(), num_threads, [&](std::size_t i) { bounds[i] = screen.Bound(grid[i]); });
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (bounds[i].feasible) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return bounds[a].epsilon_lower_rad_s < bounds[b].epsilon_lower_rad_s;
  });
  std::optional<std::size_t> best;
  double best_epsilon = std::numeric_limits<double>::infinity();
  std::size_t next = 0;
  while (next < order.size()) {
    std::vector<std::size_t> batch;
    while (next < order.size() && batch.size() < kScreenedBatchSize &&
           !(best && PrefixScreen::CannotBeatWithBound(bounds[order[next]], best_epsilon))) {
      batch.push_back(order[next++]);
    }
    if (batch.empty()) break;
    std::vector<Evaluation> values(batch.size());
    ParallelFor(batch.size(), num_threads, [&](std::size_t k) { values[k] = objective.Evaluate(grid[batch[k]]); });
    for (std::size_t k = 0; k < batch.size(); ++k) {
      const std::size_t i = batch[k];
      if (!values[k].feasible) continue;
      if (!best || values[k].epsilon_rad_s < best_epsilon || (values[k].epsilon_rad_s == best_epsilon && i < *best)) {
        best = i;
        best_epsilon = values[k].epsilon_rad_s;
      }
    }
  }
  if (best && best_epsilon_rad_s) *best_epsilon_rad_s = best_epsilon;
  return best;
}

}  // namespace rockfit::fitting
