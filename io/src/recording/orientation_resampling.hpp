// Orientation samples onto the gyro's time base (docs/design.md §5: "orientation at another rate is
// resampled"). Attitude is interpolated on the rotation group (slerp between neighbouring samples),
// never by averaging Euler angles, so that wrap-around at ±180° cannot corrupt it. Gyro samples
// before the first or after the last orientation sample are not covered (no extrapolation).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rockfit::io {

// Two times closer than this are the same instant (both come from the same integer clock and the
// same arithmetic, so they agree to rounding).
inline constexpr double kSameInstant_s = 1e-9;

// Attitude samples q_WS at strictly increasing times on the gyro clock [s].
struct OrientationSeries {
  std::vector<double> t_s;
  std::vector<Eigen::Quaterniond> q_WS;
  bool empty() const { return t_s.empty(); }
};

// A stretch without orientation samples (longer than kGapStepFactor median steps) that gyro samples
// fall into: their attitude is interpolated across it.
struct OrientationHole {
  double t_s = 0.0;         // start of the stretch [s]
  double duration_s = 0.0;  // its length [s]
  std::size_t samples = 0;  // gyro samples inside it
};

struct ResampledOrientation {
  std::size_t first = 0;                 // index of the first covered gyro sample
  std::vector<Eigen::Quaterniond> q_WS;  // attitude at gyro samples first … first + size − 1
  std::vector<OrientationHole> holes;
  double median_step_s = 0.0;            // of the orientation series
};

// Attitude at each target time inside [series.t_s.front(), series.t_s.back()]. Targets must increase.
ResampledOrientation ResampleOrientation(const std::vector<double>& target_t_s, const OrientationSeries& series);

}  // namespace rockfit::io
