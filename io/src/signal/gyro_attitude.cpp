#include "rockfit/io/gyro_attitude.hpp"

#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/enum_names.hpp"
#include "rockfit/core/errors.hpp"
#include "recording/attitude.hpp"
#include "rockfit/io/impact_detection.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {

void GyroAttitudeOptions::Validate() const {
  rest.Validate();
  for (std::size_t i = 0; i < impact_times_s.size(); ++i) {
    if (!std::isfinite(impact_times_s[i]) || (i > 0 && !(impact_times_s[i] > impact_times_s[i - 1]))) {
      throw InvalidArgument(fmt::format("GyroAttitudeOptions::impact_times_s[{}] = {}: the impact times must be "
                                        "finite and increasing",
                                        i, impact_times_s[i]));
    }
  }
}

const char* ToString(AttitudeStart start) {
  switch (start) {
    case AttitudeStart::kAccelerometer: return "accelerometer";
    case AttitudeStart::kLevel: return "level";
  }
  return "unknown";
}

bool FromString(std::string_view text, AttitudeStart* value) {
  static constexpr AttitudeStart kAll[] = {AttitudeStart::kAccelerometer, AttitudeStart::kLevel};
  return core::FromStringAmong(text, kAll, value);
}

Eigen::Quaterniond BodyRateStep(const Eigen::Vector3d& w_B, double dt_s) {
  const Eigen::Vector3d half_angle = 0.5 * dt_s * w_B;
  const double theta = half_angle.norm();
  // Below this half-angle [rad] sin(θ)/θ = 1 − θ²/6 to double precision and the division would lose digits.
  constexpr double kSmallHalfAngle_rad = 1e-8;
  const double sinc = theta < kSmallHalfAngle_rad ? 1.0 - theta * theta / 6.0 : std::sin(theta) / theta;
  return Eigen::Quaterniond(std::cos(theta), sinc * half_angle.x(), sinc * half_angle.y(), sinc * half_angle.z());
}

Eigen::Quaterniond ImpactIntervalStep(const Eigen::Vector3d& w_before_B, const Eigen::Vector3d& w_after_B,
                                      double t0_s, double impact_s, double t1_s) {
  return BodyRateStep(w_before_B, impact_s - t0_s) * BodyRateStep(w_after_B, t1_s - impact_s);
}

Eigen::Vector3d LevelledEulerZyx(const Eigen::Vector3d& f_B) {
  const double phi_x = std::atan2(f_B.y(), f_B.z());
  const double phi_y = std::atan2(-f_B.x(), std::hypot(f_B.y(), f_B.z()));
  return {0.0, phi_y, phi_x};
}

GyroAttitude IntegrateGyroAttitude(const Recording& recording, const GyroAttitudeOptions& options) {
  options.Validate();
  const std::size_t n = recording.size();
  if (recording.w_B.size() != n || (recording.has_accel() && recording.accel_B.size() != n)) {
    throw BadInput("recording '" + recording.source + "': time, angular velocity and accelerometer differ in length");
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (recording.w_B[k].allFinite() && recording.w_B[k].cwiseAbs().maxCoeff() > kMaxIntegrableRate_rad_s) {
      throw BadInput(fmt::format("recording '{}': sample {} (t = {:.6g} s) has an angular rate of {:.3g} rad/s, beyond "
                                 "any gyro (at most {:g} rad/s here); check the gyro columns' unit, or cut the file "
                                 "where the values go wrong",
                                 recording.source, k, recording.t_s[k], recording.w_B[k].cwiseAbs().maxCoeff(),
                                 kMaxIntegrableRate_rad_s));
    }
    if (!std::isfinite(recording.t_s[k]) || !recording.w_B[k].allFinite() ||
        (k > 0 && !(recording.t_s[k] > recording.t_s[k - 1]))) {
      throw BadInput("recording '" + recording.source + "': sample " + std::to_string(k) +
                     " has a time or angular velocity that is not finite, or a time that does not increase");
    }
  }
  GyroAttitude result;
  if (n == 0) return result;

  // The rest before the release: found from the gyro as the mounting estimate finds it. Without an accelerometer
  // the estimate is given a constant vertical specific force, so that only its rest finder speaks.
  Recording probe;
  const Recording* rest_source = &recording;
  if (!recording.has_accel()) {
    probe.source = recording.source;
    probe.rate_hz = recording.rate_hz;
    probe.t_s = recording.t_s;
    probe.w_B = recording.w_B;
    probe.accel_B.assign(n, Eigen::Vector3d(0.0, 0.0, kMetresPerSecond2PerG));
    rest_source = &probe;
  }
  const MountingEstimate rest = EstimateMounting(*rest_source, options.rest);
  if (rest.rest_before_samples > 0) {
    result.gyro_bias_rad_s = rest.gyro_bias_rad_s;
    result.rest_samples = rest.rest_before_samples;
  }
  if (recording.has_accel() && rest.rest_before_samples > 0) {
    Eigen::Vector3d f_B = Eigen::Vector3d::Zero();
    for (std::size_t k = rest.rest_before_first; k < rest.rest_before_first + rest.rest_before_samples; ++k) {
      f_B += recording.accel_B[k];
    }
    if (f_B.allFinite() && f_B.norm() > 0.0) {
      result.start = AttitudeStart::kAccelerometer;
      result.start_euler_zyx = LevelledEulerZyx(f_B);
    }
  }
  // Without a levelled start: level at the first impact, where the block lands on its base (φx = φy = 0 to the
  // rate times half a sample), else at the first sample.
  std::size_t level_at = 0;
  if (result.start == AttitudeStart::kLevel) {
    const std::vector<Peak> impacts = DetectRatePeaks(recording, 1, ImpactDetectionOptions{});
    if (!impacts.empty()) level_at = impacts.front().index;
    result.warnings.push_back(fmt::format(
        "the attitude was integrated from the gyro and levelled at {} ({}); the drift correction removes the error "
        "of that start at the impacts",
        level_at > 0 ? fmt::format("the first impact (t = {:.3f} s)", recording.t_s[level_at]) : "the first sample",
        !recording.has_accel() ? "the recording has no accelerometer to show the tilt at rest"
                               : "no rest before the release to level it by the accelerometer: " + rest.check.message));
  }

  // The levelled attitude holds during the rest; integrate from the first sample (the rest's rates are the bias).
  Eigen::Quaterniond q_WB = QuaternionFromEulerZyx(result.start_euler_zyx);
  result.euler_zyx.resize(n);
  result.euler_zyx[0] = EulerZyxFromQuaternion(q_WB);
  const std::vector<double>& t = recording.t_s;
  const auto w = [&](std::size_t k) -> Eigen::Vector3d { return recording.w_B[k] - result.gyro_bias_rad_s; };
  auto next_impact = options.impact_times_s.begin();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    while (next_impact != options.impact_times_s.end() && *next_impact < t[k]) ++next_impact;
    std::size_t inside = 0;  // impact times in [t_k, t_k+1]
    const double split_at_s = next_impact != options.impact_times_s.end() ? *next_impact : 0.0;
    while (next_impact != options.impact_times_s.end() && *next_impact <= t[k + 1]) ++next_impact, ++inside;
    if (inside == 1) {
      q_WB = q_WB * ImpactIntervalStep(w(k), w(k + 1), t[k], split_at_s, t[k + 1]);
    } else {
      // No impact, or several (a cascade of impacts as the block settles: the rate between them is not sampled).
      q_WB = q_WB * BodyRateStep(0.5 * (w(k) + w(k + 1)), t[k + 1] - t[k]);
    }
    q_WB.normalize();  // keeps |q| = 1 against round-off over 10^5 steps
    result.euler_zyx[k + 1] = EulerZyxFromQuaternion(q_WB);
  }
  if (level_at > 0) {
    // q'_k = q_level⁻¹ ⊗ q_k makes the attitude at the impact level with the same yaw (a rotation of the world).
    Eigen::Quaterniond at_impact = QuaternionFromEulerZyx(result.euler_zyx[level_at]);
    const Eigen::Quaterniond yaw = QuaternionFromEulerZyx({result.euler_zyx[level_at][0], 0.0, 0.0});
    const Eigen::Quaterniond shift = yaw * at_impact.conjugate();
    for (Eigen::Vector3d& e : result.euler_zyx) e = EulerZyxFromQuaternion(shift * QuaternionFromEulerZyx(e));
    result.start_euler_zyx = result.euler_zyx[0];
  }
  UnwrapAngles(result.euler_zyx);
  return result;
}

Recording WithAttitude(const Recording& recording, const GyroAttitudeOptions& options) {
  if (recording.has_euler()) return recording;
  Recording result = recording;
  GyroAttitude attitude = IntegrateGyroAttitude(recording, options);
  result.euler_zyx = std::move(attitude.euler_zyx);
  result.orientation_source =
      attitude.start == AttitudeStart::kAccelerometer
          ? fmt::format("integrated from the gyro, levelled by the accelerometer over {} samples at rest "
                        "(φx = {:.3f}°, φy = {:.3f}°)",
                        attitude.rest_samples, attitude.start_euler_zyx[2] / kRadPerDeg,
                        attitude.start_euler_zyx[1] / kRadPerDeg)
          : "integrated from the gyro, levelled at the first impact (no accelerometer or no rest to level it by)";
  result.orientation_rate_hz = recording.rate_hz;
  for (std::string& w : attitude.warnings) result.warnings.push_back(std::move(w));
  return result;
}

}  // namespace rockfit::io
