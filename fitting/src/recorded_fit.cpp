#include "rockfit/fitting/recorded_fit.hpp"

#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/release_tilt_check.hpp"
#include "rockfit/fitting/sensor_yaw_check.hpp"

namespace rockfit::fitting {

FitSummary FitRecordedTrial(const Objective& objective, const ParameterSet& start, const FitOptions& options,
                            const std::optional<ReleaseRollChoice>& release_roll_choice,
                            const io::Recording* recording) {
  FitSummary summary = Fit(objective, start, options);
  summary.release_roll_choice = release_roll_choice;
  if (recording != nullptr) {
    AttachReleaseTiltCheck(recording->mounting_check, &summary);
    AttachSensorYawCheck(objective, *recording, &summary);
  }
  return summary;
}

}  // namespace rockfit::fitting
