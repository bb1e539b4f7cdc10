// A fit of a recorded trial as every front end makes it (`rockfit fit`, `rockfit batch` through FitCampaign, and
// Python's rockfit.fit): Fit() on the prepared problem, then what only the recording knows is attached to the
// summary — whether the release roll is fitted and why (release_roll_choice.hpp), the check of the fitted α against
// the tilt at rest (release_tilt_check.hpp) and, where the mounting check could not fix the sensor's turn about z,
// that turn from the fitted motion (sensor_yaw_check.hpp). One function, so that the three cannot drift apart.
#pragma once

#include <optional>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/release_roll_choice.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::fitting {

// Fit(objective, start, options) with summary.release_roll_choice = release_roll_choice and, where `recording` is
// given (the one the problem was made from, with its MountingCheck from LoadRecording), the release tilt check and
// the turn about z, with their warnings. `recording` null: a problem not made from a recording, no check
// (FitSummary::release_tilt empty).
FitSummary FitRecordedTrial(const Objective& objective, const ParameterSet& start, const FitOptions& options,
                            const std::optional<ReleaseRollChoice>& release_roll_choice,
                            const io::Recording* recording);

}  // namespace rockfit::fitting
