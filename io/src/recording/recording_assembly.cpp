#include "recording/recording_assembly.hpp"

#include <fmt/format.h>

#include "recording/attitude.hpp"
#include "text/input_problem.hpp"
#include "recording/time_base.hpp"

namespace rockfit::io {

void AssembleRecording(SensorSamples samples, const Mounting& mounting, Recording& recording) {
  const std::size_t n = samples.t_s.size();
  std::size_t first = 0;
  std::size_t count = n;
  ResampledOrientation attitude;
  if (!samples.orientation.empty()) {
    attitude = ResampleOrientation(samples.t_s, samples.orientation);
    first = attitude.first;
    count = attitude.q_WS.size();
    if (count == 0) {
      ThrowBadInput({{recording.orientation_source}, "",
                     fmt::format("attitude samples at t = {:.4f} … {:.4f} s on the gyro clock",
                                 samples.orientation.t_s.front(), samples.orientation.t_s.back()),
                     fmt::format("attitude during the gyro recording (t = 0 … {:.4f} s)", n ? samples.t_s.back() : 0.0),
                     "The attitude file belongs to another recording; pick the right files, or read the gyro data "
                     "alone with --orientation none."});
    }
    if (count < n) {
      recording.warnings.push_back(fmt::format(
          "{}: attitude covers gyro samples {} … {} of {}; the {} samples before and {} after it were dropped so that "
          "every sample has an attitude (t = 0 is now gyro sample {}; use --orientation none to keep them all)",
          recording.orientation_source, first, first + count - 1, n, first, n - first - count, first));
    }
    for (const OrientationHole& hole : attitude.holes) {
      recording.warnings.push_back(fmt::format(
          "{}: no attitude sample for {:.4f} s after t = {:.4f} s (more than {} median steps of {:.4f} s); the "
          "attitude of the {} gyro samples in between was interpolated",
          recording.orientation_source, hole.duration_s, hole.t_s - samples.t_s[first], kGapStepFactor,
          attitude.median_step_s, hole.samples));
    }
  }

  const double t0 = count > 0 ? samples.t_s[first] : 0.0;
  recording.t_s.resize(count);
  recording.w_B.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    recording.t_s[k] = samples.t_s[first + k] - t0;
    recording.w_B[k] = mounting.ToBlock(samples.w_S[first + k]);
  }
  recording.accel_B.clear();
  if (!samples.accel_S.empty()) {
    recording.accel_B.resize(count);
    for (std::size_t k = 0; k < count; ++k) recording.accel_B[k] = mounting.ToBlock(samples.accel_S[first + k]);
  }
  recording.euler_zyx.clear();
  if (!attitude.q_WS.empty()) {
    recording.euler_zyx.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      recording.euler_zyx[k] = EulerZyxFromQuaternion(mounting.BlockAttitude(attitude.q_WS[k]));
    }
    UnwrapAngles(recording.euler_zyx);
  }
  recording.gaps.clear();
  for (Gap gap : samples.gaps) {
    if (gap.index < first || gap.index + 1 >= first + count) continue;
    gap.index -= first;
    gap.t_s -= t0;
    recording.gaps.push_back(gap);
  }
  recording.mounting = mounting.text();
}

}  // namespace rockfit::io
