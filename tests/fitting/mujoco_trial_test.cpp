// Fits of recordings made by other physics: a granite box released tilted from rest on a plane and simulated by
// MuJoCo (stiff soft contact, not the paper's impact maps; tests/support/mujoco_rocking.hpp), measured by rockfit's
// x-IMU model. The truth is t0 and α: the fit's 95 % intervals must hold them (or, where the release itself is not
// the model's, the fit must say that model error dominates), and the model-error statement must flag model error
// wherever ε exceeds twice the noise floor; the fitted model must reproduce the recording's AVRF and OPMF (the
// paper's Sect. 3.2 metrics over several rocking cycles, beyond the fitting window). Skips where CMake did not find
// MuJoCo.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "build_type.hpp"
#include "fit_acceptance.hpp"
#include "mujoco_rocking.hpp"
#include "scratch_dir.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/recorded_fit.hpp"
#include "rockfit/fitting/release_tilt_check.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/synth_recording.hpp"
#include "rockfit/io/trial_metrics.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::fitting {
namespace {

#ifdef ROCKFIT_HAVE_MUJOCO

// A rolled release fitted with its roll: ε within this many noise floors (without the roll 12–33 in the study,
// with it, started from the data's roll, 3.2–6.0 (quartiles), 7.0 at the 90th percentile; MuJoCo's stiff contact
// alone, released in the plane, gives 1.2) …
constexpr double kRolledEpsilonOverNoiseFloor = 9.0;
// … and the roll found to within this [rad] (a fifth of the studies' largest roll).
constexpr double kRollTolerance_rad = 0.002;
// α's 95 % interval holds the truth in 91 % of the study's rolled fits, so one of these two trials may narrowly
// miss it: each α must lie within this many of its interval's half-widths (on the truth's side), and at least one
// interval must hold it. A release fitted without its roll is off by tens of such half-widths.
constexpr double kAlphaHalfWidths = 2.0;

// A slightly pushed release near θc: the fit's t0 and α within these of the release (the study's fit: 0.7 ms and
// 1.5 mrad; the hovering start it used to end at: 1.01 s and 12 mrad).
constexpr double kNearCriticalT0Tolerance_s = 0.01;
constexpr double kNearCriticalAlphaTolerance_rad = 0.005;

struct MujocoFit {
  testing::MujocoRockingTrial trial;
  FitSummary summary;
};

// fit_release_roll: the release roll β is a fit parameter (`rockfit fit --fit-release-roll`); otherwise it is held
// at 0 (`--release-roll-mode off`: these tests are of the model released on the edge).
MujocoFit FitMujocoTrial(const testing::MujocoRockingOptions& o, bool fit_release_roll = false) {
  MujocoFit f{testing::MakeMujocoRockingTrial(o), {}};
  ParameterSet parameters = ParameterSet::Defaults();
  parameters[ParameterId::kReleaseRoll].fixed = !fit_release_roll;
  TrialProblemOptions problem_options;
  problem_options.release_roll.mode = ReleaseRollMode::kOff;
  const TrialProblem p = PrepareTrialProblem(f.trial.signal, f.trial.block, parameters, problem_options);
  FitOptions options;
  options.intervals.method = IntervalMethod::kThorough;  // the command line's default
  options.num_threads = 1;
  f.summary = Fit(p.objective, p.start, options);
  return f;
}

bool Holds(const Interval& i, double value) { return testing::IntervalHolds(i, value); }

void ExpectTruthWithinIntervalsAndModelErrorFlagged(const MujocoFit& f) {
  const FitSummary& s = f.summary;
  ASSERT_TRUE(s.feasible);
  EXPECT_TRUE(Holds(s.uncertainty.interval_95[static_cast<std::size_t>(ParameterId::kT0)], f.trial.t0_s)) << s.FullReport();
  EXPECT_TRUE(Holds(s.uncertainty.interval_95[static_cast<std::size_t>(ParameterId::kAlpha)], f.trial.alpha_rad))
      << s.FullReport();
  ASSERT_TRUE(s.model_error.available);
  if (s.model_error.ratio > 2.0) {
    EXPECT_TRUE(s.model_error.dominates);
    EXPECT_TRUE(s.HasWarning(WarningKind::kModelErrorDominates));
  }
}

TEST(MujocoTrial, PlanarReleaseOnMujocosStiffContactHasTheTruthInTheIntervals) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  testing::MujocoRockingOptions o;
  o.alpha_rad = 0.2;
  o.roll_rad = 0.0;
  o.measurement.seed = 3;
  const MujocoFit f = FitMujocoTrial(o);
  EXPECT_GT(f.trial.impacts, 2);  // the premise: MuJoCo's block rocked and landed several times
  ExpectTruthWithinIntervalsAndModelErrorFlagged(f);
}

TEST(MujocoTrial, PerturbedBodyWithItsCentreOfMassOffTheAxisAndAProudCorner) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  testing::MujocoRockingOptions o;
  o.alpha_rad = 0.2;
  o.roll_rad = 0.0;
  o.com_offset_B_m = Eigen::Vector3d(0.0, 0.015 * o.b2_m, 0.0);  // 1.5 % of b off the axis
  o.proud_vertex = 3;                                             // V3 stands 0.1 mm proud
  o.measurement.seed = 4;
  const MujocoFit f = FitMujocoTrial(o);
  ExpectTruthWithinIntervalsAndModelErrorFlagged(f);
  EXPECT_GT(f.summary.model_error.ratio, 2.0);
}

// A release of the box at α with a roll about x (0: planar), measured with seed 5.
testing::MujocoRockingOptions ReleaseOptions(double roll_rad, double alpha_rad = 0.18) {
  testing::MujocoRockingOptions o;
  o.alpha_rad = alpha_rad;
  o.roll_rad = roll_rad;
  o.measurement.seed = 5;
  return o;
}

TEST(MujocoTrial, ReleaseWithARollIsFlaggedWhereTheIntervalsMissTheTruth) {
  // With a roll the block stands on one corner of its release edge, drops onto the edge and rocks about x through
  // the whole fall (±0.3 rad/s at 0.01 rad), which the model — released at rest on the edge — cannot make. The
  // fit's t0 and α can then be biased beyond their intervals (fitting/README.md, "Recordings made by other
  // physics"); what must hold is that the fit says so.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  for (double roll : {0.001, 0.01}) {
    const testing::MujocoRockingOptions o = ReleaseOptions(roll, 0.19);
    const MujocoFit f = FitMujocoTrial(o);
    const FitSummary& s = f.summary;
    ASSERT_TRUE(s.model_error.available);
    EXPECT_GT(s.model_error.ratio, 2.0) << "roll " << roll;  // the premise: the roll is model error
    EXPECT_TRUE(s.model_error.dominates) << "roll " << roll;
    EXPECT_TRUE(s.HasWarning(WarningKind::kModelErrorDominates)) << "roll " << roll;
    const bool holds = Holds(s.uncertainty.interval_95[static_cast<std::size_t>(ParameterId::kT0)], f.trial.t0_s) &&
                       Holds(s.uncertainty.interval_95[static_cast<std::size_t>(ParameterId::kAlpha)], f.trial.alpha_rad);
    EXPECT_TRUE(holds || s.model_error.dominates) << "roll " << roll;
  }
}

TEST(MujocoTrial, ARolledReleaseFittedWithItsRollHasTheTruthInTheIntervalsAndLessModelError) {
  // The same releases as above with the release roll fitted: the model can now stand the block on the corner
  // MuJoCo stood it on. t0 holds the truth, α comes close to it, the roll is found, and ε comes down towards the noise floor
  // (here from 7.4 and 24 noise floors for rolls of 0.001 and 0.01 rad); it does not reach it: the rest is
  // MuJoCo's soft corner and edge contact, which is not the paper's impact map.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  int alpha_held = 0;
  for (double roll : {0.001, 0.01}) {
    const testing::MujocoRockingOptions o = ReleaseOptions(roll, 0.19);
    const MujocoFit with_roll = FitMujocoTrial(o, true);
    const MujocoFit without_roll = FitMujocoTrial(o, false);
    const FitSummary& s = with_roll.summary;
    ASSERT_TRUE(s.feasible);
    ASSERT_TRUE(s.model_error.available && without_roll.summary.model_error.available);
    EXPECT_LT(s.model_error.ratio, without_roll.summary.model_error.ratio) << "roll " << roll << "\n" << s.FullReport();
    EXPECT_LT(s.model_error.ratio, kRolledEpsilonOverNoiseFloor) << "roll " << roll;
    EXPECT_TRUE(Holds(s.uncertainty.interval_95[static_cast<std::size_t>(ParameterId::kT0)], with_roll.trial.t0_s))
        << "roll " << roll << "\n" << s.FullReport();
    const auto& alpha_95 = s.uncertainty.interval_95[static_cast<std::size_t>(ParameterId::kAlpha)];
    const double alpha_rad = s.parameters.value(ParameterId::kAlpha);
    const double true_alpha_rad = with_roll.trial.alpha_rad;
    const double half_width_rad = true_alpha_rad < alpha_rad ? alpha_rad - alpha_95[0] : alpha_95[1] - alpha_rad;
    EXPECT_LT(std::abs(alpha_rad - true_alpha_rad), kAlphaHalfWidths * half_width_rad)
        << "roll " << roll << ", true alpha " << true_alpha_rad << "\n" << s.FullReport();
    if (Holds(alpha_95, true_alpha_rad)) ++alpha_held;
    EXPECT_NEAR(s.parameters.value(ParameterId::kReleaseRoll), roll, kRollTolerance_rad) << "roll " << roll;
  }
  EXPECT_GE(alpha_held, 1);
}

TEST(MujocoTrial, TheRollIsTurnedOnForRolledReleasesAndLeftOffForAPlanarOne) {
  // The default choice (release_roll_choice.hpp) on MuJoCo's recordings: a release rolled by 1 or 10 mrad shows
  // its roll in the fall and is fitted with it, started near the roll; a release on the edge is not.
  for (double roll : {0.0, 0.001, 0.01}) {
    const testing::MujocoRockingTrial trial = testing::MakeMujocoRockingTrial(ReleaseOptions(roll, 0.19));
    const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
    ASSERT_TRUE(p.release_roll.judged) << "roll " << roll;
    EXPECT_EQ(p.release_roll.fitted, roll != 0.0) << "roll " << roll << ": " << p.release_roll.reason;
    EXPECT_EQ(p.start[ParameterId::kReleaseRoll].fixed, roll == 0.0) << "roll " << roll;
    // Started within a third of the roll (the gyro's sum up to the other corner's soft landing).
    EXPECT_NEAR(p.start.value(ParameterId::kReleaseRoll), roll, roll / 3.0) << "roll " << roll;
  }
}

// The AVRF and OPMF targets of the other-physics study (tools/other_physics_study.py --metrics).
constexpr double kAvrfRelativeTolerance = 0.02;  // the fitted model's AVRF within 2 % of the recording's
constexpr double kOpmfTolerance = 0.003;         // the fitted model's OPMF within 0.003 of the recording's

// A recording of the gyro alone (sensor axes = block axes): the metrics integrate the attitude from it, the
// same way for MuJoCo's recording and the model's.
io::Recording GyroRecording(const io::DeviceSamples& device) {
  io::Recording r;
  r.format = "ximu-gui";
  r.rate_hz = device.rate_hz;
  for (std::size_t n = 0; n < device.size(); ++n) {
    r.t_s.push_back(static_cast<double>(n) / device.rate_hz);
    r.w_B.push_back(device.gyro_dps[n].cast<double>() * (M_PI / 180.0));
  }
  return r;
}

struct Metrics {
  io::MetricsSummary recorded, fitted;
};

// The metrics of MuJoCo's recording and of the model's: made by `synth`'s simulator and measurement model with
// the fitted parameters and the same seed.
Metrics RecordedAndFitted(const MujocoFit& f, const testing::MujocoRockingOptions& o) {
  io::SynthRecordingOptions so;
  so.t0_s = f.summary.parameters.value(ParameterId::kT0);
  so.duration_s = o.duration_s;
  so.measurement.seed = o.measurement.seed;
  so.files.rotation_matrix_file = false;
  const io::SynthRecording model = io::Synthesize(f.trial.block, f.summary.parameters.ToModel(), so);
  return {io::ComputeTrialMetrics(GyroRecording(f.trial.device), f.trial.block, {}),
          io::ComputeTrialMetrics(GyroRecording(model.device), f.trial.block, {})};
}

// The release of the two metrics tests: α = 0.18 rad, measurement seed 5, and a roll about x [rad].
TEST(MujocoTrial, TheFittedModelReproducesTheAvrfAndOpmfOfAPlanarRelease) {
  // MuJoCo's box rocks for several cycles after the release (peaks of |φ_y| up to 0.13 rad); the fit sees only
  // the window up to the first return impact, so the AVRF over the later cycles is a prediction.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const testing::MujocoRockingOptions o = ReleaseOptions(0.0);
  const MujocoFit f = FitMujocoTrial(o);
  ASSERT_TRUE(f.summary.feasible);
  const Metrics m = RecordedAndFitted(f, o);
  ASSERT_TRUE(m.recorded.ok()) << m.recorded.message;  // the premise: the box rocks for several cycles
  ASSERT_TRUE(m.fitted.ok()) << m.fitted.message;
  EXPECT_GE(m.recorded.avrf.ratios.size(), 3u);
  EXPECT_NEAR(m.fitted.avrf.avrf / m.recorded.avrf.avrf, 1.0, kAvrfRelativeTolerance)
      << "AVRF " << m.recorded.avrf.avrf << " recorded, " << m.fitted.avrf.avrf << " fitted";
  EXPECT_NEAR(m.fitted.opmf.opmf, m.recorded.opmf.opmf, kOpmfTolerance)
      << "OPMF " << m.recorded.opmf.opmf << " recorded, " << m.fitted.opmf.opmf << " fitted";
}

TEST(MujocoTrial, WhereTheFittedModelMissesTheAvrfModelErrorIsFlagged) {
  // A roll at release is model error (the release is not the model's): the fit is biased, and the AVRF of the
  // fitted model can miss the recording's (0.815 against 0.910 here). What must hold is that the fit says so.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const testing::MujocoRockingOptions o = ReleaseOptions(0.002);
  const MujocoFit f = FitMujocoTrial(o);
  ASSERT_TRUE(f.summary.feasible);
  const Metrics m = RecordedAndFitted(f, o);
  ASSERT_TRUE(m.recorded.ok() && m.fitted.ok());
  const bool reproduced = std::abs(m.fitted.avrf.avrf / m.recorded.avrf.avrf - 1.0) <= kAvrfRelativeTolerance &&
                          std::abs(m.fitted.opmf.opmf - m.recorded.opmf.opmf) <= kOpmfTolerance;
  EXPECT_TRUE(reproduced || f.summary.model_error.dominates) << f.summary.FullReport();
  if (f.summary.model_error.ratio > 2.0) {
    EXPECT_TRUE(f.summary.model_error.dominates);
  }
}

// The trial as `rockfit fit` reads it: written as an x-IMU file set and loaded, so that the tilt at rest comes from
// the recording's accelerometer through the mounting estimate; fitted with the program's defaults (the release roll
// chosen from the fall) and checked against that tilt.
struct WrittenMujocoFit {
  FitSummary summary;
  io::MountingCheck mounting;
};

WrittenMujocoFit FitWrittenMujocoTrial(const testing::MujocoRockingOptions& o) {
  const testing::MujocoRockingTrial trial = testing::MakeMujocoRockingTrial(o);
  const testing::ScratchDir dir("mujoco_push");
  const std::string prefix = (dir / "trial").string();
  testing::WriteMujocoRockingTrial(prefix, o, trial);
  const io::Recording recording = io::LoadRecording(prefix);
  const MeasuredSignal signal{recording.t_s, recording.w_B, {}, {}};
  const TrialProblem p = PrepareTrialProblem(signal, trial.block, ParameterSet::Defaults());
  FitOptions options;
  options.intervals.method = IntervalMethod::kFast;  // the check needs α's standard error only
  options.num_threads = 1;
  return {FitRecordedTrial(p.objective, p.start, options, p.release_roll, &recording),
          recording.mounting_check};
}

TEST(MujocoTrial, APushAtTheReleaseIsCaughtByTheTiltAtRestAndAReleaseFromRestIsNot) {
  // The check of α against the tilt at rest (release_tilt_check.hpp) on MuJoCo's releases at α = 0.19 rad,
  // recorded until the box stands still (6 s):
  //  * rolled by 0.01 rad and released from rest: the fitted α agrees with the tilt at rest;
  //  * the same, pushed towards the fall at 0.1 rad/s about the edge: the fit explains the push with the release
  //    tilt and the roll, 23 mrad below the tilt at rest, against 1.7 mrad of the two standard errors together;
  //  * planar, pushed away from the fall at 0.2 rad/s: the box rises by 0.6°, stops at the top and falls from
  //    there, which the model fits as a release from rest at the top (ε below the noise floor) 14 mrad above the
  //    tilt at rest. Its rest ends before the lift: the mounting estimate finds it past the stop and says how far
  //    the box turned (io/README.md, "Mounting estimate").
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  struct Case {
    double roll_rad, push_rad_s;
  };
  for (const Case c : {Case{0.01, 0.0}, Case{0.01, 0.1}, Case{0.0, -0.2}}) {
    testing::MujocoRockingOptions o = ReleaseOptions(c.roll_rad, 0.19);
    o.duration_s = 6.0;
    o.push_w_y_rad_s = c.push_rad_s;
    const WrittenMujocoFit f = FitWrittenMujocoTrial(o);
    const FitSummary& s = f.summary;
    const std::string label = fmt::format("roll {} rad, push {} rad/s", c.roll_rad, c.push_rad_s);
    ASSERT_TRUE(s.feasible) << label;
    ASSERT_TRUE(s.release_tilt.has_value());
    const ReleaseTiltCheck& check = *s.release_tilt;
    ASSERT_TRUE(check.available) << label << ": " << check.reason;
    EXPECT_NEAR(check.rest_rad, o.alpha_rad, 4.0 * check.rest_std_error_rad) << label;
    if (c.push_rad_s == 0.0) {
      EXPECT_TRUE(check.consistent) << check.reason;
      EXPECT_FALSE(s.HasWarning(WarningKind::kReleaseTiltDisagrees));
    } else {
      EXPECT_FALSE(check.consistent) << label << ": " << check.reason;
      EXPECT_TRUE(s.HasWarning(WarningKind::kReleaseTiltDisagrees)) << label;
    }
    if (c.push_rad_s < 0.0) {
      EXPECT_GT(check.difference_rad, 0.0) << label << ": the fall starts above the tilt at rest";
      EXPECT_THAT(f.mounting.message, ::testing::HasSubstr("turned by")) << label;
      // The check carries the lift and says that α is the tilt the box fell from; the lift is what moved α.
      EXPECT_EQ(check.turn_before_fall_deg, f.mounting.turn_before_fall_deg);
      EXPECT_GT(check.turn_before_fall_deg, 0.0);
      EXPECT_THAT(check.reason, ::testing::HasSubstr("the fitted α is the tilt it fell from")) << label;
      const double turn_rad = check.turn_before_fall_deg * io::kRadPerDeg;
      EXPECT_GT(check.difference_rad, 0.5 * turn_rad) << check.reason;
      EXPECT_LT(check.difference_rad, 2.0 * turn_rad) << check.reason;
      EXPECT_TRUE(s.HasWarning(WarningKind::kTurnedBeforeFall)) << label;
    } else {
      EXPECT_EQ(check.turn_before_fall_deg, 0.0) << label << ": " << check.reason;
      EXPECT_FALSE(s.HasWarning(WarningKind::kTurnedBeforeFall)) << label;
    }
  }
}

// A trial of the pushed MuJoCo study (`other_physics_study.py --family mujoco --push 0.3 --duration 6 --seed 71`),
// remade from its drawn values.
testing::MujocoRockingOptions StudyTrial(double alpha_rad, double roll_rad, double t0_s, double b2_m, double push_rad_s,
                                         std::uint64_t seed) {
  testing::MujocoRockingOptions o;
  o.alpha_rad = alpha_rad;
  o.roll_rad = roll_rad;
  o.t0_s = t0_s;
  o.b2_m = b2_m;
  o.push_w_y_rad_s = push_rad_s;
  o.duration_s = 6.0;
  o.measurement.seed = seed;
  return o;
}

struct SignalFit {
  std::vector<std::string> notes;  // the problem's (estimate, gyro bias)
  FitSummary summary;
};

// The trial's recorded signal fitted directly (not through the files), without intervals, on one thread.
SignalFit FitSignalWithoutIntervals(const testing::MujocoRockingOptions& o) {
  const testing::MujocoRockingTrial trial = testing::MakeMujocoRockingTrial(o);
  const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  FitOptions options;
  options.intervals.method = IntervalMethod::kNone;
  options.num_threads = 1;
  return {p.notes, Fit(p.objective, p.start, options)};
}

// What the motion before the fitted release says of a fit of trial `o`: pushed (push_w_y_rad_s ≠ 0), t0 late by more
// than 20 ms and the recording turning before it by at most the push's rate times the part of the lookback after the
// push, warned; released from rest, t0 within 5 ms and a turn of a tenth of the warning's at most, not warned.
void ExpectMotionBeforeReleaseShowsThePush(const testing::MujocoRockingOptions& o, const FitSummary& s) {
  const MotionBeforeRelease& m = s.motion_before_release;
  ASSERT_TRUE(m.available);
  const double late_s = s.parameters.value(ParameterId::kT0) - o.t0_s;
  if (o.push_w_y_rad_s != 0.0) {
    EXPECT_GT(late_s, 0.02) << s.FullReport();
    EXPECT_TRUE(m.moving) << MotionBeforeReleaseText(m);
    EXPECT_TRUE(s.HasWarning(WarningKind::kMovingAtRelease));
    EXPECT_LE(m.turn_deg * io::kRadPerDeg, std::abs(o.push_w_y_rad_s) * std::min(late_s, m.lookback_s))
        << MotionBeforeReleaseText(m);
  } else {
    EXPECT_LT(std::abs(late_s), 0.005) << s.FullReport();
    EXPECT_FALSE(m.moving) << MotionBeforeReleaseText(m);
    EXPECT_FALSE(s.HasWarning(WarningKind::kMovingAtRelease));
    EXPECT_LT(m.turn_deg, 0.1 * MotionBeforeReleaseOptions{}.warn_turn_deg) << MotionBeforeReleaseText(m);
  }
}

TEST(MujocoTrial, ANearlyCriticalReleasePushedSlightlyIsFittedInItsBasinNotAtAHoveringStart) {
  // α = 0.95 θc, rolled by 2 mrad and pushed towards the fall at 0.01 rad/s (trial 1 of the pushed MuJoCo study,
  // seed 71). A model block just below θc hovers as long as asked, and (28) is a mean over [t0, t_end]: on the
  // global stage's first short windows a start with t0 far too early gains by the recorded rest it adds, and the
  // stop rule of the continuation used to drop every start in the release's basin against it (the fit ended at
  // α = θc, t0 = 0, ε 2.6 times this one's). The rule now compares the tracks also by their error summed over the
  // window, which the added rest does not lower (global_stage.cpp, PruneTracks).
  const testing::MujocoRockingOptions o = StudyTrial(0.23264191328489417, 0.001994886510985525, 1.01064453125,
                                                     0.05377554771664128, 0.010280897436384884, 1001);
  const FitSummary s = FitSignalWithoutIntervals(o).summary;
  ASSERT_TRUE(s.feasible);
  EXPECT_NEAR(s.parameters.value(ParameterId::kT0), o.t0_s, kNearCriticalT0Tolerance_s) << s.FullReport();
  EXPECT_NEAR(s.parameters.value(ParameterId::kAlpha), o.alpha_rad, kNearCriticalAlphaTolerance_rad) << s.FullReport();
}

TEST(MujocoTrial, APushWithoutAStopAtTheTopIsCaughtByTheMotionBeforeTheFittedRelease) {
  // Trial 89 of the pushed MuJoCo study (seed 71): a rolled box pushed away from the fall at 0.21 rad/s that
  // never stops at the top. The fit releases it from rest tens of milliseconds after the push, with ε near the
  // noise floor, and the tilt at rest cannot tell (no stop, so no turn before the fall). The recording turns
  // before that t0 while the model is at rest (motion_before_release.hpp). The same box released from rest at
  // the push's time turns by noise alone before its fitted t0. The gyro's rest ends before the push, not 50 ms
  // before the late estimate of the release (rest_noise.hpp): the noise floor is the sensor's, as without the push,
  // and the push's model error is flagged (with the push in the rest: 1.1 noise floors, not flagged).
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  std::vector<double> noise_floors_rad_s;
  for (const double push_rad_s : {-0.2117412670537667, 0.0}) {
    const testing::MujocoRockingOptions o = StudyTrial(0.16417122782068572, 0.0015203053278883961, 0.94541015625,
                                                       0.053658038885871506, push_rad_s, 1089);
    const SignalFit f = FitSignalWithoutIntervals(o);
    const FitSummary& s = f.summary;
    ASSERT_TRUE(s.feasible);
    ASSERT_TRUE(s.model_error.available);
    noise_floors_rad_s.push_back(s.model_error.noise_floor_rad_s);
    ExpectMotionBeforeReleaseShowsThePush(o, s);
    if (push_rad_s != 0.0) {
      EXPECT_TRUE(s.model_error.dominates) << ModelErrorText(s.model_error);
      EXPECT_THAT(f.notes, ::testing::Contains(::testing::HasSubstr("the recording already moves there")));
    }
  }
  EXPECT_NEAR(noise_floors_rad_s[0], noise_floors_rad_s[1], 0.1 * noise_floors_rad_s[1]);
}

TEST(MujocoTrial, APushedPerturbedBodyIsWarnedAboutThePushWhereModelErrorIsFlaggedWithoutIt) {
  // Trial 10 of the pushed study of perturbed bodies (`--family mujoco-perturbed --push 0.3 --seed 71`, a family held
  // out of every threshold): the centre of mass 1.26 % of b2 off the axis and base corner V3 0.1 mm proud, rolled by
  // 4.3 mrad and pushed away from the fall at 0.157 rad/s. The perturbation alone makes model error dominant, so ε
  // flags the fit released from rest as much as the pushed one and says nothing about the push. The motion before
  // the fitted release does: the pushed fit's t0 is late and the recording turns before it; released from rest, the
  // same body's fit turns by noise alone before its t0.
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  for (const double push_rad_s : {-0.1567781807533725, 0.0}) {
    testing::MujocoRockingOptions o = StudyTrial(0.1710708837378014, 0.004252793257328876, 1.4576171875,
                                                 0.05979201992522172, push_rad_s, 1010);
    o.com_offset_B_m.y() = 0.01258725258050539 * o.b2_m;
    o.proud_vertex = 3;
    const FitSummary s = FitSignalWithoutIntervals(o).summary;
    ASSERT_TRUE(s.feasible);
    ASSERT_TRUE(s.model_error.available);
    EXPECT_TRUE(s.model_error.dominates) << ModelErrorText(s.model_error);
    ExpectMotionBeforeReleaseShowsThePush(o, s);
  }
}

#else

TEST(MujocoTrial, SkippedWithoutMujoco) { GTEST_SKIP() << "MuJoCo (libmujoco-dev) was not found by CMake"; }

#endif

}  // namespace
}  // namespace rockfit::fitting
