// Recordings made from known motion for the tests of drift correction, OPMF and AVRF.
//
// PlanarRocking integrates the 1-DOF rocking of a rigid block in the xz plane (Housner's equation of motion)
// about alternating base edges, with Chatzis' AVRF (6) at each impact, to round-off accuracy (RK4 with 32 steps
// per output sample, impacts located to 1e-13 s). It stands in for the hybrid simulator (core, not on main yet)
// with λ_lat = 0, where the facet map equals (6) (docs/design.md §3). MakeRecording adds what an IMU adds: linear and
// random-walk drift of the Euler angles, white gyro noise and gyro ringing after impacts, with fixed seeds.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"
#include "signal/euler_kinematics.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::testing {

// A block like the paper's (b1 = 5 cm, h = 20 cm: atan(b1/h) = 0.245 rad, Sect. 3.1), granite.
inline core::Block PaperLikeBlock(double b2_m = 0.05) { return core::Block::FromDensity(0.05, b2_m, 0.20, 2692.0); }

// (6) with θ = Θ_yy, b = b1: the AVRF of Chatzis' map for rocking about y.
inline double ChatzisAvrfAboutY(const core::Block& block, double lambda) {
  const double m = block.mass(), h = block.h(), b = block.b1(), theta = block.inertia_C_B()(1, 1);
  return (theta + m * h * h - m * lambda * b * b) / (theta + m * h * h + m * lambda * b * b);
}

struct PlanarRockingSpec {
  double alpha_rad = 0.20;    // release tilt (φy = −α, +x side lifted, docs/design.md §2)
  double lambda = 0.6;        // Chatzis' λ of every impact
  double rate_hz = 256.0;     // the paper's IMU rate
  double release_s = 0.5;     // at rest on the release edge until then
  double duration_s = 4.0;
  int max_impacts = 40;       // then the block is put to rest
  double rest_rate_rad_s = 0.02;  // a post-impact rate below this also ends the motion
  int substeps = 32;          // RK4 steps per output sample
};

struct PlanarRocking {
  double r = 0.0;                     // r_Cha(λ)
  std::vector<double> t_s;            // samples k / rate
  std::vector<double> phi_y_rad;      // true inclination φ_y
  std::vector<double> omega_y_rad_s;  // true ω_y (= φ̇_y in the plane)
  std::vector<double> impact_times_s;
  std::vector<double> omega_minus_rad_s;
  std::vector<double> omega_plus_rad_s;
  // |φ_y| at the peak after each impact from energy conservation (exact, not sampled).
  std::vector<double> peak_angles_rad;
};

// Planar rocking of `block` (θ = Θ_yy, b = b1) with the pivot on the base edge on the side of the inclination:
//   φ̈ = −s·p²·sin(α_c − s·φ),  s = −1 on V1V2 (φ ≤ 0), +1 on V3V4,  p² = m g R / J,  J = Θ_yy + m R²,
// R = √(b1² + h²), α_c = atan(b1/h). At φ = 0: ω⁺ = r·ω⁻ (6), and the pivot switches.
inline PlanarRocking SimulatePlanarRocking(const core::Block& block, const PlanarRockingSpec& spec) {
  const double g = core::kStandardGravity;
  const double m = block.mass(), b = block.b1(), h = block.h();
  const double radius = std::hypot(b, h), alpha_c = std::atan2(b, h);
  const double inertia_pivot = block.inertia_C_B()(1, 1) + m * radius * radius;
  const double p2 = m * g * radius / inertia_pivot;
  PlanarRocking out;
  out.r = ChatzisAvrfAboutY(block, spec.lambda);

  double side = -1.0;  // pivot V1V2
  double phi = -spec.alpha_rad, omega = 0.0, t = spec.release_s;
  bool resting = false;
  const auto accel = [&](double angle) { return -side * p2 * std::sin(alpha_c - side * angle); };
  const auto rk4 = [&](double angle, double rate, double step, double& angle_out, double& rate_out) {
    const double k1p = rate, k1w = accel(angle);
    const double k2p = rate + 0.5 * step * k1w, k2w = accel(angle + 0.5 * step * k1p);
    const double k3p = rate + 0.5 * step * k2w, k3w = accel(angle + 0.5 * step * k2p);
    const double k4p = rate + step * k3w, k4w = accel(angle + step * k3p);
    angle_out = angle + step / 6.0 * (k1p + 2 * k2p + 2 * k3p + k4p);
    rate_out = rate + step / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  };
  const double h_step = 1.0 / (spec.rate_hz * spec.substeps);
  const auto samples = static_cast<std::size_t>(std::floor(spec.duration_s * spec.rate_hz)) + 1;
  for (std::size_t k = 0; k < samples; ++k) {
    const double t_k = static_cast<double>(k) / spec.rate_hz;
    while (!resting && t_k > spec.release_s && t < t_k - 1e-15) {
      const double step = std::min(h_step, t_k - t);
      double phi1, omega1;
      rk4(phi, omega, step, phi1, omega1);
      if (side * phi1 >= 0.0) {
        phi = phi1, omega = omega1, t += step;
        continue;
      }
      // The base lands inside this step: bisect the RK4 step length for φ = 0.
      double lo = 0.0, hi = step;
      for (int it = 0; it < 200 && hi - lo > 1e-14; ++it) {
        const double mid = 0.5 * (lo + hi);
        double pm, wm;
        rk4(phi, omega, mid, pm, wm);
        (side * pm >= 0.0 ? lo : hi) = mid;
      }
      double p_hit, w_hit;
      rk4(phi, omega, hi, p_hit, w_hit);
      t += hi;
      const double w_plus = out.r * w_hit;  // (2), (6)
      out.impact_times_s.push_back(t);
      out.omega_minus_rad_s.push_back(w_hit);
      out.omega_plus_rad_s.push_back(w_plus);
      // Energy: ½ J ω⁺² = m g u(φ_peak), u = R cos(α_c − φ) − h.
      const double c = std::cos(alpha_c) + inertia_pivot * w_plus * w_plus / (2.0 * m * g * radius);
      out.peak_angles_rad.push_back(c < 1.0 ? alpha_c - std::acos(c) : alpha_c);
      side = -side;
      phi = 0.0;
      omega = w_plus;
      if (static_cast<int>(out.impact_times_s.size()) >= spec.max_impacts ||
          std::abs(w_plus) < spec.rest_rate_rad_s) {
        resting = true;
        phi = 0.0;
        omega = 0.0;
      }
    }
    out.t_s.push_back(t_k);
    out.phi_y_rad.push_back(resting && t_k >= t ? 0.0 : phi);
    out.omega_y_rad_s.push_back(resting && t_k >= t ? 0.0 : omega);
  }
  return out;
}

// What the IMU adds to the true motion. Drift and its random walk go into the Euler angles; noise and ringing
// into the gyro (ringing is a rotation of the sensor board, so its integral also enters the angles).
struct MeasurementModel {
  Eigen::Vector3d drift_offset_rad = Eigen::Vector3d::Zero();    // (φz, φy, φx) at t = 0
  Eigen::Vector3d drift_rate_rad_s = Eigen::Vector3d::Zero();    // linear drift
  double random_walk_rad_per_sqrt_s = 0.0;  // angle random walk of each Euler angle
  double gyro_noise_rad_s = 0.0;            // white noise on each gyro axis
  double ringing_fraction = 0.0;            // ringing amplitude / |ω⁻| of the impact, on ω_y
  double ringing_hz = 80.0;
  double ringing_decay_s = 0.008;
  std::uint32_t seed = 20211230;
};

struct MeasuredRecording {
  io::Recording recording;
  std::vector<Eigen::Vector3d> true_euler_zyx;  // without drift, ringing or noise
  std::vector<Eigen::Vector3d> drift_zyx;       // what was added to the angles (linear + random walk + ∫ringing)
};

inline MeasuredRecording MakeRecording(const std::vector<double>& t_s, const std::vector<Eigen::Vector3d>& euler_zyx,
                                       const std::vector<Eigen::Vector3d>& w_B, double rate_hz,
                                       const std::vector<double>& impact_times_s,
                                       const std::vector<double>& omega_minus_rad_s, const MeasurementModel& model) {
  MeasuredRecording out;
  out.true_euler_zyx = euler_zyx;
  io::Recording& rec = out.recording;
  rec.format = "test";
  rec.source = "synthetic planar rocking";
  rec.rate_hz = rate_hz;
  rec.rate_source = io::RateSource::kOption;
  rec.t_s = t_s;
  std::mt19937_64 rng(model.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d walk = Eigen::Vector3d::Zero();
  const double dt = 1.0 / rate_hz;
  const double a = 1.0 / model.ringing_decay_s, w = 2.0 * M_PI * model.ringing_hz;
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    const double t = t_s[k];
    if (k > 0) {
      for (int axis = 0; axis < 3; ++axis) walk[axis] += model.random_walk_rad_per_sqrt_s * std::sqrt(dt) * normal(rng);
    }
    double ring = 0.0, ring_integral = 0.0;
    for (std::size_t i = 0; i < impact_times_s.size(); ++i) {
      const double since = t - impact_times_s[i];
      if (since <= 0.0) continue;
      const double amplitude = model.ringing_fraction * std::abs(omega_minus_rad_s[i]);
      ring += amplitude * std::exp(-a * since) * std::sin(w * since);
      ring_integral += amplitude * (w - std::exp(-a * since) * (a * std::sin(w * since) + w * std::cos(w * since))) /
                       (a * a + w * w);
    }
    Eigen::Vector3d drift = model.drift_offset_rad + model.drift_rate_rad_s * t + walk;
    drift[1] += ring_integral;
    out.drift_zyx.push_back(drift);
    rec.euler_zyx.push_back(euler_zyx[k] + drift);
    Eigen::Vector3d gyro = w_B[k];
    gyro.y() += ring;
    for (int axis = 0; axis < 3; ++axis) gyro[axis] += model.gyro_noise_rad_s * normal(rng);
    rec.w_B.push_back(gyro);
  }
  return out;
}

// The planar rocking as a recording: φz = φx = 0, w_B = (0, ω_y, 0).
inline MeasuredRecording MeasurePlanar(const PlanarRocking& motion, double rate_hz, const MeasurementModel& model) {
  std::vector<Eigen::Vector3d> euler, w;
  for (std::size_t k = 0; k < motion.t_s.size(); ++k) {
    euler.emplace_back(0.0, motion.phi_y_rad[k], 0.0);
    w.emplace_back(0.0, motion.omega_y_rad_s[k], 0.0);
  }
  return MakeRecording(motion.t_s, euler, w, rate_hz, motion.impact_times_s, motion.omega_minus_rad_s, model);
}

// A 3D motion with known angles built on the planar one: φx = ε(t)·φy with ε(t) = ε0·(1 + ½ sin 2π·0.7 t) (so
// φx = 0 at every impact, as at a flat landing), φz = 0.3 + 0.02 sin 2π·0.4 t; w_B from the ZYX kinematics.
inline MeasuredRecording Measure3d(const PlanarRocking& motion, double rate_hz, double epsilon0,
                                   const MeasurementModel& model) {
  std::vector<Eigen::Vector3d> euler, w;
  const double f_eps = 0.7, f_z = 0.4;
  for (std::size_t k = 0; k < motion.t_s.size(); ++k) {
    const double t = motion.t_s[k];
    const double eps = epsilon0 * (1.0 + 0.5 * std::sin(2 * M_PI * f_eps * t));
    const double eps_dot = epsilon0 * 0.5 * 2 * M_PI * f_eps * std::cos(2 * M_PI * f_eps * t);
    const double phi_y = motion.phi_y_rad[k], rate_y = motion.omega_y_rad_s[k];
    const Eigen::Vector3d angles(0.3 + 0.02 * std::sin(2 * M_PI * f_z * t), phi_y, eps * phi_y);
    const Eigen::Vector3d rates(0.02 * 2 * M_PI * f_z * std::cos(2 * M_PI * f_z * t), rate_y,
                                eps_dot * phi_y + eps * rate_y);
    euler.push_back(angles);
    w.push_back(io::BodyRatesFromEulerZyx(angles, rates));
  }
  return MakeRecording(motion.t_s, euler, w, rate_hz, motion.impact_times_s, motion.omega_minus_rad_s, model);
}

// A run of the hybrid simulator (core/simulator.hpp) as the IMU would record it: released at `release_s` of the
// recording, sampled at k/rate_hz for `duration_s`, with the IMU errors of `model` (ringing after every impact,
// scaled by its |ω⁻_y|). `trajectory` receives the simulator's output with its own time (0 at the release).
inline MeasuredRecording MeasureSimulated(const core::Block& block, const core::ModelParameters& params,
                                          double release_s, double duration_s, double rate_hz,
                                          const MeasurementModel& model, core::Trajectory* trajectory = nullptr) {
  core::SimulationOptions options;
  options.stop = core::StopCondition::kTMax;
  options.t_max_s = duration_s - release_s;
  const auto samples = static_cast<std::size_t>(std::floor(duration_s * rate_hz)) + 1;
  std::vector<double> t;
  for (std::size_t k = 0; k < samples; ++k) {
    t.push_back(static_cast<double>(k) / rate_hz);
    options.sample_times_s.push_back(t.back() - release_s);  // before 0: held at the release attitude
  }
  const core::Trajectory run = core::Simulate(block, params, options);
  t.resize(run.t_s.size());
  std::vector<double> impact_times, omega_minus;
  for (const core::ImpactRecord& impact : run.impacts) {
    impact_times.push_back(impact.t_s + release_s);
    omega_minus.push_back(impact.w_minus_B.y());
  }
  if (trajectory) *trajectory = run;
  return MakeRecording(t, run.euler_zyx, run.w_B, rate_hz, impact_times, omega_minus, model);
}

// Realistic IMU errors: 1 °/s linear drift of φy (the "large drift" of the paper's Fig. 5e), 0.3 °/s of φx,
// an angle random walk of 5e-4 rad/√s, gyro noise of 0.2 °/s rms and ringing of 5 % of the impact rate.
inline MeasurementModel RealisticImu(std::uint32_t seed = 20211230) {
  MeasurementModel model;
  model.drift_offset_rad = Eigen::Vector3d(0.4, 0.03, -0.02);
  model.drift_rate_rad_s = Eigen::Vector3d(0.01, 0.0175, 0.005);
  model.random_walk_rad_per_sqrt_s = 5e-4;
  model.gyro_noise_rad_s = 0.0035;
  model.ringing_fraction = 0.05;
  model.seed = seed;
  return model;
}

// Linear drift only (no noise, no ringing).
inline MeasurementModel LinearDriftOnly() {
  MeasurementModel model;
  model.drift_offset_rad = Eigen::Vector3d(0.4, 0.03, -0.02);
  model.drift_rate_rad_s = Eigen::Vector3d(0.01, 0.0175, 0.005);
  return model;
}

}  // namespace rockfit::testing
