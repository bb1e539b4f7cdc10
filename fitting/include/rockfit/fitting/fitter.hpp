// The fitting pipeline for one trial: (optional) global stage, then the local back end(s) of FitOptions::method,
// keeping the point with the lowest (28); then identifiability, bounds and standard errors (docs/design.md §7).
//
//   nelder-mead: global stage → Nelder–Mead
//   ceres:       global stage → Ceres
//   auto:        global stage → Nelder–Mead → Ceres polish, the best of all kept
#pragma once

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

// Fits the free parameters of `objective`, starting at the free values of `start` (clamped into the bounds).
// Throws InvalidArgument for bad options or when no parameter is free; numerical trouble is reported in the
// summary (termination, warnings), never thrown. The objective is evaluated with options.gyro_scale projected
// out (Objective::WithGyroScale), whatever its own setting; the scale is in the summary's gyro_scale.
FitSummary Fit(const Objective& objective, const ParameterSet& start, const FitOptions& options);

}  // namespace rockfit::fitting
