#include "rockfit/io/trial_metrics.hpp"

#include "rockfit/core/enum_names.hpp"

namespace rockfit::io {

const char* ToString(MetricsStatus status) {
  switch (status) {
    case MetricsStatus::kOk: return "ok";
    case MetricsStatus::kNoImpact: return "no_impact";
    case MetricsStatus::kNoInPlaneMotion: return "no_in_plane_motion";
    case MetricsStatus::kTooFewPeaks: return "too_few_peaks";
    case MetricsStatus::kInvalidUplift: return "invalid_uplift";
    case MetricsStatus::kNoBlock: return "no_block";
    case MetricsStatus::kLoadError: return "load_error";
  }
  return "ok";
}

bool FromString(std::string_view text, MetricsStatus* status) {
  static constexpr MetricsStatus kAll[] = {MetricsStatus::kOk,          MetricsStatus::kNoImpact,
                                           MetricsStatus::kNoInPlaneMotion, MetricsStatus::kTooFewPeaks,
                                           MetricsStatus::kInvalidUplift, MetricsStatus::kNoBlock,
                                           MetricsStatus::kLoadError};
  return core::FromStringAmong(text, kAll, status);
}

namespace {

// The metrics outcome of an OPMF or AVRF status: the names are shared, so the value is the one of that name.
template <class Status>
MetricsStatus AsMetricsStatus(Status status) {
  MetricsStatus out = MetricsStatus::kOk;
  FromString(ToString(status), &out);
  return out;
}

}  // namespace

void MetricsOptions::Validate() const {
  correction.Validate();
  avrf.Validate();
}

MetricsSummary ComputeTrialMetrics(const Recording& recording, const std::optional<core::Block>& block,
                                   const MetricsOptions& options) {
  options.Validate();
  MetricsSummary summary;
  summary.correction = CorrectDrift(recording, options.correction);
  const bool has_impact = !summary.correction.impacts_y.empty();
  summary.opmf = ComputeOpmf(recording.t_s, summary.correction.euler_corrected_zyx, has_impact,
                             summary.correction.first_impact_s(), summary.correction.last_impact_s());
  if (block) {
    summary.avrf = ComputeAvrf(recording.t_s, summary.correction, *block, options.avrf);
  } else {
    summary.avrf.status = AvrfStatus::kNoBlock;
    summary.avrf.message = "the AVRF needs the block geometry (b1, h): give --manifest/--block or --b1 --b2 --h";
  }
  if (!summary.opmf.ok()) {
    summary.status = AsMetricsStatus(summary.opmf.status);
    summary.message = summary.opmf.message;
  } else if (!summary.avrf.ok()) {
    summary.status = AsMetricsStatus(summary.avrf.status);
    summary.message = summary.avrf.message;
  } else {
    summary.status = MetricsStatus::kOk;
  }
  return summary;
}

}  // namespace rockfit::io
