// The fitting library's part of an HDF5 file (docs/design.md §8; layout in fitting/README.md, "HDF5 layout
// /fits/<trial>", and docs/file-formats.md §5): one group /fits/<trial> per fitted trial and the campaign tables
// /summary/fits/per_trial and /summary/fits/per_group rebuilt from all of them. Writers take a group of an open
// file (the caller wraps them in an io::hdf5::Transaction); readers take a group or a path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/group_pooling.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::fitting {

// The parameters of the campaign tables, in their column order.
inline constexpr const char* kSummaryParameters[] = {"t0", "alpha", "lambda", "lambda_lat", "lambda_lon", "tau_edge"};

// The `settings_hash` stored with each fit: FNV-1a 64 of the canonical settings text, as 16 hex digits.
std::string SettingsHash(const std::string& settings);

// Writes /fits/<trial> under `root` (the group must not exist: callers replace it through the transaction). The
// objective is the one that was fitted (its nodes of (28) and the model at the result are stored); `settings` is
// the canonical text of every setting that changed the result (stored with its SettingsHash).
void WriteFitGroup(const io::hdf5::Group& root, const std::string& trial, const io::TrialLabels& labels,
                   const Objective& objective, const std::string& settings, const FitSummary& summary);

// /fits/<trial>/parameters read back: parallel columns, one row per parameter. A file written before the
// intervals existed reads NaN intervals and empty `determined`.
struct StoredParameters {
  std::vector<std::string> name, unit, determined;
  std::vector<double> value, lower, upper;
  std::vector<double> interval_68_lower, interval_68_upper, interval_95_lower, interval_95_upper;  // NaN: open
  std::vector<bool> fixed;      // held fixed in the fit (false for a file without the column)
  bool has_intervals = false;   // the file has the interval columns (written since the intervals exist)
  std::size_t size() const { return name.size(); }
  // The row of `parameter` ("alpha", …), or size() when the table has none.
  std::size_t Row(const std::string& parameter) const;
};
// `fit` is the group /fits/<trial>. BadInput when its columns have different lengths.
StoredParameters ReadFitParameters(const io::hdf5::Group& fit);

// The attributes of /fits/<trial> that campaigns use (absent ones: empty, NaN, 0; `feasible` true;
// model_error_dominates -1).
struct StoredFitLabels {
  std::string block, position, settings_hash, mounting;
  bool feasible = true;
  double epsilon_rad_s = 0.0, wall_s = 0.0;
  std::int64_t simulations = 0;
  // The model-error statement (model_error.hpp); NaN and -1 when not measured or written before it existed.
  double noise_floor_rad_s = 0.0, model_error_rad_s = 0.0, noise_share = 0.0;
  std::int64_t model_error_dominates = -1;  // 1 yes, 0 no, -1 not measured
  // The check of α against the tilt at rest (release_tilt_check.hpp); NaN, -1 and "" when not compared or written
  // before it existed.
  double release_tilt_z = 0.0;
  std::int64_t release_tilt_consistent = -1;  // 1 yes, 0 no, -1 not compared
  std::string release_tilt_check;
};
StoredFitLabels ReadFitLabels(const io::hdf5::Group& fit);

// The trials of /fits in name order (none when the file has no /fits).
std::vector<std::string> StoredFitTrials(const io::hdf5::Group& root);

// trial → settings_hash of every fit in the file at `path` (empty when the file does not exist, is not HDF5 or
// has no /fits): what a resumed campaign compares with.
std::map<std::string, std::string> StoredSettingsHashes(const std::filesystem::path& path);

// One (block, position) row of /summary/fits/per_group: per parameter the mean and spread of the trials' values
// and their pooled estimate (PoolTrials).
struct GroupSummary {
  std::string block, position;
  std::int64_t n = 0;
  std::map<std::string, double> mean, std_dev;  // std_dev: between trials, NaN for n = 1
  std::map<std::string, PooledEstimate> pooled;
};

// Rebuilds /summary/fits/per_trial and /summary/fits/per_group from every /fits/<trial> under `root` (the groups
// must not exist: callers replace /summary/fits through the transaction). Returns the per-group rows.
std::vector<GroupSummary> WriteFitSummaryTables(const io::hdf5::Group& root);

// /summary/fits/per_group read back (pooled: value, 95 % interval, n_pooled, χ²/dof, consistency; n_trials is
// the group's n). A parameter column the table lacks reads NaN (counts 0). BadInput when `root` has no such table,
// no `n` column, or a column shorter than the table.
std::vector<GroupSummary> ReadFitGroupSummaries(const io::hdf5::Group& root);
// Whether `root` holds /summary/fits/per_group.
bool HasFitGroupSummaries(const io::hdf5::Group& root);

}  // namespace rockfit::fitting
