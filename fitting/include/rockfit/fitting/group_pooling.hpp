// The parameter range of one block and position from its trials (the paper's Sect. 5.2 reports ranges per block
// and position): a pooled estimate with its 95 % interval, the spread between trials and whether the trials
// agree within their own intervals (fitting/README.md, "Per block and position").
#pragma once

#include <vector>

#include "rockfit/fitting/uncertainty.hpp"

namespace rockfit::fitting {

// One trial's value of one parameter with its 95 % interval (NaN ends: open) and its determination.
struct TrialEstimate {
  double value = 0.0;
  Interval interval_95{};
  bool determined = false;  // `determined` yes: the interval is closed and enters the pooled estimate
};

struct PooledEstimate {
  int n_trials = 0;  // trials with a finite value
  int n_pooled = 0;  // of them, determined ones with a closed interval (the pooled estimate uses these)
  double pooled = 0.0;      // inverse-variance weighted mean, σ_i = (95 % width)/(2·1.96); NaN if n_pooled = 0
  Interval interval_95{};   // pooled ± 1.96·σ_pooled, widened by √(χ²/dof) when that exceeds 1 (Birge ratio)
  double spread = 0.0;      // sample standard deviation of the values of all trials (NaN for fewer than 2)
  double chi2_per_dof = 0.0;   // Σ((x_i − pooled)/σ_i)² / (n_pooled − 1); NaN for fewer than 2
  double consistency_p = 0.0;  // P(χ²_{n_pooled−1} ≥ χ²): below 0.05 the trials disagree beyond their intervals
};

PooledEstimate PoolTrials(const std::vector<TrialEstimate>& trials);

}  // namespace rockfit::fitting
