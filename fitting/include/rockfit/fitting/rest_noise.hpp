// The gyro at rest before the release: the samples from the start of the recording to t_release − margin, when
// that stretch lasts at least min_duration. Their mean is the gyro bias (trial_problem.hpp subtracts it); their
// scatter about it is the sensor noise, which the lateral-motion check (lateral_motion_check.hpp) and the
// model-error statement (model_error.hpp) compare the residuals of (28) with.
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

struct RestSegmentOptions {
  double margin_s = 0.05;        // the segment ends this long before the release [s] (the release is estimated)
  double min_duration_s = 0.1;   // shorter segments are not used [s]
  void Validate() const;         // throws InvalidArgument
};

struct RestNoise {
  bool available = false;       // the segment lasts at least min_duration_s and holds at least two samples
  std::size_t samples = 0;      // samples t_k < t_release − margin, less the excluded ones (MeasuredSignal)
  double duration_s = 0.0;      // t_release − margin − first sample time
  Eigen::Vector3d mean_rad_s = Eigen::Vector3d::Zero();      // the bias at rest
  Eigen::Vector3d variance_rad2_s2 = Eigen::Vector3d::Zero();  // per axis, about the mean (1/n)
  // The error (28) that the noise alone makes: the mean of ‖ω_k − mean‖ over the segment. A model that
  // reproduced the motion exactly would reach this ε on a recording with the same noise in motion.
  double epsilon_floor_rad_s = 0.0;
};

// Never throws for short or empty signals (available = false instead); InvalidArgument for bad options.
RestNoise MeasureRestNoise(const MeasuredSignal& signal, double t_release_s, const RestSegmentOptions& options = {});

}  // namespace rockfit::fitting
