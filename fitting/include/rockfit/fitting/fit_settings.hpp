// Everything that determines a fit's result, as canonical JSON and a hash of it: stored with each fit
// (/fits/<trial> attributes settings, settings_hash) so that `rockfit batch --resume` skips exactly the trials
// already fitted with the same settings.
#pragma once

#include <string>

#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trial_fit.hpp"

namespace rockfit::fitting {

// Parameter set (values of fixed parameters, bounds, fixed flags, facet τ rule) and every option of the fit,
// the data estimate and the simulator, plus `extra` (e.g. the trial's files, format, rate, mounting and block)
// as one JSON object with sorted keys.
std::string FitSettingsJson(const ParameterSet& parameters, const TrialFitOptions& options, const std::string& extra_json = "{}");
// FNV-1a 64 of the text, 16 hex digits.
std::string SettingsHash(const std::string& text);

}  // namespace rockfit::fitting
