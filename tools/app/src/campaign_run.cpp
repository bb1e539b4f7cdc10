#include "rockfit/app/campaign_run.hpp"

#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::app {

CampaignRun RunCampaign(const io::Manifest& manifest, const io::MetricsOptions& options,
                        const TrialCallback& on_trial) {
  CampaignRun run;
  for (const io::TrialSpec& trial : manifest.trials) {
    const io::BlockSpec& block = manifest.FindBlock(trial.block_id);
    io::Recording recording;
    io::MetricsSummary metrics;
    try {
      recording = LoadManifestTrial(trial);
      metrics = io::ComputeTrialMetrics(recording, block.ToBlock(), options);
    } catch (const BadInput& e) {
      run.summary.trials.push_back(io::MakeFailedTrialRow(trial, block, e.what()));
      ++run.load_errors;
      continue;
    }
    io::TrialRow row = io::MakeTrialRow(trial, block, metrics);
    row.mounting = recording.mounting;
    row.mounting_check = recording.mounting_check;
    run.summary.trials.push_back(std::move(row));
    if (on_trial) on_trial(trial, block, recording, metrics);
  }
  run.summary.groups = io::GroupTrials(run.summary.trials);
  return run;
}

}  // namespace rockfit::app
