// Attitude from the gyro: the quaternion step against the closed-form rotation, the levelling against a known tilt,
// and the metrics of synthetic trials read with their attitude files and without them.
#include "rockfit/io/gyro_attitude.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "recording/attitude.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/synth_recording.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::io {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() / ("rockfit_gyro_att_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(BodyRateStep, ManyStepsOfAConstantRateGiveTheClosedFormRotation) {
  const Eigen::Vector3d w_B(0.7, -1.3, 2.1);
  const double dt_s = 1.0 / 256.0;
  const int steps = 2560;
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (int k = 0; k < steps; ++k) q = q * BodyRateStep(w_B, dt_s);
  const Eigen::Quaterniond exact(Eigen::AngleAxisd(w_B.norm() * dt_s * steps, w_B.normalized()));
  // 2560 products of unit quaternions: round-off of ~1e-16 per step.
  EXPECT_LT(q.angularDistance(exact), 1e-12);
}

TEST(BodyRateStep, AZeroRateIsTheIdentity) {
  const Eigen::Quaterniond q = BodyRateStep(Eigen::Vector3d::Zero(), 0.01);
  EXPECT_EQ(q.w(), 1.0);
  EXPECT_EQ(q.vec().norm(), 0.0);
}

TEST(ImpactIntervalStep, ARateThatJumpsInsideTheIntervalGivesTheExactAngle) {
  // About a fixed axis the rotation is exp of the angle ω⁻·(τ − t0) + ω⁺·(t1 − τ), for any τ in the interval.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
  const double t0_s = 0.25, t1_s = 0.25 + 1.0 / 256.0;
  for (const double fraction : {0.0, 0.13, 0.5, 0.91, 1.0}) {
    const double impact_s = t0_s + fraction * (t1_s - t0_s);
    const double before_rad_s = 1.4, after_rad_s = -0.9;  // the rate drops and reverses, as at a rocking impact
    const Eigen::Quaterniond q =
        ImpactIntervalStep(before_rad_s * axis, after_rad_s * axis, t0_s, impact_s, t1_s);
    const double angle_rad = before_rad_s * (impact_s - t0_s) + after_rad_s * (t1_s - impact_s);
    const Eigen::Quaterniond exact(Eigen::AngleAxisd(angle_rad, axis));
    // Two products of unit quaternions: round-off only.
    EXPECT_LT(q.angularDistance(exact), 1e-14) << fraction;
  }
}

// A recording turning about its z axis (yaw: no tilt, so neither levelling moves it) whose rate jumps from
// before_rad_s to after_rad_s at impact_s, inside a sample interval; the rest before it gives a zero bias.
Recording YawJump(double before_rad_s, double after_rad_s, double impact_s) {
  Recording r;
  r.source = "yaw_jump";
  r.rate_hz = 256.0;
  for (int k = 0; k < 512; ++k) {
    const double t_s = k / r.rate_hz;
    r.t_s.push_back(t_s);
    r.w_B.emplace_back(0.0, 0.0, t_s < 0.5 ? 0.0 : (t_s < impact_s ? before_rad_s : after_rad_s));
  }
  return r;
}

TEST(IntegrateGyroAttitude, SplitAtTheImpactARateJumpInsideAnIntervalGivesTheExactAngle) {
  const double before_rad_s = 1.2, after_rad_s = 0.4;
  const double impact_s = 1.0 + 0.3 / 256.0;  // 0.3 of the way into the interval after t = 1 s
  const Recording r = YawJump(before_rad_s, after_rad_s, impact_s);
  // φz at the end: the rate from 0.5 s to the impact, then after.
  const double exact_rad = before_rad_s * (impact_s - 0.5) + after_rad_s * (r.t_s.back() - impact_s);
  GyroAttitudeOptions split;
  split.impact_times_s = {0.5, impact_s};  // the start at 0.5 s is a jump too, at a sample time
  const GyroAttitude with = IntegrateGyroAttitude(r, split);
  const GyroAttitude without = IntegrateGyroAttitude(r);
  // 511 quaternion steps: round-off only.
  constexpr double kRoundOff_rad = 1e-12;
  EXPECT_NEAR(with.euler_zyx.back()[0], exact_rad, kRoundOff_rad);
  // The mean of an interval's two samples puts a jump in its middle: off by (ω⁻ − ω⁺)·(t_mid − τ) for each jump
  // (the start's τ is the end of its interval).
  const double dt_s = 1.0 / 256.0;
  const double midpoint_error_rad =
      (0.0 - before_rad_s) * (-0.5 * dt_s) + (before_rad_s - after_rad_s) * (1.0 + 0.5 * dt_s - impact_s);
  EXPECT_NEAR(without.euler_zyx.back()[0] - exact_rad, midpoint_error_rad, kRoundOff_rad);
}

TEST(GyroAttitudeOptions, ImpactTimesThatDoNotIncreaseAreRefused) {
  GyroAttitudeOptions o;
  o.impact_times_s = {1.0, 1.0};
  EXPECT_THROW(o.Validate(), InvalidArgument);
  o.impact_times_s = {1.0, std::nan("")};
  EXPECT_THROW(o.Validate(), InvalidArgument);
  o.impact_times_s = {1.0, 2.0};
  EXPECT_NO_THROW(o.Validate());
}

TEST(LevelledEulerZyx, TheSpecificForceOfATiltedBlockGivesItsRollAndPitch) {
  for (const Eigen::Vector3d& zyx : {Eigen::Vector3d(0.0, -0.2, 0.0), Eigen::Vector3d(0.0, 0.1, -0.3),
                                    Eigen::Vector3d(0.0, 1.2, 0.7)}) {
    // At rest the accelerometer reads g·R_WBᵀ·e_z, whatever the yaw.
    const Eigen::Vector3d f_B = RotationFromEulerZyx(zyx + Eigen::Vector3d(0.9, 0, 0)).transpose() * Eigen::Vector3d(0, 0, 9.81);
    EXPECT_LT((LevelledEulerZyx(f_B) - zyx).norm(), 1e-12) << zyx.transpose();
  }
}

core::Block GraniteBlock() { return core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0); }

core::ModelParameters Rocking3d(double lambda_lat) {
  core::ModelParameters p;
  p.alpha_rad = 0.2;
  p.lambda = 1.2;
  p.lambda_lat = lambda_lat;
  p.lambda_lon = 0.6;
  return p;
}

TEST(IntegrateGyroAttitude, AnIdealRecordingGivesTheTrueAttitude) {
  SynthRecordingOptions o;
  o.t0_s = 1.0;
  o.duration_s = 6.0;
  o.measurement = MeasurementOptions::Ideal();
  const SynthRecording synth = Synthesize(GraniteBlock(), Rocking3d(-1.0), o);
  TempDir dir;
  WriteSynthRecording((dir.path() / "t").string(), GraniteBlock(), Rocking3d(-1.0), o, synth);
  LoadOptions gyro_only;
  gyro_only.orientation = OrientationChoice::kNone;
  const Recording r = LoadRecording(dir.path() / "t", gyro_only);
  ASSERT_FALSE(r.has_euler());
  const GyroAttitude a = IntegrateGyroAttitude(r);
  EXPECT_EQ(a.start, AttitudeStart::kAccelerometer);
  ASSERT_EQ(a.euler_zyx.size(), synth.motion.size());
  double worst_rad = 0.0;
  for (std::size_t k = 0; k < synth.motion.size(); ++k) {
    const Eigen::Vector3d truth = EulerZyxFromQuaternion(synth.motion.q_WB[k]);
    worst_rad = std::max({worst_rad, std::abs(a.euler_zyx[k][1] - truth[1]), std::abs(a.euler_zyx[k][2] - truth[2])});
  }
  // Single-precision accelerometer at rest (levelling ≈ 1e-6 rad) plus the O(Δt²) error of the interval rate over
  // impacts, where the rate jumps inside a sample interval: up to |Δω|·Δt/2 per impact (≈ 3e-3 rad at 1 rad/s).
  constexpr double kIdealAttitudeTolerance_rad = 1e-2;
  EXPECT_LT(worst_rad, kIdealAttitudeTolerance_rad);
}

// The OPMF and AVRF of a synthetic trial with the device's artefacts (noise, bias, ringing, quantisation, the
// attitude's drift), read once with its attitude files and once from the gyro and accelerometer alone.
struct Agreement {
  double opmf_with = 0, opmf_without = 0, avrf_with = 0, avrf_without = 0;
  double corrected_phi_rad = 0;  // max |Δφy|, |Δφx| of the drift-corrected angles between the first and last impact
};

Agreement CompareMetrics(const core::ModelParameters& p, std::uint64_t seed, const std::string& mounting) {
  SynthRecordingOptions o;
  o.t0_s = 2.0;
  o.duration_s = 10.0;
  o.measurement.seed = seed;
  const Mounting m = Mounting::Parse(mounting);
  o.R_BS = m.R_BS();
  o.mounting_text = mounting;
  const SynthRecording synth = Synthesize(GraniteBlock(), p, o);
  TempDir dir;
  WriteSynthRecording((dir.path() / "t").string(), GraniteBlock(), p, o, synth);
  LoadOptions with;
  with.mounting = m;
  LoadOptions without = with;
  without.orientation = OrientationChoice::kNone;
  const MetricsSummary a = ComputeTrialMetrics(LoadRecording(dir.path() / "t", with), GraniteBlock(), {});
  const MetricsSummary b = ComputeTrialMetrics(LoadRecording(dir.path() / "t", without), GraniteBlock(), {});
  EXPECT_TRUE(a.ok()) << a.message;
  EXPECT_TRUE(b.ok()) << b.message;
  EXPECT_EQ(a.correction.attitude, "file");
  EXPECT_NE(b.correction.attitude.find("levelled by the accelerometer"), std::string::npos) << b.correction.attitude;
  double worst_rad = 0.0;
  const Recording& timeline = LoadRecording(dir.path() / "t", with);
  for (std::size_t k = 0; k < timeline.size(); ++k) {
    if (timeline.t_s[k] < a.correction.first_impact_s() || timeline.t_s[k] > a.correction.last_impact_s()) continue;
    const Eigen::Vector3d d = a.correction.euler_corrected_zyx[k] - b.correction.euler_corrected_zyx[k];
    worst_rad = std::max({worst_rad, std::abs(d[1]), std::abs(d[2])});
  }
  return {a.opmf.opmf, b.opmf.opmf, a.avrf.avrf, b.avrf.avrf, worst_rad};
}

// The required agreement of gyro-only metrics (io/README.md, "Attitude from the gyro"): OPMF within 0.003, AVRF
// within 1 % of the values from the device's attitude.
constexpr double kOpmfAgreement = 0.003;
constexpr double kAvrfRelativeAgreement = 0.01;
// The drift-corrected angles agree to what the device's own attitude filter adds between impacts (its drift and
// random walk, synth_measurement.hpp) plus what is left of the integrated attitude's step at each impact once the
// impacts are located where the levelled angle is zero: measured ≤ 1.5e-3 rad on these cases (2.5e-3 by the mean
// rule alone, 3.9e-3 while synth's attitude lacked the gyro's errors).
constexpr double kCorrectedAngleAgreement_rad = 2.5e-3;

TEST(GyroOnlyMetrics, OpmfAndAvrfAgreeWithThoseFromTheDevicesAttitude) {
  struct Case {
    double lambda_lat;
    std::uint64_t seed;
    const char* mounting;
  };
  for (const Case c : {Case{-1.0, 1, "x,y,z"}, Case{-1.5, 2, "x,-y,-z"}, Case{0.0, 3, "x,y,z"}, Case{-0.5, 4, "-y,x,z"}}) {
    const Agreement g = CompareMetrics(Rocking3d(c.lambda_lat), c.seed, c.mounting);
    std::cout << "[ measured ] λ_lat " << c.lambda_lat << " seed " << c.seed << " mounting " << c.mounting
              << ": OPMF " << g.opmf_with << " vs " << g.opmf_without << ", AVRF " << g.avrf_with << " vs "
              << g.avrf_without << " (" << 100.0 * (g.avrf_without / g.avrf_with - 1.0) << " %), corrected φ within "
              << g.corrected_phi_rad << " rad\n";
    EXPECT_NEAR(g.opmf_without, g.opmf_with, kOpmfAgreement) << c.seed;
    EXPECT_NEAR(g.avrf_without / g.avrf_with, 1.0, kAvrfRelativeAgreement) << c.seed;
    EXPECT_LT(g.corrected_phi_rad, kCorrectedAngleAgreement_rad) << c.seed;
  }
}

TEST(GyroOnlyMetrics, WithoutAnAccelerometerTheStartIsLevelWithAWarning) {
  Recording r;
  r.rate_hz = 100.0;
  for (int k = 0; k < 200; ++k) {
    r.t_s.push_back(k / 100.0);
    r.w_B.emplace_back(0.0, 0.5, 0.0);
  }
  const GyroAttitude a = IntegrateGyroAttitude(r);
  EXPECT_EQ(a.start, AttitudeStart::kLevel);
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_NE(a.warnings.front().find("levelled at"), std::string::npos);
  EXPECT_NEAR(a.euler_zyx.back()[1], 0.5 * 1.99, 1e-12);  // φy = ω·t for a rotation about y alone
}

TEST(IntegrateGyroAttitude, ARateBeyondAnyGyroIsBadInputNotAnOverflow) {
  // Found by fuzzing: 2.7e301 rad/s passes the reader (a finite number) but the step's angle overflowed to NaN.
  Recording r;
  r.source = "g.csv";
  r.rate_hz = 100.0;
  for (int k = 0; k < 10; ++k) {
    r.t_s.push_back(k / 100.0);
    r.w_B.emplace_back(0.0, k == 3 ? -2.7e301 : 0.1, 0.0);
  }
  try {
    IntegrateGyroAttitude(r);
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("sample 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("beyond any gyro"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rockfit::io
