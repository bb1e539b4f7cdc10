// The result of `metrics` as both front ends give it: the JSON document of `rockfit metrics --json`, which the
// Python module returns as its dictionary (with arrays for the lists).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "rockfit/core/block.hpp"
#include "rockfit/io/recording.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::app {

// trial, source, format, rate_hz, samples, status, message, opmf, opmf_status, max_abs_phi_x, max_abs_phi_y, avrf,
// avrf_status, avrf_ratios, avrf_peaks_used, avrf_peak_times, avrf_peak_angles, lambda_equivalent, impact_times,
// phi_x_anchor_times, uplift_formula, anchor_method, mounting, block, warnings, units; a missing value is null.
nlohmann::json MetricsJson(const std::string& trial_id, const io::Recording& recording, const core::Block& block,
                           const io::MetricsOptions& options, const io::MetricsSummary& metrics);

}  // namespace rockfit::app
