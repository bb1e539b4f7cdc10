#include "rockfit/io/impact_detection.hpp"

#include <cmath>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

void ImpactDetectionOptions::Validate() const {
  if (!std::isfinite(min_prominence_rad_s) || min_prominence_rad_s < 0.0) {
    throw InvalidArgument("impact min_prominence_rad_s must be a finite number ≥ 0 [rad/s], got " +
                          std::to_string(min_prominence_rad_s));
  }
  if (!std::isfinite(min_separation_s) || min_separation_s < 0.0) {
    throw InvalidArgument("impact min_separation_s must be a finite number ≥ 0 [s], got " +
                          std::to_string(min_separation_s));
  }
}

std::vector<Peak> DetectRatePeaks(const Recording& recording, int axis, const ImpactDetectionOptions& options) {
  options.Validate();
  if (axis < 0 || axis > 2) throw InvalidArgument("DetectRatePeaks: axis must be 0, 1 or 2");
  if (!(recording.rate_hz > 0.0) || !std::isfinite(recording.rate_hz)) {
    throw BadInput("recording '" + recording.source + "' has no valid sample rate (got " +
                   std::to_string(recording.rate_hz) + " Hz); give the rate with --rate or in the manifest");
  }
  std::vector<double> magnitude(recording.w_B.size());
  for (std::size_t i = 0; i < magnitude.size(); ++i) {
    magnitude[i] = std::abs(recording.w_B[i][axis]);
    if (!std::isfinite(magnitude[i])) {
      throw BadInput("recording '" + recording.source + "': angular velocity sample " + std::to_string(i) +
                     " is not a finite number; the reader should have rejected it — check the file");
    }
  }
  PeakOptions peak_options;
  peak_options.min_prominence = options.min_prominence_rad_s;
  peak_options.min_separation_samples =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(options.min_separation_s * recording.rate_hz)));
  return FindPeaks(magnitude, peak_options);
}

}  // namespace rockfit::io
