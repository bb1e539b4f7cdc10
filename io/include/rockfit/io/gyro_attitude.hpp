// The attitude of a recording that has none, integrated from its gyro (io/README.md, "Attitude from the gyro").
//
// Phone apps, Arduino loggers and most CSV exports give the angular rate (and the specific force) but no
// attitude, which the drift correction and the OPMF/AVRF need. R_WB is integrated on SO(3) as unit quaternions,
//   q_WB(t_{k+1}) = q_WB(t_k) ⊗ Exp(½·w̄_k·Δt_k),   w̄_k = ½ (w_B,k + w_B,k+1) − b,
// which is exact when the rate is constant over each sample interval (w̄_k is the interval's rate; for a smooth
// rate the error is O(Δt²) per second of recording). b is the gyro bias measured at rest before the release.
// At an impact the rate jumps inside its sample interval, and w̄_k puts the jump in the interval's middle: the
// angle is off by (ω⁻ − ω⁺)·(t_mid − τ), up to |Δω|·Δt/2. Given the impact times τ (options.impact_times_s), the
// interval holding one is integrated in two pieces split there, each side's sample held to τ (ImpactIntervalStep):
// exact for a rate constant on each side, error ½·|ω̇|·Δt² at most for a smooth one. Fitting the integrated angle
// cannot give them (it is the gyro's own trapezoid sum and places every impact near its interval's middle);
// CorrectDrift finds them where the levelled angle comes back to zero (impact_zero_crossing.hpp) and passes them
// here (io/README.md, "Attitude from the gyro", measured).
// The start is levelled by the accelerometer during the rest before the release: the specific force at rest is
// g·R_WBᵀ·e_z = g·(−sin φy, sin φx cos φy, cos φx cos φy), so φx = atan2(f_y, f_z), φy = atan2(−f_x, √(f_y²+f_z²));
// φz starts at 0 (the yaw is free: nothing in the metrics depends on it). Without an accelerometer (or without
// a rest before the release) the attitude is levelled at the first impact instead, where the block lands on its
// base (φx = φy = 0 to within the rate times half a sample), with a warning; the bias still comes from the rest,
// found from the gyro alone. The drift correction needs the angles only relative to their values at the impacts.
// No correction by the accelerometer after the release: impacts saturate it, and the drift correction removes
// what the gyro's errors add between impacts.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/io/mounting_estimate.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

// No gyro measures more: MEMS ranges end at ±4000 °/s ≈ 70 rad/s. A larger rate is a wrong unit or a broken file
// (and its angle over a step would overflow), refused with BadInput.
inline constexpr double kMaxIntegrableRate_rad_s = 1e4;

struct GyroAttitudeOptions {
  MountingEstimateOptions rest;  // how the rest before the release is found (mounting_estimate.hpp)
  // Impact times [s], increasing: the sample interval holding each is integrated in two pieces split there
  // (ImpactIntervalStep). Empty: every interval by the mean of its two samples. A time outside the recording is
  // ignored; an interval holding several (a cascade as the block settles, the rate between them not sampled) is
  // integrated by its mean.
  std::vector<double> impact_times_s;
  // Throws InvalidArgument naming the bad option (a time that is not finite or does not increase).
  void Validate() const;
};

// How the start of the integration was fixed.
enum class AttitudeStart {
  kAccelerometer,  // "accelerometer": levelled by the specific force at rest before the release
  kLevel,          // "level": φx = φy = 0 at the first impact (no accelerometer or no rest; else at the first sample)
};
const char* ToString(AttitudeStart start);
bool FromString(std::string_view text, AttitudeStart* value);  // the inverse of ToString

struct GyroAttitude {
  std::vector<Eigen::Vector3d> euler_zyx;  // (φz, φy, φx) of R_WB at every sample [rad], unwrapped
  AttitudeStart start = AttitudeStart::kLevel;
  Eigen::Vector3d start_euler_zyx = Eigen::Vector3d::Zero();  // at the first sample [rad]
  Eigen::Vector3d gyro_bias_rad_s = Eigen::Vector3d::Zero();  // subtracted from w_B (zero without a rest)
  std::size_t rest_samples = 0;                                // samples of the rest that levelled the start
  std::vector<std::string> warnings;
};

// The rotation over one sample interval of constant body rate w_B [rad/s] lasting dt_s [s]: Exp(½·w·dt), exact.
Eigen::Quaterniond BodyRateStep(const Eigen::Vector3d& w_B, double dt_s);

// The rotation over the sample interval [t0_s, t1_s] in which the rate jumps at impact_s (t0_s ≤ impact_s ≤ t1_s):
// w_before_B (the sample at t0_s) held over [t0_s, impact_s], then w_after_B (the sample at t1_s) over
// [impact_s, t1_s]. Exact for a rate that is constant on each side; for a smooth rate on each side the error is
// at most ½·max|ω̇|·Δt² (each side's rate is its sample's, held at most Δt).
Eigen::Quaterniond ImpactIntervalStep(const Eigen::Vector3d& w_before_B, const Eigen::Vector3d& w_after_B,
                                      double t0_s, double impact_s, double t1_s);

// ZYX Euler angles (φz, φy, φx) of the attitude whose specific force at rest is f_B (any length > 0), yaw 0.
Eigen::Vector3d LevelledEulerZyx(const Eigen::Vector3d& f_B);

// The attitude integrated from recording.w_B (and levelled by recording.accel_B), as described above.
// Throws BadInput for a recording whose samples are not finite, whose times do not increase, or whose rates exceed
// kMaxIntegrableRate_rad_s.
GyroAttitude IntegrateGyroAttitude(const Recording& recording, const GyroAttitudeOptions& options = {});

// `recording` with euler_zyx from IntegrateGyroAttitude when it has none (orientation_source says so and the
// warnings are appended); unchanged when it has Euler angles.
Recording WithAttitude(const Recording& recording, const GyroAttitudeOptions& options = {});

}  // namespace rockfit::io
