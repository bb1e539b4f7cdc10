// Metrics of every trial of a manifest, trial by trial (`rockfit summary`, `rockfit plot summary`). A trial
// whose files cannot be read is reported, not fatal.
#pragma once

#include <functional>
#include <string>

#include "rockfit/io/campaign_summary.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::app {

struct CampaignRun {
  io::CampaignSummary summary;
  std::size_t load_errors = 0;
};

// Called after each trial that could be read, e.g. to store it; a recording is not kept after its call.
using TrialCallback =
    std::function<void(const io::TrialSpec&, const io::BlockSpec&, const io::Recording&, const io::MetricsSummary&)>;

CampaignRun RunCampaign(const io::Manifest& manifest, const io::MetricsOptions& options,
                        const TrialCallback& on_trial = {});

}  // namespace rockfit::app
