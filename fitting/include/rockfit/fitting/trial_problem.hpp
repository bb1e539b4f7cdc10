// The fitting problem of one recorded trial, ready for Fit(): the data estimate (initial_guess.hpp), the gyro
// bias measured at rest removed from the signal, the window [t0, t_end] and the hybrid simulator as the model.
// `rockfit fit` and `rockfit batch` build their problems here (tools/app/src/fit_setup.cpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/gyro_clipping.hpp"
#include "rockfit/fitting/initial_guess.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/release_roll_choice.hpp"
#include "rockfit/fitting/rest_noise.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "rockfit/fitting/trajectory_model.hpp"

namespace rockfit::fitting {

struct TrialProblemOptions {
  InitialGuessOptions guess;
  // Subtract the mean ω over the samples at rest (from the start of the recording to rest_margin_s before the
  // estimated release, when that lasts at least rest_min_duration_s). A constant gyro bias of 0.3 deg/s
  // otherwise shifts the fitted t0 by milliseconds: (28) absorbs it into the shape of phase 1.
  bool subtract_rest_bias = true;
  double rest_margin_s = 0.05;
  double rest_min_duration_s = 0.1;
  // A detected window ends this long before the impact that ends it (a simulated impact right at t_end moves in
  // and out of the window with the parameters and makes ε jump). Not applied to a given t_end. The later window
  // ends (window_extension.hpp) end this long before the later return impacts.
  double window_end_margin_s = 0.012;
  std::optional<double> t_end_s;  // given end of the window (recording time)
  // Samples at the gyro's full scale enter (28) as censored (or are left out, `censored` false); the noise floor
  // and the phase-1 estimate pass over them.
  GyroClippingOptions clipping;
  // Whether the release roll β is fitted (release_roll_choice.hpp): `auto` frees it when the fall shows a roll,
  // when `parameters` holds it fixed at 0. A β that `parameters` frees is fitted (mode on) and, when its value is 0,
  // started from the data; a β fixed at another value stays as given (mode off).
  ReleaseRollChoiceOptions release_roll;
  void Validate() const;          // throws InvalidArgument
};

struct TrialProblem {
  Objective objective;          // the bias-corrected signal, the window, the model, the bounds
  ParameterSet start;           // the data estimate (fixed parameters at their values), inside the bounds
  InitialGuess guess;           // on the corrected signal
  Eigen::Vector3d rest_bias_rad_s = Eigen::Vector3d::Zero();
  bool bias_subtracted = false;
  GyroClipping clipping;        // the samples at the gyro's full scale, marked excluded in the objective's signal
  ReleaseRollChoice release_roll;  // whether β is fitted, why, and its start
  std::vector<std::string> notes;  // the guess's notes and the bias
};

// The rest segment before the release (rest_noise.hpp, with the options' margin and minimum duration) placed from the
// release of the closed-form phase-1 fit (EstimateRelease with InitialGuessOptions::closed_form_fall), when it is
// provably the segment that the default fit's t0 would place: the same samples, the same verdict on the minimum
// duration and the same duration to the note's 2 decimals for every t0 within 1e-6 s of it (the two fits agree to
// ~1e-8 s), and a usable sample after the first impact. nullopt when in doubt or without a rest segment: the caller
// then places it from EstimateInitialGuess. Throws BadInput as EstimateRelease does.
std::optional<RestNoise> RestBeforeClosedFormRelease(const MeasuredSignal& signal, const core::Block& block,
                                                     const ParameterSet& parameters, const TrialProblemOptions& options);

// The objective carries the later window ends, just before the later return impacts (none for a given t_end).
// `model` defaults to the hybrid simulator for `block`. t0 bounds left open in `parameters` are narrowed to
// [start of the recording, first impact]. Throws BadInput when the recording shows no release, InvalidArgument
// for a given t_end outside (t0, end of the recording].
TrialProblem PrepareTrialProblem(const MeasuredSignal& recorded, const core::Block& block,
                                 const ParameterSet& parameters, const TrialProblemOptions& options = {},
                                 std::shared_ptr<const TrajectoryModel> model = nullptr);

}  // namespace rockfit::fitting
