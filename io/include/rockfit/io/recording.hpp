// A Recording: uniform-time IMU samples of one trial, in SI units and the block frame (DESIGN §5).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace rockfit::io {

// A hole in the time base: samples that the device dropped (x-IMU3 timestamp jumps).
struct Gap {
  std::size_t index = 0;     // sample index after which the gap opens
  double t_s = 0.0;          // time of that sample [s]
  double duration_s = 0.0;   // time to the next sample [s]
  std::size_t missing = 0;   // samples missing at the nominal rate
};

struct Recording {
  std::string format;   // "ximu-gui", "ximu3", "generic-csv", "rockfit-hdf5"
  std::string source;   // the path the recording was read from
  double rate_hz = 0.0; // nominal sample rate of the gyro
  std::string rate_source;  // where the rate came from: "registers", "timestamps", "manifest", "option", "file"

  std::vector<double> t_s;                 // sample times [s], first sample at 0
  std::vector<Eigen::Vector3d> w_B;        // angular velocity in the block frame [rad/s]
  std::vector<Eigen::Vector3d> euler_zyx;  // ZYX Euler angles (φz, φy, φx) of R_WB [rad], unwrapped; empty if absent
  std::vector<Eigen::Vector3d> accel_B;    // specific force in the block frame [m/s²]; empty if absent

  std::string orientation_source;  // file(s) the attitude was read from; empty without attitude
  double orientation_rate_hz = 0.0;  // rate of those files before resampling onto t_s; 0 without attitude
  std::string mounting = "identity";  // the sensor→block mounting R_BS that was applied (Mounting::text())

  std::vector<std::string> columns;   // source columns that were read, as "file: header"
  std::vector<Gap> gaps;              // dropped samples
  std::vector<std::string> warnings;  // documented repairs that were applied

  std::size_t size() const { return t_s.size(); }
  bool has_euler() const { return !euler_zyx.empty(); }
  bool has_accel() const { return !accel_B.empty(); }
  double duration_s() const { return t_s.empty() ? 0.0 : t_s.back() - t_s.front(); }
};

}  // namespace rockfit::io
