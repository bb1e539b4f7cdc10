// Fitting every trial of a campaign manifest into one HDF5 file (DESIGN §7, §8; `rockfit batch`).
//
// Trials run in parallel (TBB, `jobs` at a time, one thread each). Each finished trial is written at once to its
// own small HDF5 file in a side directory `<output>.parts/` (atomically: temporary file, fsync, rename), so a kill
// at any moment loses at most the trials still running. When all are done, the parts are merged into <output> in
// one atomic rewrite (io::hdf5::Transaction, which keeps everything else the file held) and the side directory is
// removed. A failing trial (unreadable files, no impact, a fit that finds no feasible point, …) is recorded with
// its message and does not stop the others.
//
// Resume: with `resume`, a trial is skipped when <output> or the side directory holds a successful fit of it
// with the same settings hash (fit_settings.hpp); everything else is fitted again. Without `resume` the side
// directory is cleared first and every trial is fitted.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trial_fit.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::fitting {

struct BatchOptions {
  ParameterSet parameters = ParameterSet::Defaults();  // bounds and fixed flags for every trial
  TrialFitOptions trial;       // fit.num_threads is set to 1: the parallelism is over trials
  int jobs = 0;                // trials at a time; 0 = all cores
  bool resume = false;
  std::string rockfit_version;
  std::vector<std::string> only_trials;  // empty: every trial of the manifest
  void Validate() const;       // throws InvalidArgument
};

struct BatchTrialResult {
  std::string trial_id;
  std::string status;   // "ok", "failed", "skipped" (resumed)
  std::string message;  // why it failed
  double epsilon_rad_s = 0.0;
  double wall_time_s = 0.0;
  std::int64_t simulations = 0;
  std::size_t warnings = 0;
};

struct BatchReport {
  std::vector<BatchTrialResult> trials;  // manifest order
  std::size_t ok = 0, failed = 0, skipped = 0;
  double wall_time_s = 0.0;
  std::filesystem::path output;
};

// Reads a trial's recording (tools pass their reader, which knows every format and the manifest's options).
using TrialLoader = std::function<io::Recording(const io::TrialSpec&)>;
// Called (from one thread at a time) after each trial, with the number finished so far.
using BatchProgress = std::function<void(const BatchTrialResult&, std::size_t finished, std::size_t total)>;

// OutputError when the output or its side directory cannot be written.
BatchReport RunBatch(const io::Manifest& manifest, const std::filesystem::path& output, const BatchOptions& options,
                     const TrialLoader& load, const BatchProgress& progress = {});

// The side directory of an output file: "<output>.parts".
std::filesystem::path PartsDirectory(const std::filesystem::path& output);

// Settings hash of one manifest trial under `options` (what --resume compares).
std::string TrialSettingsHash(const io::TrialSpec& trial, const io::BlockSpec& block, const BatchOptions& options,
                              std::string* settings_json = nullptr);

}  // namespace rockfit::fitting
