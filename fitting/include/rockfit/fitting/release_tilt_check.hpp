// The fitted release tilt α against the tilt at rest before the release, measured by the accelerometer (fitting/
// README.md, "The tilt at rest").
//
// Before the release the block leans on its release edge at α; the mounting estimate (io/mounting_estimate.hpp)
// reads that tilt from the accelerometer as the angle about the edge between gravity at rest before the release and
// gravity at rest after the rocking (the block flat), so it needs neither the block's dimensions nor the rocking
// model, and a level error of the table cancels. The fit's α comes from the motion: mostly from the fall time T(α)
// of the model's block. The two are independent measurements of one angle, and
//
//   z = (α_fit − α_rest) / √(σ_fit² + σ_rest²)
//
// says whether they agree. A large |z| points at what the fit's α rests on and the rest tilt does not: the block's
// dimensions (b1, b2, h), the release (a push, a hand that follows), or a model that does not fall like the block.
// The check only reports; it changes no fitted value. Without rest after the rocking the mounting's turn about
// block y is not fixed and the tilt at rest is the given mounting's: no comparison then.
#pragma once

#include <limits>
#include <string>

#include "rockfit/fitting/parameters.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::fitting {

struct FitSummary;

// |z| above which the two tilts disagree: 4 σ happens by noise alone about once in 16,000 fits. (On the 16 sample
// recordings |z| ≤ 1.5; σ_rest holds the estimate's scatter and a 0.02° calibration floor per direction, not an
// accelerometer's whole calibration, hence more than 3.)
inline constexpr double kReleaseTiltMaxZ = 4.0;

// A turn of the block between its rest and its fall above this [deg] is warned about (turned_before_fall): the fit's
// t0 and α are then those of the fall from where the block stopped, not of the release from the rest. 0.1° = 1.7 mrad
// is about the tilt at rest's own standard error (1.3–2.2 mrad on the sample and MuJoCo recordings): a smaller turn
// moves α by less than the accelerometer can tell.
inline constexpr double kTurnBeforeFallWarningDeg = 0.1;

struct ReleaseTiltCheck {
  bool available = false;     // both tilts and both standard errors are known
  double rest_rad = 0.0;      // α at rest (accelerometer)
  double rest_std_error_rad = 0.0;
  double fitted_rad = 0.0;    // α of the fit
  double fitted_std_error_rad = 0.0;
  double difference_rad = 0.0;  // fitted − rest
  double z = 0.0;               // difference / combined standard error
  bool consistent = true;       // |z| ≤ kReleaseTiltMaxZ (true when not available)
  // The block's turn between the rest and the start of its fall [deg] (MountingCheck::turn_before_fall_deg; NaN
  // without a tilt at rest): above 0 a hand lifted or pushed it as it let go, and the fitted α is the tilt it fell
  // from, which a push away from the fall puts above the tilt at rest by about that turn.
  double turn_before_fall_deg = std::numeric_limits<double>::quiet_NaN();
  std::string reason;           // one sentence: the comparison, or why there is none
};

// The check of a fitted α (its standard error NaN where not available) against the recording's tilt at rest
// (`mounting`, from LoadRecording).
ReleaseTiltCheck CheckReleaseTilt(const io::MountingCheck& mounting, const Parameter& alpha,
                                  double alpha_std_error_rad);

// Sets summary->release_tilt and, when the two disagree, adds a warning (WarningKind::kReleaseTiltDisagrees); when
// the block turned by more than kTurnBeforeFallWarningDeg before its fall, adds WarningKind::kTurnedBeforeFall,
// compared or not.
void AttachReleaseTiltCheck(const io::MountingCheck& mounting, FitSummary* summary);

// {"available", "rest_rad", "rest_std_error_rad", "fitted_rad", "fitted_std_error_rad", "difference_rad", "z",
//  "consistent", "turn_before_fall_deg", "reason"}; numbers null when not available (the turn: when not known).
std::string ReleaseTiltCheckJson(const ReleaseTiltCheck& check);
std::string ReleaseTiltCheckText(const ReleaseTiltCheck& check);

}  // namespace rockfit::fitting
