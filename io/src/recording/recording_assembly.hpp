// The last step of every reader: from what the files hold (SI units, sensor axes, attitude on the
// gyro clock) to a Recording in block axes with unwrapped Euler angles of R_WB (docs/design.md §2, §5).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "rockfit/io/mounting.hpp"
#include "recording/orientation_resampling.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

struct SensorSamples {
  std::vector<double> t_s;               // gyro sample times [s], increasing, first at 0
  std::vector<Eigen::Vector3d> w_S;      // angular velocity in sensor axes [rad/s]
  std::vector<Eigen::Vector3d> accel_S;  // specific force in sensor axes [m/s²]; empty if absent
  std::vector<Gap> gaps;                 // on t_s
  OrientationSeries orientation;         // attitude of the sensor q_WS; empty if absent
};

// Fills t_s, w_B, accel_B, euler_zyx, gaps and mounting of `recording` (whose format, source,
// rate and orientation_source the reader has set) and appends warnings:
//  * w_B = R_BS·w_S, accel_B = R_BS·accel_S, R_WB = R_WS·R_BSᵀ, Euler ZYX of R_WB, unwrapped;
//  * attitude resampled onto t_s; gyro samples outside the attitude's time span are dropped with a
//    warning (t_s then starts at 0 again); no overlap at all throws BadInput.
void AssembleRecording(SensorSamples samples, const Mounting& mounting, Recording& recording);

}  // namespace rockfit::io
