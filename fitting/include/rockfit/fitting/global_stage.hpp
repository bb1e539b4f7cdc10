// The global stage of a fit without a starting point.
//
// The error (28) over the whole window is strongly multimodal in the impact parameters: the lateral rocking
// after the facet impact runs through several half-cycles whose phase depends on λ_lat and λ, so a small change
// of amplitude early on shifts everything later. Over a short window the same parameters act almost linearly.
// Hence a continuation in the window length:
//
//  1. First window [t0, t1 + first_window_s], t1 the first impact of the model at the estimate: Latin-hypercube
//     starts (plus the estimate) over the parameters that matter there, evaluated in parallel; the best few
//     distinct starts — always the best of each sign of λ_lat, because the sign selects the vertex the block
//     rocks on after the facet impact (docs/design.md §3) — are polished by Nelder–Mead in parallel.
//  2. The best num_continued of them are carried to the full window through windows growing by a factor
//     `continuation_growth` after t1, with a short Nelder–Mead run in each. Parameters that do not act yet in a
//     window (λ before the first edge impact) are held fixed there; when one starts to act, it is first
//     scanned over its bounds, because its first influence (the timing of the next lateral half-cycles) is
//     again multimodal.
//     The carried starts go window by window together; after each window a start whose (28) there exceeds
//     `continuation_prune_ratio` times the best start's is dropped (the stop rule).
//  3. On the full window, the impact parameters (everything but t0 and α) are scanned over their bounds once
//     more, one at a time, followed by a last Nelder–Mead run; the best carried start by (28) is kept.
//  4. Refinement of that start, for what one-at-a-time scans and short local searches miss: (a) a joint scan
//     of λ over its bounds and λ_lat within ±20 % of its value — with weak lateral motion the two trade for
//     each other along a narrow, rippled valley of (28) —; its best point joins the kept start as a second
//     candidate; (b) each candidate is carried once more from the first window to the full window, without
//     scans: with the impact parameters now close, the short windows hold t0, α and λ_lon where phase 1 and the
//     facet impact put them (in the first pass they drift along the t0–α–λ_lon ridge to make up for a λ that is
//     still wrong); (c) a scan along that ridge (t0 + T(α) fixed, λ_lon re-fitted at each point) and a last
//     Nelder–Mead run. The best by (28) of the kept start and the refined candidates is the result.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

struct GlobalStageResult {
  Eigen::VectorXd best_x;  // free parameters of the full problem
  double best_epsilon_rad_s = 0.0;
  bool feasible = false;
  bool converged = false;        // the last continuation step of the kept start converged
  double first_window_end_s = 0.0;
  int num_samples = 0;           // starts evaluated in the first window
  int num_feasible_samples = 0;
  int num_continued = 0;
  std::int64_t evaluations = 0;
  double wall_time_s = 0.0;
  // Every feasible start carried to the full window and every refined candidate, with its (28): the fitter
  // reports a distinct one with nearly the same ε as a second solution.
  std::vector<std::pair<Eigen::VectorXd, double>> candidates;
};

// The sampling box: t0 and α within the given half-widths of the estimate (they are well determined by
// phase 1), every other free parameter over its whole bounds; always clipped to the bounds.
void GlobalSamplingBox(const Objective& objective, const Eigen::VectorXd& estimate, const GlobalStageOptions& options,
                       Eigen::VectorXd* lower, Eigen::VectorXd* upper);

// The best of `points` equally spaced values of `id` over its bounds and its value at `at` (others held). With
// prefix_fraction > 0 each value is first bounded by a run over that part of the window (prefix_screen.hpp) and
// runs over the whole window only when the bound does not rule it out: the same result, fewer full runs.
ParameterSet ScanParameter(const Objective& window, const ParameterSet& at, ParameterId id, int points,
                           double prefix_fraction = 0.0);

// Time of the model's first impact at `at` (values of every parameter) in recording time; nullopt when the model
// fails there or has no impact in the window.
std::optional<double> FirstImpactTime(const Objective& objective, const ParameterSet& at);

// T'(α) [s/rad] at `at`: the central difference of the model's fall time T = t1 − t0 over α ± h_rad (two model runs,
// counted in *model_runs when given). nullopt where α ± h_rad leaves α's bounds, the model has no impact at either,
// or T does not grow with α. Moving α by −dt0/T'(α) with t0 keeps the first impact t1 = t0 + T(α) to first order.
std::optional<double> FallTimeSlope(const Objective& objective, const ParameterSet& at, double h_rad,
                                    std::int64_t* model_runs = nullptr);

// Every scan over a parameter's bounds (steps 2–4) first bounds each point's (28) from below by a run over the first
// `scan_prefix_fraction` of the window and runs the whole window only where the bound leaves the point a chance
// (prefix_screen.hpp): the scans' results are those of the unscreened scans.
//
// Deterministic for a given seed whatever the number of threads (options.num_threads, 0 = all cores).
GlobalStageResult RunGlobalStage(const Objective& objective, const Eigen::VectorXd& estimate,
                                 const FitOptions& options);

}  // namespace rockfit::fitting
