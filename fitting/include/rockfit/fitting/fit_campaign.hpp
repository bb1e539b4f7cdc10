// Fits of a whole campaign into one HDF5 file (docs/design.md §7, §8): the trials run in parallel on a TBB arena,
// each finished trial is committed by its own io::hdf5::Transaction (/fits/<trial> and /summary/fits replaced,
// the writers serialised by a mutex), so a kill at any moment leaves the file as of the last finished trial, and a
// resumed campaign skips the trials the file holds with the same settings (fit_store.hpp, SettingsHash).
//
//   fitting::CampaignOptions options;
//   options.num_threads = 4;
//   options.resume = true;
//   const fitting::CampaignSummary s = fitting::FitCampaign(trials, "fits.h5", options,
//       [](const fitting::TrialOutcome& o, double elapsed_s) { ... });
#pragma once

#include <string_view>

#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/fitting/model_error.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/release_roll_choice.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::fitting {

struct CampaignOptions {
  int num_threads = 0;          // trials fitted at once, at most the cores (0: all cores)
  bool resume = false;          // skip trials whose stored settings_hash equals the hash of their settings
  std::string rockfit_version;  // the root attribute rockfit_version written with each trial (io::WriteFileAttributes)
  void Validate() const;        // InvalidArgument naming the bad option
};

// One trial's problem, ready to fit.
struct PreparedTrial {
  Objective objective;
  ParameterSet start;
  FitOptions options;
  // The recording fitted; its mounting is stored with the fit (io::WriteMountingHdf5). May be null.
  std::shared_ptr<const io::Recording> recording;
  // Whether the release roll is fitted and why (trial_problem.hpp), stored with the fit. May be empty.
  std::optional<ReleaseRollChoice> release_roll_choice;
};

// One trial of a campaign. `settings` and `prepare` run on a worker thread; an exception from either (or from the
// fit or its commit) fails this trial only.
struct CampaignTrial {
  std::string id;  // the group /fits/<id>
  io::TrialLabels labels;
  // The canonical text of every setting that changes the fit (stored; its hash decides the resume).
  std::function<std::string()> settings;
  // Loads the recording and builds the problem; called only when the trial is fitted.
  std::function<PreparedTrial()> prepare;
};

enum class TrialStatus {
  kFitted,      // fitted and committed
  kSkipped,     // already in the file with the same settings (resume)
  kInfeasible,  // fitted and committed, but no parameters in the bounds let the model run
  kFailed,      // not fitted or not committed: see `error`
};
const char* ToString(TrialStatus status);  // "fitted", "skipped", "infeasible", "failed"
bool FromString(std::string_view text, TrialStatus* value);  // the inverse of ToString

struct TrialOutcome {
  std::string trial;
  TrialStatus status = TrialStatus::kFailed;
  std::string message;          // why the trial failed or is infeasible; empty otherwise
  std::exception_ptr error;     // the exception that failed it (kFailed only), for callers that classify errors
  double epsilon_rad_s = std::numeric_limits<double>::quiet_NaN();  // ε (28) of the fit; NaN when not fitted
  double fit_wall_s = 0.0;      // the fitter's own wall time (FitSummary::wall_time_s); 0 when not fitted
  ModelErrorStatement model_error;  // of the fit (not available when not fitted)
  bool ok() const { return status == TrialStatus::kFitted || status == TrialStatus::kSkipped; }
};

// Called once per trial as it ends (in the order the trials end, never two at once): its outcome and the wall time
// from its start to its end, reading, fitting and writing included [s].
using TrialEndCallback = std::function<void(const TrialOutcome& outcome, double elapsed_s)>;

struct CampaignSummary {
  std::vector<TrialOutcome> trials;  // in the order given
  std::size_t fitted = 0, skipped = 0, failed = 0;  // failed: kFailed and kInfeasible
  std::vector<GroupSummary> groups;  // /summary/fits/per_group as of the last commit (empty without one)
};

// Fits `trials` into the HDF5 file `output` (created or extended; other groups are kept). OutputError before any
// work when `output` cannot be written; InvalidArgument for bad options.
CampaignSummary FitCampaign(const std::vector<CampaignTrial>& trials, const std::filesystem::path& output,
                            const CampaignOptions& options, const TrialEndCallback& on_trial_end = {});

}  // namespace rockfit::fitting
