// Metrics of every trial of a campaign and their statistics per (block, position) — the paper's Fig. 6
// (docs/design.md §6, §9 `rockfit summary`).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/io/manifest.hpp"
#include "rockfit/io/recording.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::io {

struct TrialRow {
  std::string trial_id;
  std::string block_id;
  std::string position;
  double b1_m = 0.0, b2_m = 0.0, h_m = 0.0;
  MetricsStatus status = MetricsStatus::kOk;  // of the metrics, or kLoadError
  std::string message;   // why a value is missing
  std::optional<double> opmf;
  std::optional<double> avrf;
  std::optional<double> lambda_equivalent;
  std::size_t avrf_peaks_used = 0;
  std::size_t impacts = 0;
  std::string mounting = "identity";  // the mounting applied (Recording::mounting)
  MountingCheck mounting_check;       // what the data say about it (Recording::mounting_check)
};

struct GroupRow {
  std::string block_id;
  std::string position;
  double b1_m = 0.0, b2_m = 0.0, h_m = 0.0;
  std::size_t n_trials = 0;
  // Mean and sample standard deviation (n − 1) over the trials that have the value; the std is absent when
  // fewer than two do, the mean when none does.
  std::size_t n_opmf = 0;
  std::optional<double> opmf_mean, opmf_std;
  std::size_t n_avrf = 0;
  std::optional<double> avrf_mean, avrf_std;
};

struct CampaignSummary {
  std::vector<TrialRow> trials;  // manifest order
  std::vector<GroupRow> groups;  // blocks in manifest order, positions in order of first appearance
};

TrialRow MakeTrialRow(const TrialSpec& trial, const BlockSpec& block, const MetricsSummary& metrics);
// A trial whose files could not be read: status load_error and the reader's message.
TrialRow MakeFailedTrialRow(const TrialSpec& trial, const BlockSpec& block, const std::string& message);

// Groups the rows per (block, position) with the statistics above.
std::vector<GroupRow> GroupTrials(const std::vector<TrialRow>& trials);

}  // namespace rockfit::io
