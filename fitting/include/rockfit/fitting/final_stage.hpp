// A last search around the fit's best point that does not depend on how the stages before it got there
// (fitting/README.md, "A final stage that does not depend on the start"). Off by default: measured there.
//
// (28) is rippled: a simulated impact that crosses a sample time changes it by a step, and λ acts through cascades
// of edge impacts, so next to the fit's minimum lie others, 0.1–1 % higher or lower behind barriers of about 1 %
// that the local searches do not cross: a few standard errors of λ away with λ_lat moved a little along the valley
// where the two trade, or a fraction of a sample period along the ridge t0 + T(α) = t1 with λ_lon moved. Which of
// them the stages end in can depend on round-off of the start. The stage scans λ × λ_lat around the best point (the
// others held) and t0 × λ_lon along that ridge, polishes the best points of each grid away from the centre by short
// Nelder–Mead searches over every free parameter, and keeps the lowest (28); it repeats from a new best point while
// that lowers (28), up to `rounds` passes. It only ever returns a point with a lower (28) than it was given, or that
// point itself.
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

struct NelderMeadOptions;

struct FinalStageOptions {
  bool enabled = false;
  // The grid: λ at lambda_points values over ±lambda_half_width around the best point, λ_lat at lambda_lat_points
  // values over ±lambda_lat_half_width (a parameter that is not free is not scanned; points beyond a bound are
  // skipped). Neighbouring minima of the coverage study lay 0.02 apart in λ with λ_lat 0.001 off its value.
  double lambda_half_width = 0.03;
  int lambda_points = 21;
  double lambda_lat_half_width = 0.0015;
  int lambda_lat_points = 11;
  // A second grid along the ridge t0 + T(α) = t1 that the data fix (T the model's fall time; dα = −dt0/T'(α), T' by
  // a central difference of two model runs with the α step ridge_alpha_difference_rad): t0 at ridge_points values
  // over ±ridge_t0_half_width_s (a fraction of a sample period: an impact crossing a sample time is a step of
  // (28)), λ_lon at lambda_lon_points values over ±lambda_lon_half_width at each. ridge_points 0: no such grid.
  // The profiles of the intervals met lower minima 0.2 ms along this ridge from the local stages' end.
  int ridge_points = 11;
  double ridge_t0_half_width_s = 5e-4;
  double ridge_alpha_difference_rad = 1e-4;
  int lambda_lon_points = 5;
  double lambda_lon_half_width = 0.004;
  // The best grid points of each grid other than the centre (at most one per value of λ, or of t0), each polished by
  // Nelder–Mead over every free parameter with this many evaluations and its initial simplex this fraction of
  // nelder_mead.initial_step (a short search that stays in the grid point's basin).
  int polished = 2;
  int evaluations_per_polish = 150;
  double step_fraction = 0.25;
  // The grids and polishes again from the new best point while a pass lowers (28), at most this many passes.
  int rounds = 1;
  void Validate() const;  // throws InvalidArgument
};

struct FinalStageResult {
  Eigen::VectorXd x;             // free parameters: the given point unless a lower (28) was found
  double epsilon_rad_s = 0.0;    // (28) at x
  bool feasible = false;
  bool improved = false;         // x is not the given point
  std::int64_t evaluations = 0;  // evaluations of (28): the grid and the polishes
  double wall_time_s = 0.0;
  std::string termination;       // what happened, for the summary's stage list
};

// From the free parameters x_best of `objective` with (28) = epsilon_best_rad_s there. Returns x_best itself unless
// a feasible point with a lower (28) was found. Options not enabled, an infeasible given point, or λ not free run
// nothing.
FinalStageResult RunFinalStage(const Objective& objective, const Eigen::VectorXd& x_best, double epsilon_best_rad_s,
                               bool feasible, const FinalStageOptions& options, const NelderMeadOptions& nelder_mead);

}  // namespace rockfit::fitting
