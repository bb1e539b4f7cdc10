// "Not identifiable": a free parameter that has no influence on the error (28) at the optimum — typically λ
// when no edge impact happened in the fitting window, or λ_lat/λ_lon when the window ends before the facet
// impact. Checked by the sensitivity of ε: the parameter is moved by ±probe_step (within its bounds) and ε
// must change by more than relative_tolerance·ε. The model's impact log at the optimum gives the reason.
#pragma once

#include <array>
#include <string>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

struct IdentifiabilityReport {
  std::array<bool, kNumParameters> identifiable{};  // fixed parameters count as identifiable
  PerParameter max_abs_change_rad_s{};              // largest |Δε| of the two probes (0 for fixed)
  int edge_impacts_in_window = 0;
  int facet_impacts_in_window = 0;
  // One sentence per non-identifiable parameter (empty for the others).
  std::array<std::string, kNumParameters> reason{};
};

// Costs 1 + 2·(free parameters) evaluations.
IdentifiabilityReport CheckIdentifiability(const Objective& objective, const ParameterSet& at,
                                           const IdentifiabilityOptions& options);

}  // namespace rockfit::fitting
