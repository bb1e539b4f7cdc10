#include "rockfit/fitting/final_stage.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "rockfit/core/checks.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/global_stage.hpp"
#include "rockfit/fitting/local_optimizer.hpp"

namespace rockfit::fitting {
namespace {

// The position of `id` among the free parameters; -1 when it is fixed.
Eigen::Index FreeIndex(const Objective& objective, ParameterId id) {
  const std::vector<ParameterId>& ids = objective.free_ids();
  const auto it = std::find(ids.begin(), ids.end(), id);
  return it == ids.end() ? -1 : static_cast<Eigen::Index>(it - ids.begin());
}

// `points` offsets evenly spaced over [−half_width, half_width]; the centre alone for one point.
std::vector<double> Offsets(double half_width, int points) {
  if (points == 1) return {0.0};
  std::vector<double> offsets;
  for (int i = 0; i < points; ++i) offsets.push_back(-half_width + 2.0 * half_width * i / (points - 1));
  return offsets;
}

struct GridPoint {
  Eigen::VectorXd x;
  double epsilon_rad_s = 0.0;
  int row = 0;  // the value of the grid's first coordinate (λ, or t0 on the ridge)
};

// A grid over two free coordinates (i_row, i_col; i_col −1: the first alone) around x_best: x_best moved by
// row_offsets[r]·row_direction + col_offsets[c] along i_col, the centre left out, points beyond a bound skipped.
// Returns the feasible points with their (28).
std::vector<GridPoint> RunGrid(const Objective& objective, const Eigen::VectorXd& x_best,
                               const Eigen::VectorXd& row_direction, const std::vector<double>& row_offsets,
                               Eigen::Index i_col, const std::vector<double>& col_offsets, std::int64_t* evaluations) {
  const Eigen::VectorXd lower = objective.FreeLower();
  const Eigen::VectorXd upper = objective.FreeUpper();
  std::vector<GridPoint> grid;
  for (int row = 0; row < static_cast<int>(row_offsets.size()); ++row) {
    for (double dc : i_col < 0 ? std::vector<double>{0.0} : col_offsets) {
      const double dr = row_offsets[static_cast<std::size_t>(row)];
      if (dr == 0.0 && dc == 0.0) continue;
      Eigen::VectorXd x = x_best + dr * row_direction;
      if (i_col >= 0) x[i_col] += dc;
      if ((x.array() < lower.array()).any() || (x.array() > upper.array()).any()) continue;
      const Evaluation e = objective.EvaluateFree(x);
      ++*evaluations;
      if (e.feasible) grid.push_back({x, e.epsilon_rad_s, row});
    }
  }
  return grid;
}

// The best point of each row, best rows first, at most `count`.
std::vector<GridPoint> BestRows(std::vector<GridPoint> grid, int count) {
  std::stable_sort(grid.begin(), grid.end(),
                   [](const GridPoint& a, const GridPoint& b) { return a.epsilon_rad_s < b.epsilon_rad_s; });
  std::vector<GridPoint> best;
  std::vector<int> rows;
  for (const GridPoint& g : grid) {
    if (static_cast<int>(best.size()) >= count) break;
    if (std::find(rows.begin(), rows.end(), g.row) != rows.end()) continue;
    rows.push_back(g.row);
    best.push_back(g);
  }
  return best;
}

}  // namespace

void FinalStageOptions::Validate() const {
  RequirePositive(lambda_half_width, "fit option final_stage.lambda_half_width");
  RequirePositive(lambda_lat_half_width, "fit option final_stage.lambda_lat_half_width");
  RequireAtLeast(lambda_points, 1, "fit option final_stage.lambda_points");
  RequireAtLeast(lambda_lat_points, 1, "fit option final_stage.lambda_lat_points");
  RequireAtLeast(ridge_points, 0, "fit option final_stage.ridge_points");
  RequirePositive(ridge_t0_half_width_s, "fit option final_stage.ridge_t0_half_width_s", "seconds");
  RequirePositive(ridge_alpha_difference_rad, "fit option final_stage.ridge_alpha_difference_rad", "radians");
  RequireAtLeast(lambda_lon_points, 1, "fit option final_stage.lambda_lon_points");
  RequirePositive(lambda_lon_half_width, "fit option final_stage.lambda_lon_half_width");
  RequireAtLeast(polished, 0, "fit option final_stage.polished");
  RequireAtLeast(evaluations_per_polish, 1, "fit option final_stage.evaluations_per_polish");
  RequirePositive(step_fraction, "fit option final_stage.step_fraction");
  RequireAtLeast(rounds, 1, "fit option final_stage.rounds");
}

namespace {

// One pass of the grids and polishes from `result->x` (λ free), lowering result->x and result->epsilon_rad_s where
// it finds a lower (28). Returns the grid points run and the polishes.
std::pair<std::size_t, std::size_t> RunPass(const Objective& objective, const FinalStageOptions& options,
                                            const NelderMeadOptions& nelder_mead, FinalStageResult* result) {
  const Eigen::VectorXd x_best = result->x;
  const Eigen::Index i_lambda = FreeIndex(objective, ParameterId::kLambda);
  const Eigen::Index n = static_cast<Eigen::Index>(objective.num_free());

  // λ × λ_lat around the best point, the others held.
  Eigen::VectorXd along_lambda = Eigen::VectorXd::Zero(n);
  along_lambda[i_lambda] = 1.0;
  const std::vector<GridPoint> lambda_grid =
      RunGrid(objective, x_best, along_lambda, Offsets(options.lambda_half_width, options.lambda_points),
              FreeIndex(objective, ParameterId::kLambdaLat),
              Offsets(options.lambda_lat_half_width, options.lambda_lat_points), &result->evaluations);
  std::vector<GridPoint> starts = BestRows(lambda_grid, options.polished);
  std::size_t grid_points = lambda_grid.size();

  // t0 × λ_lon along the ridge t0 + T(α) = t1.
  const Eigen::Index i_t0 = FreeIndex(objective, ParameterId::kT0);
  const Eigen::Index i_alpha = FreeIndex(objective, ParameterId::kAlpha);
  if (options.ridge_points > 0 && i_t0 >= 0 && i_alpha >= 0) {
    // dα/dt0 = −1/T'(α) keeps the first impact t1 = t0 + T(α).
    const std::optional<double> fall_slope = FallTimeSlope(objective, objective.WithFree(x_best),
                                                           options.ridge_alpha_difference_rad, &result->evaluations);
    if (fall_slope) {
      Eigen::VectorXd along_ridge = Eigen::VectorXd::Zero(n);
      along_ridge[i_t0] = 1.0;
      along_ridge[i_alpha] = -1.0 / *fall_slope;
      const std::vector<GridPoint> ridge_grid =
          RunGrid(objective, x_best, along_ridge, Offsets(options.ridge_t0_half_width_s, options.ridge_points),
                  FreeIndex(objective, ParameterId::kLambdaLon),
                  Offsets(options.lambda_lon_half_width, options.lambda_lon_points), &result->evaluations);
      grid_points += ridge_grid.size();
      for (const GridPoint& g : BestRows(ridge_grid, options.polished)) starts.push_back(g);
    }
  }

  NelderMeadOptions search = nelder_mead;
  for (double& step : search.initial_step) step *= options.step_fraction;
  search.max_evaluations = options.evaluations_per_polish;
  for (const GridPoint& g : starts) {
    // A grid point below the best is a candidate in itself.
    if (g.epsilon_rad_s < result->epsilon_rad_s) {
      result->x = g.x;
      result->epsilon_rad_s = g.epsilon_rad_s;
      result->improved = true;
    }
    const LocalResult r = MakeNelderMead(search)->Minimize(objective, g.x);
    result->evaluations += r.evaluations;
    // Only a feasible point with a strictly lower (28) replaces the best: the stage never returns a higher ε.
    if (r.feasible && r.epsilon_rad_s < result->epsilon_rad_s) {
      result->x = r.x;
      result->epsilon_rad_s = r.epsilon_rad_s;
      result->improved = true;
    }
  }
  return {grid_points, starts.size()};
}

}  // namespace

FinalStageResult RunFinalStage(const Objective& objective, const Eigen::VectorXd& x_best, double epsilon_best_rad_s,
                               bool feasible, const FinalStageOptions& options, const NelderMeadOptions& nelder_mead) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  FinalStageResult result;
  result.x = x_best;
  result.epsilon_rad_s = epsilon_best_rad_s;
  result.feasible = feasible;
  if (!options.enabled || !feasible || FreeIndex(objective, ParameterId::kLambda) < 0) {
    result.termination = !options.enabled ? "not run" : !feasible ? "not run: the given point is infeasible"
                                                                  : "not run: λ is fixed";
    return result;
  }
  std::size_t grid_points = 0, polished = 0;
  int passes = 0;
  for (; passes < options.rounds;) {
    const double before = result.epsilon_rad_s;
    const auto [g, p] = RunPass(objective, options, nelder_mead, &result);
    grid_points += g;
    polished += p;
    ++passes;
    if (!(result.epsilon_rad_s < before)) break;
  }
  result.termination =
      fmt::format("{} pass(es), {} grid points, {} polished; {}", passes, grid_points, polished,
                  result.improved ? fmt::format("(28) lowered by {:.4g} %",
                                                100.0 * (1.0 - result.epsilon_rad_s / epsilon_best_rad_s))
                                  : std::string("no lower (28)"));
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace rockfit::fitting
