// Impact parameters for `rockfit respond` taken from a fit file (the /fits layout of fitting/README.md):
// one trial's fitted values, or the mean over the fitted trials of one block and position.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rockfit/core/simulator.hpp"

namespace rockfit::tools {

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

}  // namespace rockfit::tools
