// The measurement model on hand-made motions with closed-form signals: ideal sensor, mounting, specific
// force, ringing, the gyro errors the attitude estimate integrates, and the statistics of noise, quantisation
// and drift against their sampling error.
#include "rockfit/io/synth_measurement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <vector>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;
constexpr double kRate = 256.0;
// Single precision holds 24 bits: a value v is stored to |v|·2⁻²⁴ (≈6e-8 relative).
constexpr double kFloatRelative = 1.0 / 16777216.0;
// Euler angles pass through a single-precision quaternion: about 4 float ulps of a unit quaternion
// (2.4e-7 rad, amplified by 1/cos φy for roll and yaw, and pitch through the arctangent) plus the
// single-precision degree conversion of an angle up to 180° (1.1e-5 deg).
double SinglePrecisionAngleToleranceDeg(double pitch_rad) {
  return 2.4e-7 * kDegPerRad / std::cos(pitch_rad) + 180.0 * kFloatRelative;
}
// Finite differences and the single-precision specific force: |f| ≤ 2 g stored to ~1.2e-7 g; central
// differences of smooth test motions are exact or nearly so.
constexpr double kAccelToleranceG = 1e-6;

// ZYX Euler angles (φz, φy, φx) of R = Rz(φz)·Ry(φy)·Rx(φx) (docs/design.md §2), for the expected values.
Eigen::Vector3d EulerZyxFromRotation(const Eigen::Matrix3d& R) {
  return {std::atan2(R(1, 0), R(0, 0)), std::asin(-R(2, 0)), std::atan2(R(2, 1), R(2, 2))};
}
Eigen::Quaterniond QuaternionFromEulerZyx(const Eigen::Vector3d& zyx) {
  return Eigen::AngleAxisd(zyx[0], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(zyx[1], Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(zyx[2], Eigen::Vector3d::UnitX());
}

// A motion sampled by functions of time: w_B(t), q_WB(t) and the pivot.
BlockMotion SampledMotion(std::size_t count, const std::function<Eigen::Vector3d(double)>& w_B,
                          const std::function<Eigen::Quaterniond(double)>& q_WB, const Eigen::Vector3d& pivot_B) {
  BlockMotion m;
  m.rate_hz = kRate;
  for (std::size_t n = 0; n < count; ++n) {
    const double t = m.t_s(n);
    m.w_B.push_back(w_B(t));
    m.q_WB.push_back(q_WB(t));
    m.p_BK_B.push_back(pivot_B);
  }
  return m;
}

// Steady rotation about the body's fixed axis `w_B` (constant in B and in W).
BlockMotion SteadyRotation(std::size_t count, const Eigen::Vector3d& w_B, const Eigen::Vector3d& pivot_B = Eigen::Vector3d::Zero()) {
  return SampledMotion(
      count, [w_B](double) { return w_B; },
      [w_B](double t) {
        const double angle = w_B.norm() * t;
        return angle == 0.0 ? Eigen::Quaterniond::Identity() : Eigen::Quaterniond(Eigen::AngleAxisd(angle, w_B.normalized()));
      },
      pivot_B);
}

// At rest, tilted about y by `tilt_rad` (R_WB = Ry(tilt)).
BlockMotion RestTilted(std::size_t count, double tilt_rad) {
  return SampledMotion(
      count, [](double) { return Eigen::Vector3d::Zero(); },
      [tilt_rad](double) { return Eigen::Quaterniond(Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitY())); },
      Eigen::Vector3d::Zero());
}

double StandardDeviation(const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double sum_sq = 0.0;
  for (double v : x) sum_sq += (v - mean) * (v - mean);
  return std::sqrt(sum_sq / static_cast<double>(x.size() - 1));
}

TEST(SynthMeasurement, IdealGyroscopeReportsTheTrueAngularVelocityInDegreesPerSecond) {
  const Eigen::Vector3d w_B(0.3, -1.2, 0.05);
  const DeviceSamples d = MeasureMotion(SteadyRotation(300, w_B), SensorMounting{}, MeasurementOptions::Ideal());
  ASSERT_EQ(d.size(), 300u);
  for (std::size_t n = 0; n < d.size(); ++n) {
    for (int i = 0; i < 3; ++i) EXPECT_EQ(d.gyro_dps[n][i], static_cast<float>(kDegPerRad * w_B[i]));
  }
}

TEST(SynthMeasurement, MountingExpressesTheSignalsInTheSensorFrame) {
  const Eigen::Vector3d w_B(0.3, -1.2, 0.05);
  SensorMounting mounting;
  mounting.R_BS = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();  // sensor upside down: x,-y,-z
  const DeviceSamples d = MeasureMotion(SteadyRotation(10, w_B), mounting, MeasurementOptions::Ideal());
  EXPECT_EQ(d.gyro_dps[5].x(), static_cast<float>(kDegPerRad * w_B.x()));
  EXPECT_EQ(d.gyro_dps[5].y(), static_cast<float>(-kDegPerRad * w_B.y()));
  EXPECT_EQ(d.gyro_dps[5].z(), static_cast<float>(-kDegPerRad * w_B.z()));
  // At rest flat, the upside-down sensor reads −1 g on its z axis.
  const DeviceSamples rest = MeasureMotion(RestTilted(3, 0.0), mounting, MeasurementOptions::Ideal());
  EXPECT_NEAR(rest.accel_g[1].z(), -1.0, kAccelToleranceG);
}

TEST(SynthMeasurement, MirroredMountingIsRejected) {
  SensorMounting mounting;
  mounting.R_BS = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  EXPECT_THROW(MeasureMotion(RestTilted(3, 0.0), mounting, MeasurementOptions::Ideal()), InvalidArgument);
}

TEST(SynthMeasurement, IdealEulerAnglesAndQuaternionEqualTheTrueAttitude) {
  // A tumbling attitude that visits large angles on every axis.
  const BlockMotion motion = SampledMotion(
      512, [](double) { return Eigen::Vector3d::Zero(); },
      [](double t) { return QuaternionFromEulerZyx(Eigen::Vector3d(2.5 * std::sin(t), 1.2 * std::sin(2 * t), 3.0 * std::cos(0.7 * t))); },
      Eigen::Vector3d::Zero());
  const DeviceSamples d = MeasureMotion(motion, SensorMounting{}, MeasurementOptions::Ideal());
  for (std::size_t n = 0; n < d.size(); ++n) {
    const Eigen::Vector3d zyx = EulerZyxFromRotation(motion.q_WB[n].toRotationMatrix());
    const double tolerance = SinglePrecisionAngleToleranceDeg(zyx[1]);
    EXPECT_NEAR(d.euler_deg[n].x(), kDegPerRad * zyx[2], tolerance) << n;
    EXPECT_NEAR(d.euler_deg[n].y(), kDegPerRad * zyx[1], tolerance) << n;
    EXPECT_NEAR(d.euler_deg[n].z(), kDegPerRad * zyx[0], tolerance) << n;
    // The file quaternion is the conjugate of q_WB (Earth relative to sensor), up to sign.
    const Eigen::Quaterniond q_file(d.quaternion[n][0], d.quaternion[n][1], d.quaternion[n][2], d.quaternion[n][3]);
    EXPECT_NEAR(std::abs(q_file.dot(motion.q_WB[n].conjugate())), 1.0, 4.0 * kFloatRelative) << n;
  }
}

TEST(SynthMeasurement, AccelerometerAtRestReadsOneGUpwardInTheSensorFrame) {
  const double tilt = -0.2;  // the release attitude φy = −α
  const DeviceSamples d = MeasureMotion(RestTilted(5, tilt), SensorMounting{}, MeasurementOptions::Ideal());
  // f_B = R_WBᵀ e_z = Ry(−tilt) e_z = (−sin tilt, 0, cos tilt).
  EXPECT_NEAR(d.accel_g[2].x(), -std::sin(tilt), kAccelToleranceG);
  EXPECT_NEAR(d.accel_g[2].y(), 0.0, kAccelToleranceG);
  EXPECT_NEAR(d.accel_g[2].z(), std::cos(tilt), kAccelToleranceG);
}

TEST(SynthMeasurement, SteadySpinAboutTheVerticalGivesCentripetalAcceleration) {
  const double omega = 3.0;
  const double radius = 0.05;
  SensorMounting mounting;
  mounting.p_BS_B = Eigen::Vector3d(radius, 0.0, 0.4);
  const DeviceSamples d = MeasureMotion(SteadyRotation(50, Eigen::Vector3d(0, 0, omega)), mounting, MeasurementOptions::Ideal());
  const double g = 9.81;
  for (std::size_t n = 0; n < d.size(); ++n) {
    EXPECT_NEAR(d.accel_g[n].x(), -omega * omega * radius / g, kAccelToleranceG) << n;
    EXPECT_NEAR(d.accel_g[n].y(), 0.0, kAccelToleranceG) << n;
    EXPECT_NEAR(d.accel_g[n].z(), 1.0, kAccelToleranceG) << n;
  }
}

TEST(SynthMeasurement, UniformAngularAccelerationAfterABreakGivesTheRigidBodySpecificForce) {
  // At rest until t_b, then φ(t) = ε(t − t_b)²/2 about the body y axis through the pivot at the origin.
  const double t_b = 0.25;
  const double epsilon = 4.0;
  const double height = 0.4;
  const auto phi = [=](double t) { return t < t_b ? 0.0 : 0.5 * epsilon * (t - t_b) * (t - t_b); };
  const auto rate = [=](double t) { return t < t_b ? 0.0 : epsilon * (t - t_b); };
  BlockMotion motion = SampledMotion(
      200, [&](double t) { return Eigen::Vector3d(0.0, rate(t), 0.0); },
      [&](double t) { return Eigen::Quaterniond(Eigen::AngleAxisd(phi(t), Eigen::Vector3d::UnitY())); },
      Eigen::Vector3d::Zero());
  motion.breaks_s = {t_b};
  SensorMounting mounting;
  mounting.p_BS_B = Eigen::Vector3d(0.0, 0.0, height);
  const DeviceSamples d = MeasureMotion(motion, mounting, MeasurementOptions::Ideal());
  const double g = motion.gravity_m_s2;
  for (std::size_t n = 0; n < d.size(); ++n) {
    const double t = motion.t_s(n);
    const double eps = t < t_b ? 0.0 : epsilon;
    // f_B = (ε h − g sin φ, 0, −ω² h + g cos φ) / g.
    EXPECT_NEAR(d.accel_g[n].x(), (eps * height - g * std::sin(phi(t))) / g, kAccelToleranceG) << t;
    EXPECT_NEAR(d.accel_g[n].z(), (-rate(t) * rate(t) * height + g * std::cos(phi(t))) / g, kAccelToleranceG) << t;
  }
}

// Two impacts on an otherwise steady motion: ω jumps, the block's ω pieces are constant.
BlockMotion TwoImpacts(double t1, const Eigen::Vector3d& jump1, double t2, const Eigen::Vector3d& jump2) {
  const Eigen::Vector3d w0(0.0, 1.0, 0.0);
  BlockMotion m = SampledMotion(
      768,
      [=](double t) {
        Eigen::Vector3d w = w0;
        if (t >= t1) w += jump1;
        if (t >= t2) w += jump2;
        return w;
      },
      [](double) { return Eigen::Quaterniond::Identity(); }, Eigen::Vector3d::Zero());
  m.breaks_s = {t1, t2};
  m.impacts = {{t1, w0, w0 + jump1}, {t2, w0 + jump1, w0 + jump1 + jump2}};
  return m;
}

TEST(SynthMeasurement, RingingIsTheDampedOscillationOfEachImpactsJump) {
  const double t1 = 0.5003;
  const double t2 = 1.7001;
  const Eigen::Vector3d jump1(0.1, -1.6, 0.3);
  const Eigen::Vector3d jump2(0.0, 0.4, -0.2);
  const BlockMotion motion = TwoImpacts(t1, jump1, t2, jump2);
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.ringing_gain = 0.3;
  o.ringing_frequency_hz = 37.0;
  o.ringing_decay_time_s = 0.04;
  const DeviceSamples d = MeasureMotion(motion, SensorMounting{}, o);
  for (std::size_t n = 0; n < d.size(); ++n) {
    const double t = motion.t_s(n);
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    for (const auto& [ti, jump] : {std::pair{t1, jump1}, std::pair{t2, jump2}}) {
      if (t >= ti) {
        expected += o.ringing_gain * kDegPerRad * jump * std::exp(-(t - ti) / o.ringing_decay_time_s) *
                    std::sin(2.0 * kPi * o.ringing_frequency_hz * (t - ti));
      }
    }
    const Eigen::Vector3d truth = kDegPerRad * motion.w_B[n];
    for (int i = 0; i < 3; ++i) {
      const double tolerance = 2.0 * kFloatRelative * std::abs(truth[i] + expected[i]) + 1e-12;
      EXPECT_NEAR(d.gyro_dps[n][i], truth[i] + expected[i], tolerance) << "t = " << t << " axis " << i;
    }
  }
}

TEST(SynthMeasurement, QuantisationRoundsToTheDeviceResolution) {
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.quantisation = true;
  o.gyro_noise_dps = 0.3;
  o.accel_noise_g = 0.01;
  const DeviceSamples d = MeasureMotion(SteadyRotation(400, Eigen::Vector3d(0.2, 0.7, -0.1)), SensorMounting{}, o);
  for (std::size_t n = 0; n < d.size(); ++n) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(d.gyro_dps[n][i] * 16.0f, std::round(d.gyro_dps[n][i] * 16.0f));
      EXPECT_EQ(d.accel_g[n][i] * 2048.0f, std::round(d.accel_g[n][i] * 2048.0f));
      EXPECT_EQ(d.mag_G[n][i] * 2048.0f, std::round(d.mag_G[n][i] * 2048.0f));
    }
  }
}

TEST(SynthMeasurement, GyroscopeSaturatesAtFullScale) {
  MeasurementOptions o = MeasurementOptions::Ideal();
  const DeviceSamples d = MeasureMotion(SteadyRotation(4, Eigen::Vector3d(0.0, 0.0, 50.0)), SensorMounting{}, o);
  EXPECT_EQ(d.gyro_dps[1].z(), 2000.0f);  // 50 rad/s = 2865 deg/s
}

TEST(SynthMeasurement, GyroWhiteNoiseAndBiasMatchTheRequestWithinSamplingError) {
  constexpr std::size_t kCount = 20000;
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.gyro_noise_dps = 0.1;
  o.gyro_bias_dps = Eigen::Vector3d(0.05, -0.02, 0.0);
  const Eigen::Vector3d w_B(0.0, 0.5, 0.0);
  const DeviceSamples d = MeasureMotion(SteadyRotation(kCount, w_B), SensorMounting{}, o);
  for (int i = 0; i < 3; ++i) {
    std::vector<double> residual;
    double mean = 0.0;
    for (std::size_t n = 0; n < kCount; ++n) {
      residual.push_back(d.gyro_dps[n][i] - kDegPerRad * w_B[i]);
      mean += residual.back() / kCount;
    }
    // 4 standard errors: SE(mean) = σ/√N, SE(s) = σ/√(2(N−1)).
    EXPECT_NEAR(mean, o.gyro_bias_dps[i], 4.0 * o.gyro_noise_dps / std::sqrt(kCount)) << "axis " << i;
    EXPECT_NEAR(StandardDeviation(residual), o.gyro_noise_dps, 4.0 * o.gyro_noise_dps / std::sqrt(2.0 * (kCount - 1)))
        << "axis " << i;
  }
}

TEST(SynthMeasurement, QuantisedNoiseAddsTheVarianceOfAUniformStep) {
  // Sheppard: a quantiser of step q on noise with σ > q adds variance q²/12 (the remainder is ~exp(−2π²σ²/q²)).
  constexpr std::size_t kCount = 20000;
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.gyro_noise_dps = 0.1;
  o.quantisation = true;
  const DeviceSamples d = MeasureMotion(SteadyRotation(kCount, Eigen::Vector3d(0.0, 0.01, 0.0)), SensorMounting{}, o);
  std::vector<double> residual;
  for (std::size_t n = 0; n < kCount; ++n) residual.push_back(d.gyro_dps[n].x());
  const double expected = std::sqrt(o.gyro_noise_dps * o.gyro_noise_dps + kXimuGyroResolutionDps * kXimuGyroResolutionDps / 12.0);
  EXPECT_NEAR(StandardDeviation(residual), expected, 4.0 * expected / std::sqrt(2.0 * (kCount - 1)));
}

TEST(SynthMeasurement, AccelerometerNoiseMatchesTheRequestWithinSamplingError) {
  constexpr std::size_t kCount = 20000;
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.accel_noise_g = 0.015;
  const DeviceSamples d = MeasureMotion(RestTilted(kCount, 0.0), SensorMounting{}, o);
  std::vector<double> z;
  for (std::size_t n = 0; n < kCount; ++n) z.push_back(d.accel_g[n].z());
  EXPECT_NEAR(StandardDeviation(z), o.accel_noise_g, 4.0 * o.accel_noise_g / std::sqrt(2.0 * (kCount - 1)));
}

TEST(SynthMeasurement, RingingDecayRateWithNoiseMatchesTheRequestWithinSamplingError) {
  const double t1 = 0.2;
  const Eigen::Vector3d jump(0.0, -2.0, 0.0);
  BlockMotion motion = TwoImpacts(t1, jump, 10.0, Eigen::Vector3d::Zero());
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.gyro_noise_dps = 0.1;
  o.ringing_gain = 0.25;
  o.ringing_frequency_hz = 38.0;
  o.ringing_decay_time_s = 0.03;
  const DeviceSamples d = MeasureMotion(motion, SensorMounting{}, o);
  // Residual after the impact on the y axis: y_n = A e^{−λ τ_n} sin(ω τ_n) + σ ε_n, τ_n = t_n − t1.
  const double omega = 2.0 * kPi * o.ringing_frequency_hz;
  std::vector<double> tau;
  std::vector<double> y;
  for (std::size_t n = 0; n < motion.size(); ++n) {
    const double dt = motion.t_s(n) - t1;
    if (dt < 0.0 || dt > 8.0 * o.ringing_decay_time_s) continue;
    tau.push_back(dt);
    y.push_back(d.gyro_dps[n].y() - kDegPerRad * motion.w_B[n].y());
  }
  // Least squares in (A, λ): A is linear for a given λ; λ by golden-section search.
  const auto fit_amplitude = [&](double lambda, double* ssr) {
    double sy = 0.0;
    double ss = 0.0;
    for (std::size_t k = 0; k < tau.size(); ++k) {
      const double s = std::exp(-lambda * tau[k]) * std::sin(omega * tau[k]);
      sy += s * y[k];
      ss += s * s;
    }
    const double a = sy / ss;
    *ssr = 0.0;
    for (std::size_t k = 0; k < tau.size(); ++k) {
      const double r = y[k] - a * std::exp(-lambda * tau[k]) * std::sin(omega * tau[k]);
      *ssr += r * r;
    }
    return a;
  };
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 5.0;
  double hi = 200.0;
  for (int it = 0; it < 200; ++it) {
    const double a = hi - golden * (hi - lo);
    const double b = lo + golden * (hi - lo);
    double fa = 0.0;
    double fb = 0.0;
    fit_amplitude(a, &fa);
    fit_amplitude(b, &fb);
    (fa < fb ? hi : lo) = fa < fb ? b : a;
  }
  const double lambda_hat = 0.5 * (lo + hi);
  // Standard error of λ from the Fisher information σ⁻²JᵀJ at the true (A, λ).
  const double lambda_true = 1.0 / o.ringing_decay_time_s;
  const double a_true = o.ringing_gain * kDegPerRad * jump.y();
  double jaa = 0.0;
  double jal = 0.0;
  double jll = 0.0;
  for (double t : tau) {
    const double da = std::exp(-lambda_true * t) * std::sin(omega * t);
    const double dl = -t * a_true * da;
    jaa += da * da;
    jal += da * dl;
    jll += dl * dl;
  }
  const double se_lambda = o.gyro_noise_dps * std::sqrt(jaa / (jaa * jll - jal * jal));
  EXPECT_NEAR(lambda_hat, lambda_true, 4.0 * se_lambda);
  EXPECT_LT(se_lambda, 0.05 * lambda_true);  // the test is sharp: 4 SE are less than 20 % of λ
}

TEST(SynthMeasurement, DriftSlopeAndRandomWalkMatchTheRequestWithinSamplingError) {
  constexpr std::size_t kCount = 60 * 256;  // one minute
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.drift_slope_dps = Eigen::Vector3d(0.02, -0.05, 0.4);
  o.drift_walk_deg_per_rt_s = Eigen::Vector3d(0.01, 0.02, 0.03);
  const BlockMotion motion = RestTilted(kCount, -0.1);
  const DeviceSamples d = MeasureMotion(motion, SensorMounting{}, o);
  const Eigen::Vector3d truth_deg(0.0, -0.1 * kDegPerRad, 0.0);  // (roll, pitch, yaw)
  const double duration = static_cast<double>(kCount - 1) / kRate;
  for (int i = 0; i < 3; ++i) {
    // OLS slope of the Euler-angle error; for a random walk of σ_w over T, SE(slope) = σ_w √(6 / (5 T)).
    double st = 0.0;
    double se = 0.0;
    std::vector<double> error(kCount);
    for (std::size_t n = 0; n < kCount; ++n) {
      error[n] = d.euler_deg[n][i] - truth_deg[i];
      st += motion.t_s(n);
      se += error[n];
    }
    const double t_mean = st / kCount;
    const double e_mean = se / kCount;
    double sxy = 0.0;
    double sxx = 0.0;
    for (std::size_t n = 0; n < kCount; ++n) {
      sxy += (motion.t_s(n) - t_mean) * (error[n] - e_mean);
      sxx += (motion.t_s(n) - t_mean) * (motion.t_s(n) - t_mean);
    }
    const double walk = o.drift_walk_deg_per_rt_s[i];
    EXPECT_NEAR(sxy / sxx, o.drift_slope_dps[i], 4.0 * walk * std::sqrt(6.0 / (5.0 * duration))) << "axis " << i;
    // The walk's σ from the increments (minus the slope's constant step): SE(s) = s/√(2(N−1)).
    std::vector<double> increments;
    for (std::size_t n = 1; n < kCount; ++n) increments.push_back(error[n] - error[n - 1]);
    const double sigma_step = walk * std::sqrt(1.0 / kRate);
    // Single-precision angles add a rounding of ~|angle|·6e-8 deg per sample to each increment.
    const double rounding = 2.0 * (std::abs(truth_deg[i]) + 30.0) * kFloatRelative;
    EXPECT_NEAR(StandardDeviation(increments), sigma_step, 4.0 * sigma_step / std::sqrt(2.0 * (kCount - 2)) + rounding)
        << "axis " << i;
  }
}

TEST(SynthMeasurement, GyroBiasTurnsTheAttitudeEstimateAboutTheSensorAxis) {
  // At rest tilted about y, a bias b on the sensor's x axis: the device's estimate R_WS·Rx(b·t) has the ZYX angles
  // (yaw 0, pitch = tilt, roll = b·t) — turned about the sensor's own x axis, not about the world's.
  const double tilt_rad = -0.2;
  const double bias_dps = 0.5;
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.gyro_bias_dps = Eigen::Vector3d(bias_dps, 0.0, 0.0);
  const BlockMotion motion = RestTilted(5 * 256, tilt_rad);
  const DeviceSamples d = MeasureMotion(motion, SensorMounting{}, o);
  const double tolerance = SinglePrecisionAngleToleranceDeg(tilt_rad);
  for (std::size_t n = 0; n < d.size(); ++n) {
    EXPECT_NEAR(d.euler_deg[n].x(), bias_dps * motion.t_s(n), tolerance) << n;
    EXPECT_NEAR(d.euler_deg[n].y(), kDegPerRad * tilt_rad, tolerance) << n;
    EXPECT_NEAR(d.euler_deg[n].z(), 0.0, tolerance) << n;
  }
}

TEST(SynthMeasurement, RingingsNetIntegralStaysInTheAttitudeEstimate) {
  // One impact exactly on a sample (t1 = 128/256 s) with a jump along x; the attitude is held at identity, so
  // the estimate's roll is the device's sum of its ringing samples times Δt: with z = exp((−1/T + i2πf)Δt),
  // Σ_k e^(−kΔt/T) sin(2πf kΔt) = Im 1/(1 − z) once the ringing has died away.
  const double t1 = 0.5;
  const Eigen::Vector3d jump(1.6, 0.0, 0.0);
  const BlockMotion motion = TwoImpacts(t1, jump, 10.0, Eigen::Vector3d::Zero());
  MeasurementOptions o = MeasurementOptions::Ideal();
  o.ringing_gain = 0.3;
  o.ringing_frequency_hz = 37.0;
  o.ringing_decay_time_s = 0.04;
  const DeviceSamples d = MeasureMotion(motion, SensorMounting{}, o);
  const double dt = 1.0 / kRate;
  const std::complex<double> z = std::exp(std::complex<double>(-dt / o.ringing_decay_time_s, 2.0 * kPi * o.ringing_frequency_hz * dt));
  const double sum = (1.0 / (1.0 - z)).imag();
  const double roll_deg = o.ringing_gain * kDegPerRad * jump.x() * dt * sum;
  // The continuous integral g·Δω·2πf/((2πf)² + T⁻²) is of the same size: the test's closed form is not a zero.
  const double w_r = 2.0 * kPi * o.ringing_frequency_hz;
  const double continuous_deg = o.ringing_gain * kDegPerRad * jump.x() * w_r / (w_r * w_r + 1.0 / (o.ringing_decay_time_s * o.ringing_decay_time_s));
  EXPECT_NEAR(roll_deg, continuous_deg, 0.1 * continuous_deg);
  const double tolerance = SinglePrecisionAngleToleranceDeg(0.0);
  for (std::size_t n = 0; n < d.size(); ++n) {
    if (motion.t_s(n) < t1) {
      EXPECT_NEAR(d.euler_deg[n].x(), 0.0, tolerance) << n;
    }
    // 30 decay times after the impact the envelope is e⁻³⁰: the sum is complete.
    if (motion.t_s(n) > t1 + 30.0 * o.ringing_decay_time_s) {
      EXPECT_NEAR(d.euler_deg[n].x(), roll_deg, tolerance) << n;
    }
    EXPECT_NEAR(d.euler_deg[n].y(), 0.0, tolerance) << n;
    EXPECT_NEAR(d.euler_deg[n].z(), 0.0, tolerance) << n;
  }
}

TEST(SynthMeasurement, SameSeedGivesIdenticalSamplesAndPartsUseIndependentStreams) {
  const BlockMotion motion = SteadyRotation(500, Eigen::Vector3d(0.1, 0.8, 0.0));
  MeasurementOptions o;  // every part on
  o.seed = 99;
  const DeviceSamples a = MeasureMotion(motion, SensorMounting{}, o);
  const DeviceSamples b = MeasureMotion(motion, SensorMounting{}, o);
  EXPECT_EQ(a.gyro_dps, b.gyro_dps);
  EXPECT_EQ(a.accel_g, b.accel_g);
  EXPECT_EQ(a.quaternion, b.quaternion);
  MeasurementOptions other_seed = o;
  other_seed.seed = 100;
  EXPECT_NE(MeasureMotion(motion, SensorMounting{}, other_seed).gyro_dps, a.gyro_dps);
  // Switching the drift off leaves the gyroscope noise exactly as it was.
  MeasurementOptions no_drift = o;
  no_drift.drift_walk_deg_per_rt_s.setZero();
  no_drift.drift_slope_dps.setZero();
  EXPECT_EQ(MeasureMotion(motion, SensorMounting{}, no_drift).gyro_dps, a.gyro_dps);
}

TEST(SynthMeasurement, InvalidOptionsAreRejectedNamingTheOption) {
  MeasurementOptions o;
  o.gyro_noise_dps = -1.0;
  try {
    o.Validate();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("gyro_noise_dps"), std::string::npos);
  }
  o = MeasurementOptions{};
  o.ringing_decay_time_s = 0.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
  BlockMotion motion = RestTilted(5, 0.0);
  motion.q_WB[2].coeffs() *= 2.0;
  EXPECT_THROW(MeasureMotion(motion, SensorMounting{}, MeasurementOptions{}), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
