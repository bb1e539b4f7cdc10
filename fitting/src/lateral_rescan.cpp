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

  ParameterSet at = from;
  double window_end = std::min(objective.t_end_s(), *t1 + options.first_window_s);
  for (;;) {
    const Objective window = objective.WithWindowEnd(window_end);
    at = ScanLambdaLat(window, at, grid, num_threads);
    if (options.lambda_scan_points > 0 && window.IsFree(ParameterId::kLambda)) {
      at = ScanParameter(window, at, ParameterId::kLambda, options.lambda_scan_points);
    }
    const LocalResult r = MakeNelderMead(step_options)->Minimize(window, window.FreeValues(at));
    if (r.feasible) at = window.WithFree(r.x);
    result.converged = r.converged;
    ++result.windows;
    if (window_end >= objective.t_end_s()) break;
    window_end = std::min(objective.t_end_s(), window_end + options.window_step_s);
  }
  const Evaluation e = objective.Evaluate(at);
  result.ran = true;
  result.at = at;
  result.feasible = e.feasible;
  result.epsilon_rad_s = e.epsilon_rad_s;
  result.evaluations = objective.counters().runs() - runs_before;
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace rockfit::fitting
