#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::io {

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
    summary.status = ToString(summary.opmf.status);
    summary.message = summary.opmf.message;
  } else if (!summary.avrf.ok()) {
    summary.status = ToString(summary.avrf.status);
    summary.message = summary.avrf.message;
  } else {
    summary.status = "ok";
  }
  return summary;
}

}  // namespace rockfit::io
