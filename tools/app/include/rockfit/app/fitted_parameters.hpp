// Impact parameters for `rockfit respond` taken from a fit file (the /fits layout of fitting/README.md):
// one trial's fitted values, or the mean over the fitted trials of one block and position.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rockfit/core/simulator.hpp"

namespace rockfit::app {

struct FittedParameters {
  core::ModelParameters params;      // λ, λ_lat, λ_lon, τ_edge and α from the fit (t0 is not used)
  std::vector<std::string> trials;   // the trials the values come from
  std::string description;           // e.g. "fit of block2-A-1" or "mean of 2 fits of block2 A"
};

// /fits/<trial>/parameters. Throws BadInput when the file, the trial or a parameter is missing.
FittedParameters ReadFittedTrial(const std::filesystem::path& fits, const std::string& trial);
// The mean of every feasible fit in /fits whose `block` and `position` attributes match. Throws BadInput when
// there is none (listing the groups present).
FittedParameters ReadFittedGroupMean(const std::filesystem::path& fits, const std::string& block,
                                     const std::string& position);

// One parameter of a block and position as `rockfit batch` summarises it in /summary/fits/per_group
// (fitting/README.md, "Per block and position"): the pooled estimate (else the mean) with the standard error
// behind its 95 % interval, and the spread between the trials.
struct FittedParameterRange {
  double value = 0.0;             // pooled, or the mean of the trials when no trial determined it
  double estimate_sd = 0.0;       // (95 % upper − lower)/(2·1.96) of the pooled estimate; 0 without one
  double between_trial_sd = 0.0;  // sample standard deviation of the trials' values; 0 for one trial
  bool pooled = false;
  // The standard deviation of the parameter of one block in one earthquake: estimate and trial-to-trial
  // variation together, √(estimate_sd² + between_trial_sd²).
  double TotalSd() const;
};

struct FittedGroupRanges {
  FittedParameterRange lambda, lambda_lat, lambda_lon, tau_edge;
  std::int64_t trials = 0;
  std::string description;  // e.g. "pooled estimates of 2 fits of block2 A"
};

// Row (block, position) of /summary/fits/per_group. BadInput when the file has no such table (a file of `rockfit
// fit -o`: run `rockfit batch`) or no such group (listing those present).
FittedGroupRanges ReadFittedGroupRanges(const std::filesystem::path& fits, const std::string& block,
                                       const std::string& position);

}  // namespace rockfit::app
