// The outcome of fitting one trial: values, bounds, fixed flags, standard errors, ε of (28) at the start and
// the end, effort, termination and warnings (docs/design.md §7).
#pragma once

#include <string_view>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/gyro_scale_estimate.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/lateral_motion_check.hpp"
#include "rockfit/fitting/model_error.hpp"
#include "rockfit/fitting/motion_before_release.hpp"
#include "rockfit/fitting/release_roll_choice.hpp"
#include "rockfit/fitting/release_tilt_check.hpp"
#include "rockfit/fitting/uncertainty.hpp"
#include "rockfit/fitting/window_extension.hpp"

namespace rockfit::fitting {

// What a warning is about; the string form ("at_bound", …) is used only at the edges (JSON, HDF5, text).
enum class WarningKind {
  kAtBound,                    // "at_bound"
  kNotIdentifiable,            // "not_identifiable"
  kSimulationFailures,         // "simulation_failures"
  kNotConverged,               // "not_converged"
  kStdErrorUnavailable,        // "std_error_unavailable"
  kInfeasible,                 // "infeasible"
  kPoorFit,                    // "poor_fit"
  kSecondBasin,                // "second_basin"
  kNotDetermined,              // "not_determined"
  kMovedByIntervals,           // "moved_by_intervals"
  kLateralMotionUnexplained,   // "lateral_motion_unexplained"
  kMovedByLateralRescan,       // "moved_by_lateral_rescan"
  kModelErrorDominates,        // "model_error_dominates"
  kWindowExtended,             // "window_extended"
  kReleaseTiltDisagrees,       // "release_tilt_disagrees"
  kTurnedBeforeFall,           // "turned_before_fall"
  kMovingAtRelease,            // "moving_at_release"
  kSensorTurnedAboutZ,         // "sensor_turned_about_z"
};
const char* ToString(WarningKind kind);
bool FromString(std::string_view text, WarningKind* value);  // the inverse of ToString

struct FitWarning {
  WarningKind kind = WarningKind::kNotConverged;
  std::string parameter;  // empty when the warning is not about one parameter
  std::string message;    // one sentence for people
};

// One stage of the pipeline (data estimate, global stage, Nelder–Mead, Ceres, …).
struct StageReport {
  std::string name;
  double epsilon_rad_s = 0.0;  // (28) at the stage's best point
  std::int64_t evaluations = 0;
  double wall_time_s = 0.0;
  TerminationType termination_type = TerminationType::kNotASearch;
  std::string termination;
};

struct FitSummary {
  FitMethod method = FitMethod::kAuto;
  ParameterSet start;       // where the local search started (data estimate or given values)
  ParameterSet parameters;  // the result (fixed parameters unchanged)
  // Per ParameterId; NaN where not available (fixed, at a bound, not identifiable, rank-deficient).
  PerParameter std_error{};
  std::array<bool, kNumParameters> identifiable{};  // true for fixed parameters
  std::array<bool, kNumParameters> at_bound{};
  // 68 % / 95 % intervals, "determined", correlation and what the data fix (uncertainty.hpp).
  UncertaintySummary uncertainty;
  // Whether the model at the fit reproduces the recorded out-of-plane motion (lateral_motion_check.hpp).
  LateralMotionCheck lateral_motion;
  // How much of ε the sensor noise at rest explains and how much is model error (model_error.hpp).
  ModelErrorStatement model_error;
  // The recorded motion just before the fitted t0, where the model is at rest (motion_before_release.hpp).
  MotionBeforeRelease motion_before_release;
  // The gyro scale projected out of the fit, with its 95 % interval (gyro_scale_estimate.hpp); mode kOff when
  // FitOptions::gyro_scale is off.
  GyroScaleEstimate gyro_scale;
  // Whether the release roll was fitted and why (release_roll_choice.hpp): set by whoever prepared the problem
  // from the recording (trial_problem.hpp); empty for a fit of an objective made otherwise.
  std::optional<ReleaseRollChoice> release_roll_choice;
  // The fitted α against the tilt at rest from the accelerometer (release_tilt_check.hpp): set, with
  // AttachReleaseTiltCheck, by whoever has the recording; empty for a fit of an objective made otherwise.
  std::optional<ReleaseTiltCheck> release_tilt;

  double epsilon_initial_rad_s = 0.0;  // (28) at `start`
  double epsilon_rad_s = 0.0;          // (28) at `parameters`
  bool feasible = false;               // the model runs at `parameters`
  double t_end_s = 0.0;                // end of the fitting window (recording time)
  // Where the first window ended, whether and why it was extended (window_extension.hpp); window.t_end_s = t_end_s.
  WindowReport window;

  std::int64_t simulations = 0;  // model runs of the whole fit
  double simulations_per_second = 0.0;
  double wall_time_s = 0.0;
  TerminationType termination_type = TerminationType::kFailure;  // of the stage whose point was kept
  std::string termination;  // the same in words (the back end's message)
  bool converged = false;
  std::string kept_stage;   // name of the stage whose point was kept

  std::map<std::string, std::int64_t> failures_by_reason;  // infeasible points by reason
  std::vector<StageReport> stages;
  std::vector<FitWarning> warnings;
  std::string model_description;

  bool HasWarning(WarningKind kind, const std::string& parameter = "") const;
  // One line: ε, time, simulations, termination.
  std::string BriefReport() const;
  // A table of parameters and every stage and warning, for terminals.
  std::string FullReport() const;
  // One JSON object with the documented keys (see fitting/README.md): parameters (value, lower, upper, fixed,
  // std_error, identifiable, at_bound, unit), epsilon, epsilon_initial, t_end, simulations, wall_s,
  // termination, warnings, …; `trial` is added when not empty.
  std::string ToJson(const std::string& trial = "") const;
};

}  // namespace rockfit::fitting
