// A Recording: uniform-time IMU samples of one trial, in SI units and the block frame (docs/design.md §5).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
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

// The outcome of the mounting check: an estimate of every angle, of some of them, or why there is none.
enum class MountingStatus { kOk, kPartial, kNoAccelerometer, kNoRelease, kNoRest, kNotChecked };
// "ok", "partial", "no_accelerometer", "no_release", "no_rest", "not_checked".
const char* ToString(MountingStatus status);
bool FromString(std::string_view text, MountingStatus* status);  // the inverse of ToString

// What the recording says about the mounting (mounting_estimate.hpp), filled by LoadRecording for IMU files
// with an accelerometer. The angles are the rotation vector, in degrees and block axes, that turns the given
// mounting into the one the data show (R_BS = Rot(angles)·R_BS,given): zero when they agree.
struct MountingCheck {
  MountingStatus status = MountingStatus::kNotChecked;
  std::string message;                 // what the data could not fix, or why there is no estimate
  std::string given = "identity";      // the mounting given (Mounting::text()), the estimate's starting point
  bool estimated = false;              // --mounting auto: Recording::mounting is the estimate
  Eigen::Vector3d angles_deg = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d std_error_deg = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  std::array<bool, 3> determined{false, false, false};  // per block axis: the data fix that angle
  double release_tilt_rad = std::numeric_limits<double>::quiet_NaN();  // α at rest from the accelerometer
  // Its standard error from the estimate's scatter and calibration floors (NaN without an estimate) [rad].
  double release_tilt_std_error_rad = std::numeric_limits<double>::quiet_NaN();
  // How far the block turned between the rest before the release and the start of its fall [deg] (a hand that
  // lifted or pushed it as it let go): 0 when that rest ends where the fall begins; NaN without an estimate.
  // Where it is above 0 the fitted α is the tilt the block fell from, not the tilt at rest.
  double turn_before_fall_deg = std::numeric_limits<double>::quiet_NaN();
  std::string warning;  // set when the data disagree with a mounting that was given (not estimated)

  bool has_estimate() const { return status == MountingStatus::kOk || status == MountingStatus::kPartial; }
};

// Where a recording's sample rate came from. The names are used only at the edges (HDF5 attribute, JSON, text,
// Python).
enum class RateSource {
  kOption,      // "option": given by the caller (--rate, or a Recording built in code)
  kManifest,    // "manifest": given in the campaign manifest
  kRegisters,   // "registers": the x-IMU's _Registers.csv (register 69)
  kTimestamps,  // "timestamps": 1 / the median step of the file's time column or timestamps
  kFile,        // "file": rockfit's HDF5 store
};
const char* ToString(RateSource source);
// Reads the name back; false (and *source unchanged) for any other text.
bool FromString(std::string_view text, RateSource* source);

struct Recording {
  std::string format;   // "ximu-gui", "ximu3", "generic-csv", "rockfit-hdf5"
  std::string source;   // the path the recording was read from
  double rate_hz = 0.0; // nominal sample rate of the gyro
  RateSource rate_source = RateSource::kOption;  // where the rate came from

  std::vector<double> t_s;                 // sample times [s], first sample at 0
  std::vector<Eigen::Vector3d> w_B;        // angular velocity in the block frame [rad/s]
  std::vector<Eigen::Vector3d> euler_zyx;  // ZYX Euler angles (φz, φy, φx) of R_WB [rad], unwrapped; empty if absent
  std::vector<Eigen::Vector3d> accel_B;    // specific force in the block frame [m/s²]; empty if absent

  std::string orientation_source;  // file(s) the attitude was read from; empty without attitude
  double orientation_rate_hz = 0.0;  // rate of those files before resampling onto t_s; 0 without attitude
  std::string mounting = "identity";  // the sensor→block mounting R_BS that was applied (Mounting::text())
  MountingCheck mounting_check;       // the data's view of the mounting

  std::vector<std::string> columns;   // source columns that were read, as "file: header"
  std::vector<std::string> recognised;  // how the reader understood the files (layout, units, time), for inspect
  std::vector<Gap> gaps;              // dropped samples
  std::vector<std::string> warnings;  // documented repairs that were applied

  std::size_t size() const { return t_s.size(); }
  bool has_euler() const { return !euler_zyx.empty(); }
  bool has_accel() const { return !accel_B.empty(); }
  double duration_s() const { return t_s.empty() ? 0.0 : t_s.back() - t_s.front(); }
};

}  // namespace rockfit::io
