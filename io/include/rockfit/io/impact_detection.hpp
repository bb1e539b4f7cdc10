// Impacts of the base seen in the gyro: local maxima of |ω_y| (and |ω_x|) with a prominence threshold and a
// minimum separation, because the gyros ring for a few tens of milliseconds after each impact (docs/design.md §6,
// paper Sect. 3.1).
#pragma once

#include <cstddef>
#include <vector>

#include "rockfit/io/peak_finding.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

struct ImpactDetectionOptions {
  // An impact peak of |ω| must stand this far above its bases. 0.05 rad/s ≈ 2.9 °/s: ten times the gyro noise
  // of an x-IMU at rest, and below the pre-impact rate of a block of the paper (b1 = 5 cm, h = 20 cm) rocking
  // with 0.005 rad amplitude (≈ 0.1 rad/s).
  double min_prominence_rad_s = 0.05;
  // Of two peaks closer than this, the higher is the impact and the other is ringing. 0.05 s is half the time
  // between impacts of the paper's blocks rocking with 0.01 rad amplitude, and longer than the ringing.
  double min_separation_s = 0.05;
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

// Peaks of |w_B[axis]| (axis 0 = x, 1 = y, 2 = z), in time order. The separation is converted to samples with
// the recording's rate (at least 1).
std::vector<Peak> DetectRatePeaks(const Recording& recording, int axis, const ImpactDetectionOptions& options);

}  // namespace rockfit::io
