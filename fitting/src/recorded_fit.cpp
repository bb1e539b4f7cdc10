#include "rockfit/fitting/recorded_fit.hpp"

#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/release_tilt_check.hpp"

namespace rockfit::fitting {

FitSummary FitRecordedTrial(const Objective& objective, const ParameterSet& start, const FitOptions& options,
                            const std::optional<ReleaseRollChoice>& release_roll_choice,
                            const io::MountingCheck* mounting) {
  FitSummary summary = Fit(objective, start, options);
  summary.release_roll_choice = release_roll_choice;
  if (mounting != nullptr) AttachReleaseTiltCheck(*mounting, &summary);
  return summary;
}

}  // namespace rockfit::fitting
