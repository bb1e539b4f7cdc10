// What `rockfit fit` and `rockfit batch` share: the fit options on the command line, the fitting problem of one
// recording (objective, data-driven start, window end), its settings text and the JSON of a result. The /fits
// HDF5 group is the fitting library's (rockfit/fitting/fit_store.hpp).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/fit_campaign.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/initial_guess.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/release_roll_choice.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::app {

struct FitArgs {
  std::string method = "auto";
  std::string bounds = "empirical";
  std::vector<std::string> free;   // parameter names, comma lists allowed
  std::vector<std::string> fix;
  std::vector<std::string> lower;  // NAME=V
  std::vector<std::string> upper;
  std::optional<double> t_end_s;
  int max_evaluations = 0;  // 0: the FitOptions default
  bool no_global = false;
  bool keep_bias = false;  // do not subtract the gyro bias measured at rest
  int threads = 0;
  std::string intervals = "thorough";  // none | fast | thorough (fitting::IntervalMethod)
  double model_error_widening = fitting::kDefaultModelErrorWidening;  // fitting::IntervalOptions (0: off)
  double t0_floor_samples = fitting::kDefaultT0FloorSamples;          // fitting::IntervalOptions (0: off)
  std::string estimate_gyro_scale = "off";  // off | common | per-axis (fitting::GyroScaleMode)
  // Estimate the release roll β (core/rolled_release.hpp) as a parameter: the same as --free release_roll or
  // --release-roll-mode on.
  bool fit_release_roll = false;
  // off | auto | on (fitting::ReleaseRollMode): auto fits β when the fall before the first impact shows a roll
  // (fitting/release_roll_choice.hpp). --fit-release-roll or --free release_roll make it on, --fix release_roll off.
  std::string release_roll_mode = "auto";
};

// The release-roll mode that `args` ask for (the rule above); InvalidArgument for an unknown --release-roll-mode.
fitting::ReleaseRollMode ReleaseRollModeOf(const FitArgs& args);

// --method, --bounds, --free, --fix, --lower, --upper, --t-end, --max-evaluations, --no-global, --keep-bias,
// --threads, --intervals, --model-error-widening, --t0-floor-samples, --estimate-gyro-scale, --fit-release-roll,
// --release-roll-mode (declared by tools/src/cli_common.cpp).

struct PreparedFit {
  fitting::Objective objective;
  fitting::ParameterSet start;  // the data estimate (fixed parameters at their values)
  fitting::FitOptions options;
  fitting::InitialGuess guess;
  std::string settings;  // canonical text of every setting that changes the result (for --resume)
  std::vector<std::string> notes;  // how the start and the window were found, the gyro bias
  fitting::ReleaseRollChoice release_roll_choice;  // whether the release roll is fitted and why
};

// One --fix entry: NAME (held at the data estimate) or NAME=VALUE.
struct FixEntry {
  fitting::ParameterId id = fitting::ParameterId::kT0;
  std::optional<double> value;
};
std::vector<FixEntry> ParseFixEntries(const FitArgs& args);

// The parameter set from the bound set and --free/--fix/--lower/--upper (InvalidArgument naming the bad entry).
// Parameters fixed without a value stay free here: the data estimate gives their value, PrepareFit fixes them.
fitting::ParameterSet MakeParameterSet(const FitArgs& args);

// The problem of one recording (fitting::PrepareTrialProblem): data estimate, gyro bias at rest removed,
// t_end (given, or just before the impact that ends phase 4), t0 bounds narrowed to [start of the recording,
// first impact] when they are unbounded.
PreparedFit PrepareFit(const io::Recording& recording, const core::Block& block, const FitArgs& args);

// The canonical text of every setting that changes a fit of `block` (not the recording): method, budget,
// window end, bounds and fixed flags, block geometry. Stored with each fit; --resume compares its hash
// (fitting::SettingsHash).
std::string FitSettingsText(const core::Block& block, const FitArgs& args);

// One trial of a manifest as the fitting library's campaigns take it (fitting::CampaignTrial): the settings of its
// block with the trial's mounting as the manifest gives it ("auto" included, it changes what is fitted), and a
// problem prepared on the worker from the recording, which `on_loaded` sees first (the caller's report of its
// mounting). `manifest` and `spec` must outlive the trial.
fitting::CampaignTrial MakeCampaignTrial(const io::Manifest& manifest, const io::TrialSpec& spec, const FitArgs& fit_args,
                                         std::function<void(const io::Recording&)> on_loaded = {});

// The documented JSON of one fit: trial, parameters (value, lower, upper, fixed, std_error, interval_68,
// interval_95, determined), correlation, uncertainty_method, uncertainty, lateral_motion, model_error, gyro_scale
// (only when estimated), epsilon, epsilon_initial, t_end, window, simulations, wall_s, termination, warnings.
nlohmann::json FitResultJson(const std::string& trial, const fitting::FitSummary& summary);

// A table for terminals.
std::string FitResultTable(const std::string& trial, const fitting::FitSummary& summary);

}  // namespace rockfit::app
