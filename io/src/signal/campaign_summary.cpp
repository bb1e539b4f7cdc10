#include "rockfit/io/campaign_summary.hpp"

#include <algorithm>
#include <cmath>

namespace rockfit::io {

namespace {

TrialRow BaseRow(const TrialSpec& trial, const BlockSpec& block) {
  TrialRow row;
  row.trial_id = trial.id;
  row.block_id = block.id;
  row.position = trial.position;
  row.b1_m = block.b1_m;
  row.b2_m = block.b2_m;
  row.h_m = block.h_m;
  return row;
}

struct Stats {
  std::size_t n = 0;
  std::optional<double> mean, std;
};

// Mean and sample standard deviation (two-pass, n − 1 in the denominator).
Stats MeanAndSampleStd(const std::vector<double>& values) {
  Stats s;
  s.n = values.size();
  if (s.n == 0) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / static_cast<double>(s.n);
  s.mean = mean;
  if (s.n < 2) return s;
  double squares = 0.0;
  for (double v : values) squares += (v - mean) * (v - mean);
  s.std = std::sqrt(squares / static_cast<double>(s.n - 1));
  return s;
}

}  // namespace

TrialRow MakeTrialRow(const TrialSpec& trial, const BlockSpec& block, const MetricsSummary& metrics) {
  TrialRow row = BaseRow(trial, block);
  row.status = metrics.status;
  row.message = metrics.message;
  if (metrics.opmf.ok()) row.opmf = metrics.opmf.opmf;
  if (metrics.avrf.ok()) {
    row.avrf = metrics.avrf.avrf;
    row.lambda_equivalent = metrics.avrf.lambda_equivalent;
  }
  row.avrf_peaks_used = metrics.avrf.peaks_used;
  row.impacts = metrics.correction.impacts_y.size();
  return row;
}

TrialRow MakeFailedTrialRow(const TrialSpec& trial, const BlockSpec& block, const std::string& message) {
  TrialRow row = BaseRow(trial, block);
  row.status = MetricsStatus::kLoadError;
  row.message = message;
  return row;
}

std::vector<GroupRow> GroupTrials(const std::vector<TrialRow>& trials) {
  std::vector<GroupRow> groups;
  // Blocks in order of first appearance, then positions in order of first appearance within the block.
  std::vector<std::string> block_order;
  for (const TrialRow& t : trials) {
    if (std::find(block_order.begin(), block_order.end(), t.block_id) == block_order.end()) block_order.push_back(t.block_id);
  }
  for (const std::string& block : block_order) {
    std::vector<std::string> positions;
    for (const TrialRow& t : trials) {
      if (t.block_id == block && std::find(positions.begin(), positions.end(), t.position) == positions.end()) {
        positions.push_back(t.position);
      }
    }
    for (const std::string& position : positions) {
      GroupRow g;
      g.block_id = block;
      g.position = position;
      std::vector<double> opmf, avrf;
      for (const TrialRow& t : trials) {
        if (t.block_id != block || t.position != position) continue;
        g.b1_m = t.b1_m, g.b2_m = t.b2_m, g.h_m = t.h_m;
        ++g.n_trials;
        if (t.opmf) opmf.push_back(*t.opmf);
        if (t.avrf) avrf.push_back(*t.avrf);
      }
      const Stats o = MeanAndSampleStd(opmf), a = MeanAndSampleStd(avrf);
      g.n_opmf = o.n, g.opmf_mean = o.mean, g.opmf_std = o.std;
      g.n_avrf = a.n, g.avrf_mean = a.mean, g.avrf_std = a.std;
      groups.push_back(g);
    }
  }
  return groups;
}

}  // namespace rockfit::io
