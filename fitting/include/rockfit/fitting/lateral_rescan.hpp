// A second search for the narrow basin of λ_lat, for fits that leave the recorded out-of-plane motion unexplained
// or have weak lateral motion that the lateral-motion check cannot judge (fitting/README.md, "Lateral rescan").
//
// With weak lateral motion on a narrow block the basin of the truth in λ_lat is a needle over the full window
// (about 10⁻³ wide), next to a broad plateau of nearly planar model motion where the global stage can end
// (lateral_motion_check.hpp). Over a shorter window the needle is wider: the lateral half-cycles that a wrong
// λ_lat puts out of phase are fewer. The needle is also tilted: its λ_lat drifts with λ. The rescan therefore
// scans λ_lat over a fine grid on [−half_range, half_range] (clipped to its bounds) jointly with λ on a window
// that ends first_window_s after the model's first impact, the other parameters held, and tracks up to
// tracked_starts of the best distinct points through windows growing by window_step_s up to the full window.
// In every later window λ_lat is scanned again (the best grid point replaces the current one if it is better),
// then λ, and a short Nelder–Mead run over every free parameter follows: the needle, once found in a short
// window, is followed as it narrows. The best track on the full window is the result.
//
// It costs about ten thousand evaluations of (28), most of them on short windows; the fitter keeps its result
// only when (28) on the full window is lower.
#pragma once

#include <cstdint>

#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

struct NelderMeadOptions;

struct LateralRescanOptions {
  bool enabled = true;
  // The fitter rescans a fit that the lateral-motion check flags, and also one whose |λ_lat| is below this when
  // its out-of-plane signal is too close to the noise for the check to judge: the truth's basin is still a needle
  // that the global stage can miss (coverage study: five misses at |λ_lat| 0.11–0.39, none judged by the check).
  double below_abs_lambda_lat = 0.5;
  // The first window ends this long after the model's first impact at the kept point [s]: the first lateral
  // half-cycle after the facet impact.
  double first_window_s = 0.1;
  // Each following window is this much longer [s]: short enough that the needle found in one window still
  // overlaps the basin of the next (measured on the coverage study: 0.1 s tracks it, doubling does not).
  double window_step_s = 0.1;
  // λ_lat is scanned over [−half_range, half_range] ∩ its bounds in steps of lambda_lat_step: weak lateral
  // motion is |λ_lat| ≲ 0.5; the step resolves the needle on windows up to a few lateral half-cycles.
  double lambda_lat_half_range = 1.0;
  double lambda_lat_step = 0.005;
  // After the λ_lat scan, λ is scanned over its bounds at this many values (0: not): the plateau's λ can lie far
  // from the truth's, farther than a short local search moves it.
  int lambda_scan_points = 48;
  // On the first window λ_lat is scanned jointly with λ, at this many values of λ over its bounds and at the
  // kept point's λ: the needle is tilted (its λ_lat drifts by a few 0.01 per unit of λ), so a scan at a held λ far
  // from the truth's misses it. The best points of the λ rows with distinct λ_lat (more than min_separation
  // apart: another needle) are tracked through the growing windows, at most tracked_starts of them.
  int first_window_lambda_points = 12;
  int tracked_starts = 3;
  double min_separation = 0.02;
  // Nelder–Mead evaluations per window; its initial simplex is this fraction of nelder_mead.initial_step.
  int evaluations_per_window = 150;
  double step_fraction = 0.25;
  void Validate() const;  // throws InvalidArgument
};

struct LateralRescanResult {
  bool ran = false;          // false: λ_lat not free, the model fails at the start, or no window to grow
  ParameterSet at;           // the point reached on the full window
  double epsilon_rad_s = 0.0;  // (28) there on the full window (feasible only)
  bool feasible = false;
  bool converged = false;    // the last local search converged
  int windows = 0;          // summed over the tracked starts
  std::int64_t evaluations = 0;
  double wall_time_s = 0.0;
};

// The rescan from `from` (values of every parameter). Grid evaluations run on num_threads threads (0 = all
// cores); the result does not depend on their number. Never throws for numerical trouble.
LateralRescanResult RunLateralRescan(const Objective& objective, const ParameterSet& from,
                                     const LateralRescanOptions& options, const NelderMeadOptions& nelder_mead,
                                     int num_threads);

}  // namespace rockfit::fitting
