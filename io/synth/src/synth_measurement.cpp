#include "rockfit/io/synth_measurement.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "rockfit/io/synth_random.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {
namespace {

constexpr double kDegPerRad = 180.0 / kPi;
// The GUI's single-precision degrees-per-radian constant (QuaternionData.Rad2Deg).
constexpr float kGuiDegPerRad = 57.2957795130823f;
// R_BS must be a rotation to this accuracy (axis permutations are exact; quaternions round to ~1e-16).
constexpr double kRotationTolerance = 1e-9;
// A ringing term is dropped once its envelope is below this fraction of its start (far below Q4 resolution).
constexpr double kRingingCutoff = 1e-12;
// Q15 range of the device's quaternion elements.
constexpr double kQ15Min = -32768.0;
constexpr double kQ15Max = 32767.0;

double Quantise(double value, double resolution) { return std::round(value / resolution) * resolution; }

// The device's reading of a value: clamped to full scale and (optionally) rounded to its fixed-point resolution.
// Exact in double precision; a Q4/Q11 value within full scale is also exact in single precision.
Eigen::Vector3d ToSensorValue(const Eigen::Vector3d& value, double resolution, double lower, double upper, bool quantise) {
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    double v = std::clamp(value[i], lower, upper);
    if (quantise) v = Quantise(v, resolution);
    out[i] = v;
  }
  return out;
}

Eigen::Vector3f ToSensorFloat(const Eigen::Vector3d& value, double resolution, double lower, double upper, bool quantise) {
  return ToSensorValue(value, resolution, lower, upper, quantise).cast<float>();
}

// Exp of a rotation vector θ [rad]: the rotation by |θ| about θ/|θ| (exact, identity for θ = 0). Written here
// rather than taken from the reader's gyro integration, so that the recordings that test the reader do not
// share its code.
Eigen::Quaterniond RotationVectorExp(const Eigen::Vector3d& theta_rad) {
  const double angle_rad = theta_rad.norm();
  if (angle_rad == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, theta_rad / angle_rad));
}

// Index of the continuous piece of motion that time t belongs to: the number of breaks at or before t
// (a sample at an impact instant carries the post-impact value).
std::size_t SegmentOf(const std::vector<double>& breaks_s, double t) {
  return static_cast<std::size_t>(std::upper_bound(breaks_s.begin(), breaks_s.end(), t) - breaks_s.begin());
}

// dω_W/dt at every sample by central differences inside a segment, one-sided at its ends, 0 for a lone sample.
std::vector<Eigen::Vector3d> AngularAccelerationW(const BlockMotion& motion, const std::vector<Eigen::Vector3d>& w_W) {
  const std::size_t count = motion.size();
  std::vector<std::size_t> segment(count);
  for (std::size_t n = 0; n < count; ++n) segment[n] = SegmentOf(motion.breaks_s, motion.t_s(n));
  std::vector<Eigen::Vector3d> dw_W(count, Eigen::Vector3d::Zero());
  const double f = motion.rate_hz;
  for (std::size_t n = 0; n < count; ++n) {
    const bool has_prev = n > 0 && segment[n - 1] == segment[n];
    const bool has_next = n + 1 < count && segment[n + 1] == segment[n];
    if (has_prev && has_next) {
      dw_W[n] = (w_W[n + 1] - w_W[n - 1]) * (0.5 * f);
    } else if (has_next) {
      dw_W[n] = (w_W[n + 1] - w_W[n]) * f;
    } else if (has_prev) {
      dw_W[n] = (w_W[n] - w_W[n - 1]) * f;
    }
  }
  return dw_W;
}

// Σ over impacts of gain·Δω_S·exp(−(t − t_i)/T)·sin(2π f (t − t_i)) for t ≥ t_i, in deg/s.
std::vector<Eigen::Vector3d> Ringing(const BlockMotion& motion, const Eigen::Matrix3d& R_BS, const MeasurementOptions& o) {
  std::vector<Eigen::Vector3d> ringing(motion.size(), Eigen::Vector3d::Zero());
  if (o.ringing_gain == 0.0) return ringing;
  const double window_s = -std::log(kRingingCutoff) * o.ringing_decay_time_s;
  const double omega = 2.0 * kPi * o.ringing_frequency_hz;
  for (const ImpactJump& impact : motion.impacts) {
    const Eigen::Vector3d jump_S_dps = kDegPerRad * (R_BS.transpose() * (impact.w_plus_B - impact.w_minus_B));
    const Eigen::Vector3d amplitude = o.ringing_gain * jump_S_dps;
    std::size_t n = static_cast<std::size_t>(std::max(0.0, std::ceil(impact.t_s * motion.rate_hz)));
    while (n > 0 && motion.t_s(n - 1) >= impact.t_s) --n;
    for (; n < motion.size(); ++n) {
      const double dt = motion.t_s(n) - impact.t_s;
      if (dt < 0.0) continue;
      if (dt > window_s) break;
      ringing[n] += amplitude * (std::exp(-dt / o.ringing_decay_time_s) * std::sin(omega * dt));
    }
  }
  return ringing;
}

// The device's quaternion as it reaches the file: Q15 (optional), then normalised in single precision.
Eigen::Vector4f DeviceQuaternion(const Eigen::Quaterniond& q_file, bool quantise) {
  Eigen::Vector4f q(static_cast<float>(q_file.w()), static_cast<float>(q_file.x()), static_cast<float>(q_file.y()),
                    static_cast<float>(q_file.z()));
  if (quantise) {
    const double elements[4] = {q_file.w(), q_file.x(), q_file.y(), q_file.z()};
    for (int i = 0; i < 4; ++i) {
      const double fixed = std::clamp(std::round(elements[i] / kXimuQuaternionResolution), kQ15Min, kQ15Max);
      q[i] = static_cast<float>(fixed) / 32768.0f;
    }
  }
  const float sum = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  const float norm = static_cast<float>(std::sqrt(static_cast<double>(sum)));
  return q / norm;
}

}  // namespace

void SensorMounting::Validate() const {
  if (!R_BS.allFinite() || !p_BS_B.allFinite()) throw InvalidArgument("sensor mounting: non-finite R_BS or position");
  const double orthogonality = (R_BS.transpose() * R_BS - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthogonality > kRotationTolerance || R_BS.determinant() < 0.0) {
    throw InvalidArgument("sensor mounting: R_BS must be a proper rotation (orthonormal, determinant +1); "
                          "a mirrored axis set such as x,y,-z is not a rotation");
  }
}

MeasurementOptions MeasurementOptions::Ideal() {
  MeasurementOptions o;
  o.gyro_noise_dps = 0.0;
  o.gyro_bias_dps.setZero();
  o.ringing_gain = 0.0;
  o.drift_slope_dps.setZero();
  o.drift_walk_deg_per_rt_s.setZero();
  o.accel_noise_g = 0.0;
  o.mag_noise_G = 0.0;
  o.quantisation = false;
  return o;
}

void MeasurementOptions::Validate() const {
  RequireNonNegative(gyro_noise_dps, "measurement option gyro_noise_dps");
  if (!gyro_bias_dps.allFinite()) throw InvalidArgument("measurement option gyro_bias_dps must be finite");
  RequirePositive(gyro_full_scale_dps, "measurement option gyro_full_scale_dps");
  RequireNonNegative(ringing_gain, "measurement option ringing_gain");
  RequirePositive(ringing_frequency_hz, "measurement option ringing_frequency_hz");
  RequirePositive(ringing_decay_time_s, "measurement option ringing_decay_time_s");
  if (!drift_slope_dps.allFinite()) throw InvalidArgument("measurement option drift_slope_dps must be finite");
  if (!drift_walk_deg_per_rt_s.allFinite() || (drift_walk_deg_per_rt_s.array() < 0.0).any()) {
    throw InvalidArgument("measurement option drift_walk_deg_per_rt_s must be finite and ≥ 0");
  }
  RequireNonNegative(accel_noise_g, "measurement option accel_noise_g");
  RequirePositive(accel_full_scale_g, "measurement option accel_full_scale_g");
  if (!mag_field_W_G.allFinite()) throw InvalidArgument("measurement option mag_field_W_G must be finite");
  RequireNonNegative(mag_noise_G, "measurement option mag_noise_G");
}

Eigen::Vector3f XimuEulerDegFromFileQuaternion(const Eigen::Vector4f& q) {
  // The x-IMU GUI's formulas (docs/file-formats.md §1.6): single-precision arguments, double-precision functions.
  const float phi = static_cast<float>(std::atan2(2.0f * (q[2] * q[3] - q[0] * q[1]), 2.0f * q[0] * q[0] - 1.0f + 2.0f * q[3] * q[3]));
  const double s = 2.0 * static_cast<double>(q[1] * q[3] + q[0] * q[2]);
  const double b = 2.0 * q[1] * q[3] + 2.0 * q[0] * q[2];
  const float theta = static_cast<float>(-std::atan(s / std::sqrt(1.0 - b * b)));
  const float psi = static_cast<float>(std::atan2(2.0f * (q[1] * q[2] - q[0] * q[3]), 2.0f * q[0] * q[0] - 1.0f + 2.0f * q[1] * q[1]));
  return {kGuiDegPerRad * phi, kGuiDegPerRad * theta, kGuiDegPerRad * psi};
}

DeviceSamples MeasureMotion(const BlockMotion& motion, const SensorMounting& mounting, const MeasurementOptions& o) {
  motion.Validate();
  mounting.Validate();
  o.Validate();
  const std::size_t count = motion.size();
  const Eigen::Matrix3d& R_BS = mounting.R_BS;
  const double g = motion.gravity_m_s2;
  const double dt_s = 1.0 / motion.rate_hz;

  std::vector<Eigen::Matrix3d> R_WB(count);
  std::vector<Eigen::Vector3d> w_W(count);
  for (std::size_t n = 0; n < count; ++n) {
    R_WB[n] = motion.q_WB[n].normalized().toRotationMatrix();
    w_W[n] = R_WB[n] * motion.w_B[n];
  }
  const std::vector<Eigen::Vector3d> dw_W = AngularAccelerationW(motion, w_W);

  DeviceSamples out;
  out.rate_hz = motion.rate_hz;
  out.gyro_dps.resize(count);
  out.accel_g.resize(count);
  out.mag_G.resize(count);
  out.quaternion.resize(count);
  out.euler_deg.resize(count);
  out.drift_deg.resize(count);
  out.gyro_error_W_rad.resize(count);
  out.ringing_dps = Ringing(motion, R_BS, o);

  SynthRandom gyro_noise(o.seed, SynthStream::kGyroNoise);
  SynthRandom accel_noise(o.seed, SynthStream::kAccelNoise);
  SynthRandom mag_noise(o.seed, SynthStream::kMagNoise);
  SynthRandom drift_walk(o.seed, SynthStream::kDriftWalk);
  const auto normal3 = [](SynthRandom& random) {
    const double x = random.Normal();
    const double y = random.Normal();
    const double z = random.Normal();
    return Eigen::Vector3d(x, y, z);
  };

  Eigen::Vector3d walk_deg = Eigen::Vector3d::Zero();
  Eigen::Quaterniond previous_q_WS = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond q_gyro_error_W = Eigen::Quaterniond::Identity();  // F: the device starts at the truth
  for (std::size_t n = 0; n < count; ++n) {
    const double t = motion.t_s(n);
    const Eigen::Matrix3d R_WS = R_WB[n] * R_BS;

    // Gyroscope.
    const Eigen::Vector3d w_S_dps = kDegPerRad * (R_BS.transpose() * motion.w_B[n]);
    const Eigen::Vector3d gyro = w_S_dps + o.gyro_bias_dps + out.ringing_dps[n] + o.gyro_noise_dps * normal3(gyro_noise);
    const Eigen::Vector3d gyro_read_dps =
        ToSensorValue(gyro, kXimuGyroResolutionDps, -o.gyro_full_scale_dps, o.gyro_full_scale_dps, o.quantisation);
    out.gyro_dps[n] = gyro_read_dps.cast<float>();

    // The on-board attitude integrates this reading: its error part e_S (bias, ringing, noise, quantisation,
    // saturation) turns the estimate away from the truth by F, R_dev = F·R_WS, with dF/dt = F·[R_WS e_S]× —
    // exact for the continuous equations, since R_dev' = R_dev·[w_S + e_S]× and R_WS' = R_WS·[w_S]×. F is
    // stepped as the device steps its estimate, the reading of sample n held over the interval ending at it.
    const Eigen::Vector3d gyro_error_S_rad = (gyro_read_dps - w_S_dps) / kDegPerRad;
    if (n > 0) q_gyro_error_W = (q_gyro_error_W * RotationVectorExp(R_WS * gyro_error_S_rad * dt_s)).normalized();
    const Eigen::AngleAxisd gyro_error_W(q_gyro_error_W);
    out.gyro_error_W_rad[n] = gyro_error_W.angle() * gyro_error_W.axis();

    // Accelerometer: specific force of the sensor point, a rigid body turning about the momentary pivot.
    const Eigen::Vector3d r_W = R_WB[n] * (mounting.p_BS_B - motion.p_BK_B[n]);
    const Eigen::Vector3d a_W = dw_W[n].cross(r_W) + w_W[n].cross(w_W[n].cross(r_W));
    const Eigen::Vector3d specific_force_S_g = R_WS.transpose() * (a_W + Eigen::Vector3d(0.0, 0.0, g)) / g;
    const Eigen::Vector3d accel = specific_force_S_g + o.accel_noise_g * normal3(accel_noise);
    out.accel_g[n] = ToSensorFloat(accel, kXimuAccelResolutionG, -o.accel_full_scale_g, o.accel_full_scale_g, o.quantisation);

    // Magnetometer.
    const Eigen::Vector3d mag = R_WS.transpose() * o.mag_field_W_G + o.mag_noise_G * normal3(mag_noise);
    out.mag_G[n] = ToSensorFloat(mag, kXimuMagResolutionGauss, -32768.0 / 2048.0, kXimuMagSaturationGauss, o.quantisation);

    // Attitude estimate: ZYX Euler angles of the gyro-integrated sensor attitude plus drift, as a quaternion.
    if (n > 0) walk_deg += std::sqrt(dt_s) * o.drift_walk_deg_per_rt_s.cwiseProduct(normal3(drift_walk));
    out.drift_deg[n] = o.drift_slope_dps * t + walk_deg;
    const Eigen::Matrix3d R_WS_device = q_gyro_error_W.toRotationMatrix() * R_WS;
    Eigen::Vector3d euler_zyx = EulerZyxFromRotation(R_WS_device);  // (φz, φy, φx)
    euler_zyx += Eigen::Vector3d(out.drift_deg[n].z(), out.drift_deg[n].y(), out.drift_deg[n].x()) / kDegPerRad;
    Eigen::Quaterniond q_WS = QuaternionFromEulerZyx(euler_zyx);
    if (n > 0 && q_WS.dot(previous_q_WS) < 0.0) q_WS.coeffs() = -q_WS.coeffs();  // the device's estimate is continuous
    previous_q_WS = q_WS;
    out.quaternion[n] = DeviceQuaternion(q_WS.conjugate(), o.quantisation);
    out.euler_deg[n] = XimuEulerDegFromFileQuaternion(out.quaternion[n]);
  }
  return out;
}

}  // namespace rockfit::io
