// Measurement model of the original x-IMU in IMU mode (the paper's Sect. 3.1): turns a true block motion
// (synth_motion.hpp) into what the device reports — gyroscope, accelerometer and magnetometer in the sensor
// frame, and the on-board attitude estimate as a quaternion and ZYX Euler angles — with the artefacts that
// real recordings show. Every part can be switched off; the result is a pure function of the motion and
// the options (including the seed). Documented in io/README.md, "Synthetic recordings".
//
// Per inertial sample n at t_n = n / f (sensor frame S, R_BS = mounting, sensor → block):
//   gyro_dps   = Q_1/16( clamp( deg(R_BSᵀ w_B) + bias + ringing(t_n) + σ_g·N(0,1) ) )
//   ringing(t) = Σ_impacts  gain · deg(R_BSᵀ Δω_i) · exp(−(t − t_i)/T_r) · sin(2π f_r (t − t_i)),  t ≥ t_i
//   accel_g    = Q_1/2048( clamp( R_WSᵀ (a_W + g e_z) / g + σ_a·N ) ),  a_W = ω̇ × r + ω × (ω × r),
//                r = R_WB (p_BS_B − p_BK_B) the lever from the momentary pivot to the sensor point
//   mag_G      = Q_1/2048( clamp( R_WSᵀ m_W + σ_m·N ) )
//   attitude   = ZYX Euler angles of F_n·R_WS (R_WS = R_WB R_BS), plus drift d(t) = slope·t + random walk,
//                random walk W_n = W_{n−1} + σ_w √(1/f) N; F_n = F_{n−1}·Exp(R_WS e_S Δt), F_0 = I, is the
//                gyro's error e_S = rad(gyro_dps) − R_BSᵀ w_B integrated as the device's AHRS integrates its
//                gyro (the estimate carries the integral of the bias, ringing, noise and quantisation it reads)
//   quaternion = conjugate (Earth relative to sensor, as the device) of the drifted attitude, Q15-quantised,
//                then normalised in single precision; Euler angles are computed from it as the x-IMU GUI does.
// Q_r(x) rounds to a multiple of r (the device's fixed-point resolution) and is skipped without quantisation.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/io/synth_motion.hpp"

namespace rockfit::io {

// Fixed-point resolutions of the original x-IMU (Q4 gyroscope, Q11 accelerometer and magnetometer, Q15 quaternion).
inline constexpr double kXimuGyroResolutionDps = 1.0 / 16.0;
inline constexpr double kXimuAccelResolutionG = 1.0 / 2048.0;
inline constexpr double kXimuMagResolutionGauss = 1.0 / 2048.0;
inline constexpr double kXimuQuaternionResolution = 1.0 / 32768.0;
// Largest magnetometer reading (int16 32767 in Q11), seen on saturated real recordings as 15.99951.
inline constexpr double kXimuMagSaturationGauss = 32767.0 / 2048.0;

// Where the sensor sits on the block.
struct SensorMounting {
  Eigen::Matrix3d R_BS = Eigen::Matrix3d::Identity();  // sensor → block: v_B = R_BS v_S (a proper rotation)
  Eigen::Vector3d p_BS_B = Eigen::Vector3d::Zero();    // the accelerometer's position in B [m]
  // Throws InvalidArgument unless R_BS is orthonormal with determinant +1 and p_BS_B finite.
  void Validate() const;
};

struct MeasurementOptions {
  // Gyroscope.
  double gyro_noise_dps = 0.1;                             // σ of white noise per axis and sample [deg/s]
  Eigen::Vector3d gyro_bias_dps = Eigen::Vector3d::Zero();  // constant bias, sensor axes [deg/s]
  double gyro_full_scale_dps = 2000.0;                     // saturation (register 8 = 3: ±2000 deg/s)
  // Ringing after impacts (the gyroscope artefact of the paper's Sect. 5.2); gain 0 switches it off.
  double ringing_gain = 0.25;           // amplitude per unit jump |Δω| (dimensionless)
  double ringing_frequency_hz = 38.0;   // oscillation frequency [Hz]
  double ringing_decay_time_s = 0.03;   // e-folding time T_r of the envelope [s]
  // Drift of the on-board attitude estimate, per Euler angle (x = roll φx, y = pitch φy, z = yaw φz).
  Eigen::Vector3d drift_slope_dps = Eigen::Vector3d(0.02, -0.05, 0.4);           // linear part [deg/s]
  Eigen::Vector3d drift_walk_deg_per_rt_s = Eigen::Vector3d(0.01, 0.01, 0.03);  // random walk σ_w [deg/√s]
  // Accelerometer.
  double accel_noise_g = 0.015;        // σ per axis and sample [g]
  double accel_full_scale_g = 8.0;     // saturation (register 32 = 2: ±8 g)
  // Magnetometer: a constant field in W (Central Europe: 0.48 G, inclination 63°), plus noise.
  Eigen::Vector3d mag_field_W_G = Eigen::Vector3d(0.22, 0.0, -0.43);
  double mag_noise_G = 0.002;          // σ per axis and sample [G]
  // The device's fixed-point resolution (gyroscope 1/16 deg/s, accelerometer and magnetometer 1/2048,
  // quaternion 1/32768).
  bool quantisation = true;
  std::uint64_t seed = 1;

  // No noise, bias, ringing, drift or quantisation: the file holds the true motion to single precision.
  static MeasurementOptions Ideal();
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

// What the device reports, at every inertial sample (the file writer decimates the orientation stream when
// its rate is lower). Single precision, as the x-IMU GUI holds and prints them.
struct DeviceSamples {
  double rate_hz = 0.0;
  std::vector<Eigen::Vector3f> gyro_dps;    // sensor frame [deg/s]
  std::vector<Eigen::Vector3f> accel_g;     // sensor frame, specific force [g]
  std::vector<Eigen::Vector3f> mag_G;       // sensor frame [G]
  std::vector<Eigen::Vector4f> quaternion;  // _Quaternion.csv: Earth relative to sensor, (w, x, y, z), unit
  std::vector<Eigen::Vector3f> euler_deg;   // _EulerAngles.csv: roll φx, pitch φy, yaw φz [deg]
  // The artefacts alone (double precision, before quantisation), for tests and the truth file.
  std::vector<Eigen::Vector3d> ringing_dps;  // sensor axes
  std::vector<Eigen::Vector3d> drift_deg;    // (x, y, z) added to (roll, pitch, yaw)
  std::vector<Eigen::Vector3d> gyro_error_W_rad;  // rotation vector of F (world axes): the integrated gyro error

  std::size_t size() const { return gyro_dps.size(); }
};

// The measurement model above. Throws InvalidArgument for invalid motion, mounting or options.
DeviceSamples MeasureMotion(const BlockMotion& motion, const SensorMounting& mounting, const MeasurementOptions& options);

// The x-IMU GUI's ZYX Euler angles (roll φx, pitch φy, yaw φz) [deg] of a file quaternion (Earth relative to
// sensor, scalar first), computed as the GUI does in single precision.
Eigen::Vector3f XimuEulerDegFromFileQuaternion(const Eigen::Vector4f& q_file);

}  // namespace rockfit::io
