// How much of the fitted error (28) the sensor noise explains, and how much is model error
// (fitting/README.md, "Model error").
//
// The noise floor ε_noise is the error (28) that the gyro noise alone makes: the mean of ‖ω_k − bias‖ over the
// samples at rest before the estimated release (rest_noise.hpp). A model that reproduced the motion exactly would reach
// about this ε. Noise and model error are independent and add in quadrature, ε² ≈ ε_noise² + ε_model² (exact
// for isotropic Gaussian errors, whose mean norm is proportional to their RMS), so
//
//   noise_share   = min(1, ε_noise² / ε²)          the share of ε² that the noise explains,
//   ε_model       = √max(0, ε² − ε_noise²)         the model error on the scale of (28),
//   dominates     = noise_share < 1 − dominance_share   (the default: ε_model > ε_noise, i.e. ε > √2·ε_noise).
//
// "Model error" is everything that white noise at rest does not explain: a body, base or contact that is not
// the paper's rigid cuboid, a sensor whose scale, axes or clock are off, ringing of the sensor after impacts,
// and a fit that missed the global minimum. A fit whose ε exceeds twice the noise floor is always flagged.
#pragma once

#include <cstddef>
#include <string>

#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/rest_noise.hpp"

namespace rockfit::fitting {

struct ModelErrorOptions {
  bool enabled = true;
  // The rest before the release (as the gyro bias is measured): from the start of the recording to the data
  // estimate of t0 − margin, at least min_duration long.
  RestSegmentOptions rest;
  // Model error dominates when it explains more than this share of ε² (0.5: ε_model > ε_noise).
  double dominance_share = 0.5;
  void Validate() const;  // throws InvalidArgument
};

struct ModelErrorStatement {
  bool available = false;          // false: no rest segment long enough, or ε not finite
  double epsilon_rad_s = 0.0;      // the fitted (28)
  double noise_floor_rad_s = 0.0;  // ε_noise: (28) of the noise at rest alone
  double ratio = 0.0;              // ε / ε_noise
  double noise_share = 0.0;        // share of ε² the noise explains, in [0, 1]
  double model_error_rad_s = 0.0;  // ε_model = √max(0, ε² − ε_noise²)
  bool dominates = false;          // model error explains more than dominance_share of ε²
  double rest_duration_s = 0.0;    // length of the rest segment used [s]
  std::size_t rest_samples = 0;
  // Samples of the recording at the gyro's full scale (clipped), censored in ε and left out of the noise floor
  // (gyro_clipping.hpp); counted whether or not the rest was measured.
  std::size_t clipped_samples = 0;
};

// The statement for a fit with error `epsilon_rad_s` on the objective's signal. The rest ends before the
// objective's start value of t0 — the data estimate of the release, as for the gyro bias (trial_problem.hpp) —,
// not before the fitted t0: a fit that model error drove far from the release would otherwise leave no rest.
// Never throws for numerical trouble (available = false instead).
ModelErrorStatement AssessModelError(const Objective& objective, double epsilon_rad_s,
                                     const ModelErrorOptions& options = {});

// {"available", "epsilon_rad_s", "noise_floor_rad_s", "ratio", "noise_share", "model_error_rad_s",
// "model_error_share", "dominates", "rest_duration_s", "rest_samples", "clipped_samples"} (numbers and `dominates` null when not
// available), for the fit JSON of the library, the command line and Python.
std::string ModelErrorJson(const ModelErrorStatement& statement);

// One line for tables: "ε = 1.87 × the noise floor 0.00279 rad/s (rest 2.28 s): the noise explains 29 % of ε²,
// model error 0.0044 rad/s dominates", or why it was not measured.
std::string ModelErrorText(const ModelErrorStatement& statement);

}  // namespace rockfit::fitting
