#include "rockfit/fitting/lateral_rescan.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "parallel_for.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/global_stage.hpp"
#include "rockfit/fitting/local_optimizer.hpp"

namespace rockfit::fitting {
namespace {

// The grid of λ_lat values: [−half_range, half_range] ∩ bounds in steps of `step`, 0 included.
std::vector<double> LambdaLatGrid(const Parameter& lat, const LateralRescanOptions& options) {
  std::vector<double> grid;
  const double lo = std::max(lat.lower, -options.lambda_lat_half_range);
  const double hi = std::min(lat.upper, options.lambda_lat_half_range);
  const auto first = static_cast<long>(std::ceil(lo / options.lambda_lat_step));
  const auto last = static_cast<long>(std::floor(hi / options.lambda_lat_step));
  for (long k = first; k <= last; ++k) grid.push_back(static_cast<double>(k) * options.lambda_lat_step);
  return grid;
}

// `at` with λ_lat replaced by the best grid value on `window`, if that is better than `at` itself. Evaluated in
// parallel; ties go to the lower grid index, so the result does not depend on the number of threads.
ParameterSet ScanLambdaLat(const Objective& window, const ParameterSet& at, const std::vector<double>& grid,
                           int num_threads) {
  std::vector<Evaluation> values(grid.size());
  ParallelFor(grid.size(), num_threads, [&](std::size_t i) {
    ParameterSet q = at;
    q[ParameterId::kLambdaLat].value = grid[i];
    values[i] = window.Evaluate(q);
  });
  const Evaluation current = window.Evaluate(at);
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (values[i].feasible && (!best || values[i].epsilon_rad_s < values[*best].epsilon_rad_s)) best = i;
  }
  if (!best || (current.feasible && current.epsilon_rad_s <= values[*best].epsilon_rad_s)) return at;
  ParameterSet q = at;
  q[ParameterId::kLambdaLat].value = grid[*best];
  return q;
}

// The joint scan of the first window: λ_lat over `grid` at first_window_lambda_points values of λ over its bounds
// and at λ of `at`, every other parameter held. Returns up to tracked_starts points, best first, from the best
// point of each λ row and `at` itself, each kept only when its λ_lat is more than min_separation from every point
// kept before (another needle, not the same one seen from a neighbouring λ). A tilted needle (its λ_lat drifts
// with λ) is found from the nearest row; a scan of λ_lat at a held λ misses it when λ is far from the truth's.
// Deterministic in any thread count.
std::vector<ParameterSet> JointFirstWindowStarts(const Objective& window, const ParameterSet& at,
                                                 const std::vector<double>& grid, const LateralRescanOptions& options,
                                                 int num_threads) {
  std::vector<double> lambdas = {at.value(ParameterId::kLambda)};
  if (window.IsFree(ParameterId::kLambda)) {
    const Parameter& lambda = window.parameters()[ParameterId::kLambda];
    for (int j = 0; j < options.first_window_lambda_points; ++j) {
      lambdas.push_back(lambda.lower + (lambda.upper - lambda.lower) * (j + 0.5) / options.first_window_lambda_points);
    }
  }
  const std::size_t n_lat = grid.size();
  std::vector<Evaluation> values(lambdas.size() * n_lat);
  ParallelFor(values.size(), num_threads, [&](std::size_t i) {
    ParameterSet q = at;
    q[ParameterId::kLambda].value = lambdas[i / n_lat];
    q[ParameterId::kLambdaLat].value = grid[i % n_lat];
    values[i] = window.Evaluate(q);
  });
  // The best point of each λ row, and the kept point itself.
  std::vector<std::pair<double, ParameterSet>> rows;
  if (const Evaluation e = window.Evaluate(at); e.feasible) rows.emplace_back(e.epsilon_rad_s, at);
  for (std::size_t r = 0; r < lambdas.size(); ++r) {
    std::optional<std::size_t> best;
    for (std::size_t k = 0; k < n_lat; ++k) {
      const Evaluation& e = values[r * n_lat + k];
      if (e.feasible && (!best || e.epsilon_rad_s < values[r * n_lat + *best].epsilon_rad_s)) best = k;
    }
    if (!best) continue;
    ParameterSet q = at;
    q[ParameterId::kLambda].value = lambdas[r];
    q[ParameterId::kLambdaLat].value = grid[*best];
    rows.emplace_back(values[r * n_lat + *best].epsilon_rad_s, std::move(q));
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<ParameterSet> starts;
  for (const auto& [epsilon, q] : rows) {
    if (static_cast<int>(starts.size()) >= options.tracked_starts) break;
    bool distinct = true;
    for (const ParameterSet& s : starts) {
      distinct &= std::abs(s.value(ParameterId::kLambdaLat) - q.value(ParameterId::kLambdaLat)) > options.min_separation;
    }
    if (distinct) starts.push_back(q);
  }
  return starts;
}

}  // namespace

void LateralRescanOptions::Validate() const {
  for (double v : {first_window_s, window_step_s, lambda_lat_half_range, lambda_lat_step, step_fraction}) {
    if (!(std::isfinite(v) && v > 0.0)) {
      throw InvalidArgument(fmt::format("lateral rescan options must be finite and positive, got {}", v));
    }
  }
  if (lambda_lat_half_range / lambda_lat_step > 1e5) {
    throw InvalidArgument(fmt::format("lateral rescan: a λ_lat grid of {} points is too fine (at most 10⁵)",
                                      lambda_lat_half_range / lambda_lat_step));
  }
  if (!(std::isfinite(below_abs_lambda_lat) && below_abs_lambda_lat >= 0.0)) {
    throw InvalidArgument(
        fmt::format("lateral rescan: below_abs_lambda_lat must be finite and not negative, got {}", below_abs_lambda_lat));
  }
  if (!(std::isfinite(min_separation) && min_separation >= 0.0)) {
    throw InvalidArgument(fmt::format("lateral rescan: min_separation must be finite and not negative, got {}", min_separation));
  }
  if (first_window_lambda_points < 0 || tracked_starts < 1) {
    throw InvalidArgument(fmt::format("lateral rescan: first_window_lambda_points must not be negative and tracked_starts "
                                      "must be at least 1, got {} and {}", first_window_lambda_points, tracked_starts));
  }
  if (lambda_scan_points < 0) {
    throw InvalidArgument(fmt::format("lateral rescan: lambda_scan_points must not be negative, got {}", lambda_scan_points));
  }
  if (evaluations_per_window < 1) {
    throw InvalidArgument(
        fmt::format("lateral rescan: evaluations_per_window must be at least 1, got {}", evaluations_per_window));
  }
}

LateralRescanResult RunLateralRescan(const Objective& objective, const ParameterSet& from,
                                     const LateralRescanOptions& options, const NelderMeadOptions& nelder_mead,
                                     int num_threads) {
  options.Validate();
  const auto clock_start = std::chrono::steady_clock::now();
  const std::int64_t runs_before = objective.counters().runs();
  LateralRescanResult result;
  result.at = from;
  const std::optional<double> t1 = FirstImpactTime(objective, from);
  if (!objective.IsFree(ParameterId::kLambdaLat) || !t1) return result;
  const std::vector<double> grid = LambdaLatGrid(objective.parameters()[ParameterId::kLambdaLat], options);
  NelderMeadOptions step_options = nelder_mead;
  step_options.max_evaluations = options.evaluations_per_window;
  for (double& step : step_options.initial_step) step *= options.step_fraction;

  const double first_window_end = std::min(objective.t_end_s(), *t1 + options.first_window_s);
  // The joint scan has scanned λ_lat on the first window already; without it (or when it found no feasible
  // point) the first window's scan of λ_lat runs from the kept point.
  std::vector<ParameterSet> starts =
      JointFirstWindowStarts(objective.WithWindowEnd(first_window_end), from, grid, options, num_threads);
  const bool scanned_first_window = !starts.empty();
  if (!scanned_first_window) starts = {from};
  // Each start is tracked from the first window to the full one; the best on the full window is kept.
  std::optional<Evaluation> best_e;
  for (const ParameterSet& start : starts) {
    ParameterSet at = start;
    bool converged = false;
    int windows = 0;
    for (double window_end = first_window_end;;) {
      const Objective window = objective.WithWindowEnd(window_end);
      if (windows > 0 || !scanned_first_window) at = ScanLambdaLat(window, at, grid, num_threads);
      if (options.lambda_scan_points > 0 && window.IsFree(ParameterId::kLambda)) {
        at = ScanParameter(window, at, ParameterId::kLambda, options.lambda_scan_points);
      }
      const LocalResult r = MakeNelderMead(step_options)->Minimize(window, window.FreeValues(at));
      if (r.feasible) at = window.WithFree(r.x);
      converged = r.converged;
      ++windows;
      if (window_end >= objective.t_end_s()) break;
      window_end = std::min(objective.t_end_s(), window_end + options.window_step_s);
    }
    const Evaluation e = objective.Evaluate(at);
    result.windows += windows;
    if (e.feasible && (!best_e || e.epsilon_rad_s < best_e->epsilon_rad_s)) {
      best_e = e;
      result.at = at;
      result.converged = converged;
    }
  }
  result.ran = true;
  result.feasible = best_e.has_value();
  if (best_e) result.epsilon_rad_s = best_e->epsilon_rad_s;
  result.evaluations = objective.counters().runs() - runs_before;
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace rockfit::fitting
