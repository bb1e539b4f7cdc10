// A lower bound of (28) on a window from a model run over the window's first part: the screen of the scans.
//
// (28) is the mean of a non-negative integrand, ε = I / W with I = Σ_i w_i ‖ω_m(t_i) − ω_s(t_i − t0)‖ over the
// nodes and W the time the weights cover. Over a shorter window [t0, t_p] that ends at a sample time t_p, the
// nodes are the full window's nodes up to t_p, each with at most its weight there (the last one gets only its
// left half), and ω_s at them is the same (a run does not depend on where it stops). So the shorter window's
// integral I_p = ε_p · W_p is at most I, and ε ≥ I_p / W. A scan point whose bound lies above the best ε found
// so far cannot win the scan: its run over the rest of the window is skipped and the scan's result is the same.
// A point whose shorter run fails fails over the whole window too.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

struct PrefixBound {
  bool feasible = false;            // false: the model fails within the prefix, hence over the whole window
  double epsilon_lower_rad_s = 0.0;  // (28) on the whole window is at least this (feasible only)
};

class PrefixScreen {
 public:
  // prefix_fraction in (0, 1): the prefix ends at the first sample at or after t0 + prefix_fraction·(t_end − t0);
  // 0 switches the screen off. Throws InvalidArgument for a fraction outside [0, 1).
  PrefixScreen(const Objective& window, double prefix_fraction);

  bool enabled() const { return prefix_fraction_ > 0.0; }
  // One model run over the prefix of `window` at `values` (counted as a run); the trivial bound (feasible, 0)
  // without a run when the screen is off or no sample time lies strictly between t0 and the window's end.
  PrefixBound Bound(const ParameterSet& values) const;
  // True when `values` cannot have (28) below best_epsilon_rad_s on the window (+∞: when it is infeasible);
  // always false with the trivial bound. Costs at most one prefix run.
  bool CannotBeat(const ParameterSet& values, double best_epsilon_rad_s) const;
  // The same verdict from a bound already computed.
  static bool CannotBeatWithBound(const PrefixBound& bound, double best_epsilon_rad_s);

 private:
  const Objective* window_;
  double prefix_fraction_;
};

// The index of the feasible point of `points` with the lowest (28) on `window` (the first of equal ones), nullopt
// when none is feasible; its (28) in *best_epsilon_rad_s when given. Every point is first bounded from below by a
// run over the prefix (in parallel on num_threads, 0: all cores); then the points run over the whole window in
// the order of their bounds, in parallel batches, until the next bound lies above the best (28) found: the points
// left cannot win. The same index as evaluating every point over the whole window, in any thread count.
std::optional<std::size_t> ScreenedArgmin(const Objective& window, const std::vector<ParameterSet>& points,
                                          double prefix_fraction, int num_threads, double* best_epsilon_rad_s = nullptr);

}  // namespace rockfit::fitting
