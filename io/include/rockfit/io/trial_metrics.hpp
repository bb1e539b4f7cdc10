// The metrics of one trial: drift correction, then OPMF and AVRF (docs/design.md §6). This is what `rockfit metrics`,
// `rockfit summary` and the HDF5 store report per trial.
#pragma once

#include <string_view>

#include <optional>
#include <string>

#include "rockfit/core/block.hpp"
#include "rockfit/io/avrf.hpp"
#include "rockfit/io/drift_correction.hpp"
#include "rockfit/io/opmf.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

struct MetricsOptions {
  DriftCorrectionOptions correction;
  AvrfOptions avrf;
  void Validate() const;
};

// The outcome of a trial's metrics: both have values, or the first reason one has none (the statuses of the OPMF
// and the AVRF), or — for a trial of a campaign — its files could not be read.
enum class MetricsStatus { kOk, kNoImpact, kNoInPlaneMotion, kTooFewPeaks, kInvalidUplift, kNoBlock, kLoadError };
// "ok", "no_impact", "no_in_plane_motion", "too_few_peaks", "invalid_uplift", "no_block", "load_error".
const char* ToString(MetricsStatus status);
bool FromString(std::string_view text, MetricsStatus* status);  // the inverse of ToString

struct MetricsSummary {
  DriftCorrection correction;
  OpmfResult opmf;
  AvrfResult avrf;
  // "ok" when both metrics have values; otherwise the first status that is not ok ("no_impact",
  // "too_few_peaks", …), and the message says why.
  MetricsStatus status = MetricsStatus::kOk;
  std::string message;
  bool ok() const { return status == MetricsStatus::kOk; }
};

// Without a block only the OPMF is computed, and the AVRF status says that the block geometry is missing
// (status "no_block"). A recording without Euler angles gets them from its gyro (gyro_attitude.hpp).
MetricsSummary ComputeTrialMetrics(const Recording& recording, const std::optional<core::Block>& block,
                                   const MetricsOptions& options);

}  // namespace rockfit::io
