// A predictive check of a campaign's fits (fitting/README.md, "Predictive check"): does a block's λ, λ_lat, λ_lon,
// fitted on some releases, describe a release they were not fitted on? That is what an earthquake prediction with
// the fitted parameters assumes.
//
// For every trial of a block and position with at least one other trial: the group's pooled λ, λ_lat, λ_lon are
// taken from the *other* trials' own fits (PoolTrials, group_pooling.hpp; the mean of the others where none of
// them determines the parameter), only the left-out trial's release — t0, α and, where its problem fits it
// (release_roll_choice.hpp), its release roll β — is fitted with the impact parameters held there, over the window
// of its own fit, and the error (28) of that prediction is compared with the trial's own fit:
//
//   ratio = ε_pred / ε_own  (1: the pooled parameters fit the trial as well as its own; ≫ 1: they do not transfer),
//
// and for each of λ, λ_lat, λ_lon whether the trial's own 95 % interval overlaps the pooled 95 % interval of the
// others. Per group: the median and largest ratio and how many trials overlap in every parameter.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "rockfit/fitting/fit_campaign.hpp"
#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/group_pooling.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/parameters.hpp"

namespace rockfit::fitting {

// The impact parameters the check pools and holds, in this order.
inline constexpr std::array<ParameterId, 3> kPooledImpactParameters = {ParameterId::kLambda, ParameterId::kLambdaLat,
                                                                       ParameterId::kLambdaLon};

// One trial's own fit, as the check needs it.
struct OwnFit {
  std::string trial, block, position;
  ParameterSet values;                                 // every parameter at the fit
  std::array<Interval, kNumParameters> interval_95{};  // NaN ends: open (or no interval)
  std::array<bool, kNumParameters> determined{};       // `determined` yes
  double epsilon_rad_s = 0.0;                          // ε (28) of the own fit
  bool feasible = true;
  std::string message;                                 // why there is no feasible own fit
  double t_end_s = std::numeric_limits<double>::quiet_NaN();  // end of the own fit's window (NaN: the problem's)
};
OwnFit OwnFitFromSummary(const std::string& trial, const std::string& block, const std::string& position,
                         const FitSummary& summary);

struct PredictiveCheckOptions {
  // Nelder–Mead evaluations of each fit of t0 and α (two starts: the own fit's values and the data estimate).
  int max_evaluations = 600;
  // The ratio above which a trial's prediction is reported as not transferring (a flag in the table and JSON).
  double ratio_warning = 1.5;
  int num_threads = 0;  // trials predicted at once (0: all cores)
  void Validate() const;  // throws InvalidArgument
};

struct TrialPrediction {
  std::string trial, block, position;
  bool predicted = false;   // false: no other trial in the group, or the own fit is infeasible
  std::string message;      // why not predicted, or a failure of the prediction's model
  int n_others = 0;
  std::array<PooledEstimate, 3> pooled{};  // per kPooledImpactParameters, from the other trials
  std::array<double, 3> held{};            // the values held in the prediction (pooled, else the others' mean)
  std::array<bool, 3> overlaps{};          // own 95 % interval ∩ pooled 95 % interval ≠ ∅ (false when either is missing)
  bool overlaps_all = false;
  double t0_s = 0.0, alpha_rad = 0.0;      // fitted with the impact parameters held
  // The release roll β of the prediction: fitted with t0 and α where the trial's problem fits it (the choice of
  // --release-roll-mode, as for the own fit), else the value the problem holds (0 unless fixed otherwise).
  double release_roll_rad = 0.0;
  bool release_roll_fitted = false;
  double t_end_s = 0.0;                    // end of the window of ε_pred and ε_own (recording time)
  // ε_own: the own fit's ε, taken again over the problem's window at the own fit's values where the own fit
  // ended its window elsewhere (an extended window); ε_pred over the same window.
  double epsilon_own_rad_s = 0.0, epsilon_pred_rad_s = 0.0;
  double ratio = 0.0;                      // ε_pred / ε_own
  bool transfers = false;                  // ratio ≤ ratio_warning
  std::int64_t simulations = 0;            // model runs of the prediction
};

struct GroupValidation {
  std::string block, position;
  int n = 0, n_predicted = 0, n_overlap_all = 0, n_transfer = 0;
  double median_ratio = 0.0, max_ratio = 0.0;  // over the predicted trials (NaN when none)
};

struct ValidationSummary {
  std::vector<TrialPrediction> trials;  // in the order given
  std::vector<GroupValidation> groups;  // sorted by block, position
  PredictiveCheckOptions options;
  std::int64_t simulations = 0;
  double wall_time_s = 0.0;
};

// The own fits of a campaign's trials (fit_campaign.hpp's trials: each prepared and fitted on a worker, in memory,
// num_threads at a time, 0: all cores). A trial that cannot be prepared or fitted gets feasible = false and the
// message.
std::vector<OwnFit> FitOwnTrials(const std::vector<CampaignTrial>& trials, int num_threads = 0);

// Runs the check over `fits`; `problem(i)` builds trial i's problem as its own fit had it (objective: signal,
// window, model, bounds and which of t0, α, β are free; start: the data estimate), called on a worker thread only
// for trials that are predicted. Both ε are over the problem's window: where the own fit ended its window elsewhere
// (fits[i].t_end_s, a window the fit extended) its ε is taken again there. An exception from `problem` fails that trial only (message).
ValidationSummary RunPredictiveCheck(const std::vector<OwnFit>& fits,
                                     const std::function<PreparedTrial(std::size_t)>& problem,
                                     const PredictiveCheckOptions& options = {});

// Leave-one-out pooling alone: the pooled estimates of the impact parameters over every trial of `fits` in the
// group of fits[left_out] except that one.
std::array<PooledEstimate, 3> PoolOthers(const std::vector<OwnFit>& fits, std::size_t left_out, int* n_others = nullptr);

// {"trials": [...], "groups": [...], "ratio_warning", "simulations", "wall_s"} with documented keys
// (fitting/README.md, "Predictive check").
std::string ValidationJson(const ValidationSummary& summary);

}  // namespace rockfit::fitting
