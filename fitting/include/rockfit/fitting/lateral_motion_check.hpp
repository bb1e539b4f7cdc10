// Does the model at the fit reproduce the recorded out-of-plane motion? (fitting/README.md, "Intervals")
//
// With weak lateral motion on a narrow block (|λ_lat| ≲ 0.5, b2 < b1) the error (28) has, next to the basin of
// the truth, a broad plateau of parameter sets whose model barely leaves the plane: the out-of-plane components
// ω_x, ω_z of the model stay near zero while the recording's do not. The truth's basin there is a needle (a
// change of λ_lat by 10⁻³ changes the sequence of contact modes), which the global stage can miss; the fitter
// then searches it once more (lateral_rescan.hpp). Such a fit has a near-optimal in-plane component ω_y but
// leaves most of the out-of-plane signal in the residual.
//
// The check compares, over the fitting window (weights of (28)), the variance of the out-of-plane residual and
// of the out-of-plane measured signal with the variance of the gyro noise measured at rest before the release:
//
//   unexplained = (RMS²(ω_m − ω_s)_xz − σ²_rest) / (RMS²(ω_m)_xz − σ²_rest),
//
// the part of the out-of-plane signal (above the noise) that the model does not reproduce. A fit is flagged
// when there is out-of-plane signal to explain (RMS²(ω_m)_xz ≥ min_signal_to_noise_variance·σ²_rest) and
// unexplained ≥ max_unexplained_fraction. Then λ and λ_lat are not determined by this fit (their values are those
// of the plateau), and the fit says so.
#pragma once

#include <string>

#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

struct LateralMotionCheckOptions {
  bool enabled = true;
  // The rest before the release: samples from the start of the recording to t0 − rest_margin_s, at least
  // rest_min_duration_s long (as the bias at rest is measured).
  double rest_margin_s = 0.05;
  double rest_min_duration_s = 0.1;
  // Out-of-plane signal variance over the noise variance at rest below this: nothing to explain (the block
  // barely left the plane, or the noise at rest is not representative).
  double min_signal_to_noise_variance = 2.0;
  // Fraction of the out-of-plane signal variance (above the noise) left in the residual that flags the fit.
  // On the coverage study, fits in the truth's basin leave ≤ 0.16, fits on the plateau 0.63–0.96.
  double max_unexplained_fraction = 0.35;
  void Validate() const;  // throws InvalidArgument
};

struct LateralMotionCheck {
  bool available = false;  // false: no rest segment, or the model fails at the fit
  double rest_noise_rad_s = 0.0;           // σ_rest, RMS of ω_x and ω_z at rest about their means
  double measured_rms_rad_s = 0.0;         // RMS of the measured ω_x, ω_z in the window
  double residual_rms_rad_s = 0.0;         // RMS of the residual ω_x, ω_z in the window
  double unexplained_fraction = 0.0;       // see the header (0 when there is no signal to explain)
  bool judged = false;                     // there was out-of-plane signal to explain (available too)
  bool unexplained = false;                // the fit is flagged
};

// {"available", "rest_noise_rad_s", "measured_rms_rad_s", "residual_rms_rad_s", "unexplained_fraction", "judged",
// "unexplained"} (numbers null when not available), for the fit JSON of the library and the command line.
std::string LateralMotionJson(const LateralMotionCheck& check);

// The check at `fitted` (values of every parameter) on the objective's signal and window. Never throws for
// numerical trouble (available = false instead).
LateralMotionCheck CheckLateralMotion(const Objective& objective, const ParameterSet& fitted,
                                      const LateralMotionCheckOptions& options = {});

}  // namespace rockfit::fitting
