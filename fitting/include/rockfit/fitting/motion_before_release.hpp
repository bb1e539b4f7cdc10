// Was the block already moving when the fit releases it? (fitting/README.md, "Motion before the release")
//
// The model releases the block from rest at t0: its ω is zero before t0 and (28) looks only at [t0, t_end]. A hand
// that pushes the block as it lets go starts the motion earlier and faster than a release from rest can; the fit
// then puts t0 later, where a release from rest best matches what follows, and the recorded motion before that t0
// is seen by nothing in (28). When the push also leaves no stop at the top (the tilt check's turn before the fall,
// release_tilt_check.hpp, measures the turn between the rest and a stop), ε, the tilt at rest and the rest
// detection can all miss it.
//
// This measures the motion the recording shows just before the fitted t0, on the signal as (28) sees it (the
// gyro bias removed by the problem, trial_problem.hpp):
//
//   turn = max over t in [t0 − lookback, t0] of ‖∫_t^t0 ω_m dt‖   (trapezoids of the linear interpolant),
//
// the farthest the block was, within the lookback, from where it stood at the fitted release. A release from rest
// fitted a few milliseconds late turns by ½·θ̈·δt² (micro-radians); noise integrates to less. Above
// `warn_turn_deg` the fit is warned about (`moving_at_release`).
#pragma once

#include <string>

#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

struct MotionBeforeReleaseOptions {
  bool enabled = true;
  // How far back from the fitted t0 to look [s]: long enough that a hand's motion of 0.05 rad/s turns the block
  // by 0.3° in it, short enough to stay within the last moments before the release.
  double lookback_s = 0.1;
  // A turn above this is warned about [deg] (1.7 mrad, about the standard error of the tilt at rest): 13 × the
  // largest turn before a fitted t0 that is not late (sample, synthetic and MuJoCo fits; fitting/README.md).
  double warn_turn_deg = 0.1;
  void Validate() const;  // throws InvalidArgument
};

struct MotionBeforeRelease {
  bool available = false;              // the recording has samples before the fitted t0
  double t0_s = 0.0;                   // the fitted release (recording time)
  double lookback_s = 0.0;             // the stretch looked at: min(options.lookback_s, t0 − first sample) [s]
  double turn_deg = 0.0;               // the farthest turn within it, from where the block stood at t0 [deg]
  double rate_at_release_rad_s = 0.0;  // ‖ω_m(t0)‖, linearly interpolated (the model's is 0) [rad/s]
  bool moving = false;                 // turn_deg > options.warn_turn_deg
};

// Never throws for a short or empty signal (available = false); InvalidArgument for bad options or a t0 that is
// not finite.
MotionBeforeRelease MeasureMotionBeforeRelease(const MeasuredSignal& signal, double t0_s,
                                               const MotionBeforeReleaseOptions& options = {});

// {"available", "t0_s", "lookback_s", "turn_deg", "rate_at_release_rad_s", "moving"} (numbers and `moving` null
// when not available), for the fit JSON of the library, the command line and Python.
std::string MotionBeforeReleaseJson(const MotionBeforeRelease& m);

// One line for tables: "turned 0.004° (0.07 mrad) in the 0.10 s before t0 = 1.2345 s, 0.012 rad/s at t0", or why
// it was not measured.
std::string MotionBeforeReleaseText(const MotionBeforeRelease& m);

// The warning's sentence for a measurement with `moving` set.
std::string MotionBeforeReleaseWarning(const MotionBeforeRelease& m);

}  // namespace rockfit::fitting
