// The gyro at rest before the release: the samples from the start of the recording to t_release − margin, when
// that stretch lasts at least min_duration. Their mean is the gyro bias (trial_problem.hpp subtracts it); their
// scatter about it is the sensor noise, which the lateral-motion check (lateral_motion_check.hpp) and the
// model-error statement (model_error.hpp) compare the residuals of (28) with.
//
// A release time that lies inside a motion (a block pushed as it was let go, whose fall a release from rest
// matches only later: motion_before_release.hpp; a lift that stops briefly at the top) would put the start of that
// motion into the rest, and with it a bias and a noise floor that the motion, not the sensor, makes. The rest
// therefore ends `margin` before the first moving sample (‖ω − the stretch's median‖ ≥ still_rate_rad_s) after the
// last still stretch of at least min_duration before t_release — where the recording is not still right up to
// t_release, and unless that leaves less than min_duration (then the stretch is kept whole, as without a rest).
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

struct RestSegmentOptions {
  double margin_s = 0.05;        // the segment ends this long before the release [s] (the release is estimated)
  double min_duration_s = 0.1;   // shorter segments are not used [s]
  // A sample this far from the rest's median is motion [rad/s] (the mounting estimate's threshold of rest,
  // io/mounting_estimate.hpp: 10 × the norm of the x-IMU's gyro noise). 0: the rest is never cut short.
  double still_rate_rad_s = 0.03;
  void Validate() const;         // throws InvalidArgument
};

struct RestNoise {
  bool available = false;       // the segment lasts at least min_duration_s and holds at least two samples
  std::size_t samples = 0;      // samples before the rest end (below), less the excluded ones (MeasuredSignal)
  double duration_s = 0.0;      // rest end − first sample time (rest end: t_release − margin, or the motion's onset − margin)
  // Where the recording was moving at t_release: how much earlier than t_release − margin the rest ends [s]
  // (0 where it was still, or where the shorter rest would be too short).
  double cut_before_release_s = 0.0;
  Eigen::Vector3d mean_rad_s = Eigen::Vector3d::Zero();      // the bias at rest
  Eigen::Vector3d variance_rad2_s2 = Eigen::Vector3d::Zero();  // per axis, about the mean (1/n)
  // The error (28) that the noise alone makes: the mean of ‖ω_k − mean‖ over the segment. A model that
  // reproduced the motion exactly would reach this ε on a recording with the same noise in motion.
  double epsilon_floor_rad_s = 0.0;
};

// Never throws for short or empty signals (available = false instead); InvalidArgument for bad options.
RestNoise MeasureRestNoise(const MeasuredSignal& signal, double t_release_s, const RestSegmentOptions& options = {});

}  // namespace rockfit::fitting
