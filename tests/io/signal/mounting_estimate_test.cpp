// The mounting estimate on hand-made recordings with a known misalignment (cheap, every build): rest at the
// release tilt, phase 1 about the block's y axis, rocking, rest flat — seen through a sensor turned by R_BBg⁻¹.
// The sweep over synthetic `rockfit synth` trials is in mounting_sweep_test.cpp.
#include "rockfit/io/mounting_estimate.hpp"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kPi = 3.14159265358979323846;
constexpr double kRate_hz = 256.0;
constexpr double kG = 9.81;
// Noise like the x-IMU's: gyro 0.1 °/s, accelerometer 0.015 g per sample.
constexpr double kGyroNoise_rad_s = 0.1 * kRadPerDeg;
constexpr double kAccelNoise_m_s2 = 0.015 * kG;
// The estimate from ~1 s of rest and ~100 phase-1 samples is good to a few hundredths of a degree; 0.1° leaves
// room for the 0.02° floor per clue and the noise.
constexpr double kAngleTolerance_deg = 0.1;
// α comes from two rests of 1 s, each direction good to 0.015 g / √256 ≈ 0.054°: σ_α ≈ 0.08°, 3σ.
constexpr double kTiltTolerance_deg = 0.25;

Eigen::Matrix3d RotationFromDeg(const Eigen::Vector3d& angles_deg) {
  const double angle = angles_deg.norm() * kRadPerDeg;
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, angles_deg.normalized()).toRotationMatrix();
}

struct HandMadeTrial {
  double alpha_rad = 0.2;
  double rest_before_s = 1.0;
  double rest_after_s = 1.0;
  bool lateral = true;  // ω_x after the first impact
  double lift_rad = 0.0;       // lifted by this much about y after the rest, stopped for a moment, then the fall
  double flat_before_s = 0.0;  // standing flat this long before being tilted into place (0.3 s) for the rest
  // Released on one corner of its release edge, rolled by this much about x: it leans sideways at rest, its fall's
  // axis is turned by −roll_rad/sin α about z (ω_x in proportion to ω_y), and the roll runs out during the fall (a bump
  // of ω_x that integrates to −roll_rad), as `rockfit synth --release-roll` and MuJoCo's rolled releases show.
  double roll_rad = 0.0;
  bool overturned = false;  // at rest after the rocking on a side face
  // Pushed past its critical tilt: it falls over its release edge (ω_y < 0) onto a side, turning by π/2 − α before
  // its first impact, and comes to rest there without rocking.
  bool over_release_edge = false;
  Eigen::Vector3d bias_rad_s = Eigen::Vector3d(0.004, -0.003, 0.002);
};

// The recording in the axes of a given mounting that is off by R_BBg (block axes from given axes).
Recording MakeRecording(const HandMadeTrial& t, const Eigen::Matrix3d& R_BBg, std::uint32_t seed = 5) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto noise = [&](double sigma) {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = sigma * normal(rng);
    return v;
  };
  const Eigen::Matrix3d R_BgB = R_BBg.transpose();
  Recording r;
  r.format = "generic-csv";
  r.rate_hz = kRate_hz;
  const auto push = [&](const Eigen::Vector3d& w_B, const Eigen::Vector3d& f_B) {
    r.t_s.push_back(static_cast<double>(r.t_s.size()) / kRate_hz);
    r.w_B.push_back(R_BgB * w_B + t.bias_rad_s + noise(kGyroNoise_rad_s));
    r.accel_B.push_back(R_BgB * f_B + noise(kAccelNoise_m_s2));
  };
  const Eigen::Vector3d tilted(std::sin(t.alpha_rad) * std::cos(t.roll_rad), -std::sin(t.roll_rad),
                               std::cos(t.alpha_rad) * std::cos(t.roll_rad));
  for (int k = 0; k < static_cast<int>(t.flat_before_s * kRate_hz); ++k) {
    push(Eigen::Vector3d::Zero(), kG * Eigen::Vector3d::UnitZ());
  }
  if (t.flat_before_s > 0.0) {
    const int tilting = static_cast<int>(0.3 * kRate_hz);  // φy from 0 to −α at a constant rate
    for (int k = 0; k < tilting; ++k) {
      const double angle = t.alpha_rad * (k + 0.5) / tilting;
      push(Eigen::Vector3d(0.0, -t.alpha_rad / 0.3, 0.0), kG * Eigen::Vector3d(std::sin(angle), 0.0, std::cos(angle)));
    }
  }
  for (int k = 0; k < static_cast<int>(t.rest_before_s * kRate_hz); ++k) push(Eigen::Vector3d::Zero(), kG * tilted);
  if (t.lift_rad > 0.0) {
    // Lifted away from the fall (ω_y < 0) with a rate falling linearly to zero in 0.15 s, so that it turns by
    // lift_rad; the block stops at the top (a few samples below the rest threshold) and the fall starts there.
    const int lift = static_cast<int>(0.15 * kRate_hz);
    for (int k = 0; k < lift; ++k) {
      const double s = (k + 0.5) / lift;
      const double angle = t.alpha_rad + t.lift_rad * s * (2.0 - s);
      push(Eigen::Vector3d(0.0, -2.0 * t.lift_rad / 0.15 * (1.0 - s), 0.0),
           kG * Eigen::Vector3d(std::sin(angle), 0.0, std::cos(angle)));
    }
  }
  if (t.over_release_edge) {
    // 0.5 s about −y, ω growing as s² so that it integrates to π/2 − α, then at rest on the side face (+x down).
    const int over = static_cast<int>(0.5 * kRate_hz);
    const double peak_rad_s = 3.0 * (kPi / 2.0 - t.alpha_rad) / 0.5;
    for (int k = 1; k <= over; ++k) {
      const double s = static_cast<double>(k) / over;
      push(Eigen::Vector3d(0.0, -peak_rad_s * s * s, 0.0), kG * tilted);
    }
    for (int k = 0; k < static_cast<int>(t.rest_after_s * kRate_hz); ++k) {
      push(Eigen::Vector3d::Zero(), -kG * Eigen::Vector3d::UnitX());
    }
    return r;
  }
  // Phase 1: 0.4 s about y, ω growing to 1.4 rad/s (the specific force is not used there).
  const int fall = static_cast<int>(0.4 * kRate_hz);
  for (int k = 1; k <= fall; ++k) {
    const double s = static_cast<double>(k) / fall;
    const double w_y = 1.4 * s * s;
    const double w_x = -std::tan(t.roll_rad / std::sin(t.alpha_rad)) * w_y - t.roll_rad * 6.0 * s * (1.0 - s) / 0.4;
    push(Eigen::Vector3d(w_x, w_y, 0.0), kG * tilted);
  }
  // Rocking: decaying oscillations about y, and about x when lateral, for 1.5 s.
  const int rocking = static_cast<int>(1.5 * kRate_hz);
  for (int k = 0; k < rocking; ++k) {
    const double time = static_cast<double>(k) / kRate_hz;
    const double envelope = 0.3 + 0.7 * std::exp(-time / 0.3);  // still rocking when the recording ends
    const Eigen::Vector3d w(t.lateral ? 0.4 * envelope * std::sin(2 * kPi * 3.0 * time) : 0.0,
                            envelope * std::cos(2 * kPi * 4.0 * time), 0.0);
    push(w, kG * Eigen::Vector3d::UnitZ());
  }
  // At rest after the rocking: on its base, or on its side face (+y up) when it overturned.
  const Eigen::Vector3d up_after = t.overturned ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
  for (int k = 0; k < static_cast<int>(t.rest_after_s * kRate_hz); ++k) push(Eigen::Vector3d::Zero(), kG * up_after);
  return r;
}

TEST(MountingEstimate, RecoversASmallRotationAboutEachAxisWithItsStandardError) {
  for (const Eigen::Vector3d& truth_deg :
       {Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, -2.5, 0), Eigen::Vector3d(1.2, -3, 2.2)}) {
    const MountingEstimate e = EstimateMounting(MakeRecording({}, RotationFromDeg(truth_deg)));
    ASSERT_EQ(e.check.status, MountingStatus::kOk) << e.check.message;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(e.check.angles_deg[i], truth_deg[i], kAngleTolerance_deg) << truth_deg.transpose();
      EXPECT_GT(e.check.std_error_deg[i], 0.0);
      EXPECT_LT(e.check.std_error_deg[i], kAngleTolerance_deg);
    }
    EXPECT_NEAR(e.check.release_tilt_rad, 0.2, kTiltTolerance_deg * kRadPerDeg);
    // The tilt's standard error: the tilt about y trades against the rotation about y, which only the rest after the
    // rocking fixes, so it is at least that angle's.
    EXPECT_GE(e.check.release_tilt_std_error_rad, 0.99 * e.check.std_error_deg[1] * kRadPerDeg);
    EXPECT_LT(e.check.release_tilt_std_error_rad, kTiltTolerance_deg * kRadPerDeg);
    EXPECT_GT(e.rest_before_samples, 200u);
    EXPECT_GT(e.phase1_samples, 50u);  // |ω| ≥ 0.2 of the landing rate: the last 55 % of the fall
    EXPECT_GT(e.rest_after_samples, 200u);
  }
}

TEST(MountingEstimate, AReleaseOnACornerIsNotTakenForASensorTurnedAboutZ) {
  // Rolled by 6 mrad on a corner: the lean at rest and the roll in the fall are, to the three clues, a sensor turned
  // by about −β/sin α about z. Read as a release about the edge (the rule switched off), that is what they say; the
  // estimate sees the roll in the fall instead, leaves phase 1 out and keeps z at the given mounting, so there is no
  // warning about an aligned sensor, and the angles about x and y of a turned one are still found.
  HandMadeTrial t;
  t.roll_rad = 0.006;
  MountingEstimateOptions edge_only;
  edge_only.phase1_across_to_noise = 1e9;
  const MountingEstimate read_as_edge = EstimateMounting(MakeRecording(t, Eigen::Matrix3d::Identity()), edge_only);
  EXPECT_GT(std::abs(read_as_edge.check.angles_deg.z()), 1.0) << read_as_edge.check.message;
  EXPECT_FALSE(MountingWarning(read_as_edge.check, Mounting()).empty());

  const MountingEstimate e = EstimateMounting(MakeRecording(t, Eigen::Matrix3d::Identity()));
  ASSERT_EQ(e.check.status, MountingStatus::kPartial) << e.check.message;
  EXPECT_TRUE(e.check.determined[0]);
  EXPECT_TRUE(e.check.determined[1]);
  EXPECT_FALSE(e.check.determined[2]);
  EXPECT_NEAR(e.check.angles_deg.z(), 0.0, kAngleTolerance_deg) << "kept at the given mounting";
  EXPECT_THAT(e.check.message, HasSubstr("about block z"));
  EXPECT_THAT(e.check.message, HasSubstr("fell rolling"));
  EXPECT_EQ(MountingWarning(e.check, Mounting()), "");
  EXPECT_NEAR(e.check.release_tilt_rad, t.alpha_rad, kTiltTolerance_deg * kRadPerDeg);

  const Eigen::Vector3d truth_deg(-1.0, 2.0, 0.0);
  const MountingEstimate turned = EstimateMounting(MakeRecording(t, RotationFromDeg(truth_deg)));
  ASSERT_EQ(turned.check.status, MountingStatus::kPartial) << turned.check.message;
  EXPECT_NEAR(turned.check.angles_deg.x(), truth_deg.x(), kAngleTolerance_deg);
  EXPECT_NEAR(turned.check.angles_deg.y(), truth_deg.y(), kAngleTolerance_deg);
}

TEST(MountingEstimate, ASensorTurnedAboutZOnAReleaseAboutTheEdgeIsStillFound) {
  // The rule's other side: a yawed sensor tilts the fall's axis but does not spread the rate about it.
  const Eigen::Vector3d truth_deg(0.0, 0.0, 3.0);
  const MountingEstimate e = EstimateMounting(MakeRecording(HandMadeTrial{}, RotationFromDeg(truth_deg)));
  ASSERT_EQ(e.check.status, MountingStatus::kOk) << e.check.message;
  EXPECT_NEAR(e.check.angles_deg.z(), truth_deg.z(), kAngleTolerance_deg);
  EXPECT_THAT(e.check.message, ::testing::Not(HasSubstr("fell rolling")));
}

TEST(MountingEstimate, ABlockThatOverturnedIsNotTakenForASensorOnAnotherFace) {
  // At rest on its side after the rocking, 90° from its rest before the release: that rest is no clue to the
  // mounting (read as one, it turned the estimate by tens of degrees). The angles about x and z come from the rest
  // before the release and phase 1; y is open, as without a rest after the rocking, and the message says why.
  HandMadeTrial t;
  t.overturned = true;
  t.lateral = false;
  const Eigen::Vector3d truth_deg(-1.0, 2.0, 4.0);
  const MountingEstimate e = EstimateMounting(MakeRecording(t, RotationFromDeg(truth_deg)));
  ASSERT_EQ(e.check.status, MountingStatus::kPartial) << e.check.message;
  EXPECT_FALSE(e.check.determined[1]);
  EXPECT_NEAR(e.check.angles_deg.x(), truth_deg.x(), kAngleTolerance_deg);
  EXPECT_NEAR(e.check.angles_deg.z(), truth_deg.z(), kAngleTolerance_deg);
  EXPECT_THAT(e.check.message, HasSubstr("did not come back to rest on its base"));
  EXPECT_EQ(e.rest_after_samples, 0u);
}

TEST(MountingEstimate, ABlockPushedOverItsReleaseEdgeIsNotTakenForASensorTurnedAboutZ) {
  // Its fall turns the other way and onto a side: read as a fall onto the base, it looked like a sensor turned by
  // about 180° about z (MuJoCo boxes pushed past θ_c: 178.7–179.0°, with the advice to turn the data by it). The fall
  // shows nothing of the mounting: no estimate, a status and a message, no warning.
  HandMadeTrial t;
  t.over_release_edge = true;
  const MountingEstimate e = EstimateMounting(MakeRecording(t, RotationFromDeg({-1.0, 2.0, 4.0})));
  EXPECT_EQ(e.check.status, MountingStatus::kNoRelease) << e.check.message;
  EXPECT_THAT(e.check.message, HasSubstr("fell over its release edge"));
  EXPECT_THAT(e.check.message, HasSubstr("turned by 78°"));  // π/2 − α = 78.5°, the samples before the impact
  EXPECT_TRUE(e.check.warning.empty()) << e.check.warning;
  // A fall onto the base read through a sensor turned by 180° about z is a turned sensor, still found.
  HandMadeTrial onto_base;
  const Eigen::Matrix3d turned_about_z = RotationFromDeg(Eigen::Vector3d(1.0, -0.5, 177.0));
  const MountingEstimate turned = EstimateMounting(MakeRecording(onto_base, turned_about_z));
  ASSERT_EQ(turned.check.status, MountingStatus::kOk) << turned.check.message;
  EXPECT_LT(Eigen::AngleAxisd(turned.R_BBg * turned_about_z.transpose()).angle() / kRadPerDeg, kAngleTolerance_deg);
}

TEST(MountingEstimate, TheGyroBiasAtRestDoesNotTiltThePhaseOneAxis) {
  HandMadeTrial t;
  t.bias_rad_s = Eigen::Vector3d(0.3, -0.25, 0.3) * kRadPerDeg;  // 0.3 °/s ≈ 0.2° of a 1.4 rad/s axis unremoved
  const MountingEstimate e = EstimateMounting(MakeRecording(t, Eigen::Matrix3d::Identity()));
  ASSERT_EQ(e.check.status, MountingStatus::kOk) << e.check.message;
  EXPECT_LT(e.check.angles_deg.norm(), kAngleTolerance_deg);
  EXPECT_LT((e.gyro_bias_rad_s - t.bias_rad_s).norm(), 1e-3);
}

TEST(MountingEstimate, AnUpsideDownSensorWithAMisalignmentIsFoundFromFarAway) {
  // Given identity, but the sensor is upside down (x,-y,-z) and turned by a few degrees: the start is 180° off.
  const Eigen::Matrix3d upside_down = Eigen::Vector3d(1, -1, -1).asDiagonal();
  const Eigen::Matrix3d small = RotationFromDeg(Eigen::Vector3d(-1.5, 2.0, 3.5));
  const Eigen::Matrix3d R_BBg = small * upside_down;
  const MountingEstimate e = EstimateMounting(MakeRecording({}, R_BBg));
  ASSERT_EQ(e.check.status, MountingStatus::kOk) << e.check.message;
  const double error_deg = Eigen::AngleAxisd(e.R_BBg * R_BBg.transpose()).angle() / kRadPerDeg;
  EXPECT_LT(error_deg, kAngleTolerance_deg);
  EXPECT_NEAR(MountingDisagreementDeg(e.check), Eigen::AngleAxisd(R_BBg).angle() / kRadPerDeg, kAngleTolerance_deg);
  // The corrected mounting is the true one: the permutation times the small rotation.
  const Mounting corrected = CorrectedMounting(Mounting(), e);
  EXPECT_LT(Eigen::AngleAxisd(corrected.R_BS() * R_BBg.transpose()).angle() / kRadPerDeg, kAngleTolerance_deg);
}

TEST(MountingEstimate, PlanarRockingWithRestAfterwardsFixesAllThreeAngles) {
  HandMadeTrial t;
  t.lateral = false;
  const Eigen::Vector3d truth_deg(-1.0, 2.0, 4.0);
  const MountingEstimate e = EstimateMounting(MakeRecording(t, RotationFromDeg(truth_deg)));
  ASSERT_EQ(e.check.status, MountingStatus::kOk) << e.check.message;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(e.check.angles_deg[i], truth_deg[i], kAngleTolerance_deg);
}

TEST(MountingEstimate, WithoutRestAfterTheRockingTheAngleAboutYIsOpenAndSaidSo) {
  HandMadeTrial t;
  t.lateral = false;
  t.rest_after_s = 0.0;
  const Eigen::Vector3d truth_deg(-1.0, 2.0, 4.0);
  const MountingEstimate e = EstimateMounting(MakeRecording(t, RotationFromDeg(truth_deg)));
  ASSERT_EQ(e.check.status, MountingStatus::kPartial);
  EXPECT_THAT(e.check.message, HasSubstr("about block y"));
  EXPECT_THAT(e.check.message, HasSubstr("does not end at rest"));
  EXPECT_TRUE(e.check.determined[0]);
  EXPECT_FALSE(e.check.determined[1]);
  EXPECT_TRUE(e.check.determined[2]);
  EXPECT_NEAR(e.check.angles_deg.x(), truth_deg.x(), kAngleTolerance_deg);
  EXPECT_NEAR(e.check.angles_deg.z(), truth_deg.z(), kAngleTolerance_deg);
  EXPECT_NEAR(e.check.angles_deg.y(), 0.0, kAngleTolerance_deg) << "kept at the given mounting";
  // The turn about y went into the tilt: the sensor turned by +2° about y reads α − 2°.
  EXPECT_NEAR(e.check.release_tilt_rad, 0.2 - 2.0 * kRadPerDeg, kTiltTolerance_deg * kRadPerDeg);
}

TEST(MountingEstimate, AShortLiftBeforeTheFallKeepsTheRestItWasHeldInAndSaysHowFar) {
  // The hand lifts the block by 0.6° as it lets go (a push away from the fall): the stop at the top is no rest,
  // the rest before the lift is, and its tilt is the one the block was held at, not the top of the lift.
  HandMadeTrial t;
  t.lift_rad = 0.6 * kRadPerDeg;
  const Eigen::Vector3d truth_deg(-1.0, 2.0, 4.0);
  const MountingEstimate e = EstimateMounting(MakeRecording(t, RotationFromDeg(truth_deg)));
  ASSERT_EQ(e.check.status, MountingStatus::kOk) << e.check.message;
  EXPECT_NEAR(e.check.release_tilt_rad, t.alpha_rad, kTiltTolerance_deg * kRadPerDeg);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(e.check.angles_deg[i], truth_deg[i], kAngleTolerance_deg);
  EXPECT_NEAR(e.check.turn_before_fall_deg, 0.6, 0.05);
  EXPECT_THAT(e.check.message, HasSubstr("turned by 0.6"));
  // Without the lift the rest ends where the fall begins and nothing is said about a turn.
  const MountingEstimate plain = EstimateMounting(MakeRecording(HandMadeTrial{}, RotationFromDeg(truth_deg)));
  EXPECT_EQ(plain.check.turn_before_fall_deg, 0.0);
  EXPECT_THAT(plain.check.message, Not(HasSubstr("turned by")));
  // With the rule off (0°) the lift leaves no rest before the fall.
  MountingEstimateOptions strict;
  strict.max_turn_before_fall_deg = 0.0;
  EXPECT_EQ(EstimateMounting(MakeRecording(t, RotationFromDeg(truth_deg)), strict).check.status,
            MountingStatus::kNoRest);
}

TEST(MountingEstimate, TheBlockStandingFlatBeforeItWasTiltedIntoPlaceIsNotTakenForTheRest) {
  // Tilted by hand from flat to α and let go after 0.1 s: too short a rest, and the flat stand before the tilting
  // (a turn of α = 11°) is not the release tilt: no rest, as before.
  HandMadeTrial t;
  t.flat_before_s = 1.0;
  t.rest_before_s = 0.1;
  const MountingEstimate e = EstimateMounting(MakeRecording(t, Eigen::Matrix3d::Identity()));
  EXPECT_EQ(e.check.status, MountingStatus::kNoRest) << e.check.message;
  // The bound on the turn is what keeps it out: above the tilting (20°) the flat stand is taken for the rest.
  MountingEstimateOptions loose;
  loose.max_turn_before_fall_deg = 20.0;
  const MountingEstimate wrong = EstimateMounting(MakeRecording(t, Eigen::Matrix3d::Identity()), loose);
  EXPECT_NE(wrong.check.status, MountingStatus::kNoRest);
  EXPECT_GT(wrong.check.turn_before_fall_deg, 10.0);
}

TEST(MountingEstimate, RecordingsItCannotUseGetAStatusNotAnException) {
  Recording no_accel = MakeRecording({}, Eigen::Matrix3d::Identity());
  no_accel.accel_B.clear();
  EXPECT_EQ(EstimateMounting(no_accel).check.status, MountingStatus::kNoAccelerometer);

  Recording still = MakeRecording({}, Eigen::Matrix3d::Identity());
  for (Eigen::Vector3d& w : still.w_B) w = Eigen::Vector3d(0.001, 0.0, 0.0);
  const MountingEstimate e = EstimateMounting(still);
  EXPECT_EQ(e.check.status, MountingStatus::kNoRelease);
  EXPECT_FALSE(e.check.has_estimate());
  EXPECT_TRUE(std::isnan(MountingDisagreementDeg(e.check)));

  HandMadeTrial short_rest;
  short_rest.rest_before_s = 0.1;
  EXPECT_EQ(EstimateMounting(MakeRecording(short_rest, Eigen::Matrix3d::Identity())).check.status, MountingStatus::kNoRest);
}

TEST(MountingEstimate, TheWarningSaysByHowMuchAndHowToFixIt) {
  const Eigen::Vector3d truth_deg(0.0, 0.0, 3.0);
  MountingEstimate e = EstimateMounting(MakeRecording({}, RotationFromDeg(truth_deg)));
  e.check.given = "x,y,z";
  const std::string warning = MountingWarning(e.check, CorrectedMounting(Mounting(), e));
  EXPECT_THAT(warning, HasSubstr("by 3.0"));
  EXPECT_THAT(warning, HasSubstr("z +3.0"));
  EXPECT_THAT(warning, HasSubstr("--mounting auto:x,y,z"));
  EXPECT_THAT(warning, HasSubstr("--mounting=0.99"));

  // A sensor on another face, turned by 180° about z and read as identity, is told the permutation.
  const Eigen::Matrix3d turned = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  const MountingEstimate on_its_back = EstimateMounting(MakeRecording({}, RotationFromDeg({0.1, 0.2, -0.3}) * turned));
  const std::string back_warning = MountingWarning(on_its_back.check, CorrectedMounting(Mounting(), on_its_back));
  EXPECT_THAT(back_warning, HasSubstr("by 179."));
  EXPECT_THAT(back_warning, HasSubstr("--mounting=-x,-y,z (the data agree with it within 1°)"));

  const MountingEstimate aligned = EstimateMounting(MakeRecording({}, RotationFromDeg({0.2, -0.3, 0.4})));
  EXPECT_EQ(MountingWarning(aligned.check, CorrectedMounting(Mounting(), aligned)), "");
}

TEST(MountingOption, AutoAloneOrWithAStartingMounting) {
  EXPECT_TRUE(MountingOption::Parse("auto").estimate);
  EXPECT_TRUE(MountingOption::Parse("auto").given.is_identity());
  EXPECT_EQ(MountingOption::Parse("auto").text(), "auto");
  const MountingOption start = MountingOption::Parse(" AUTO : x,-y,-z");
  EXPECT_TRUE(start.estimate);
  EXPECT_EQ(start.given.text(), "x,-y,-z");
  EXPECT_EQ(start.text(), "auto:x,-y,-z");
  EXPECT_FALSE(MountingOption::Parse("-x,-y,z").estimate);
  EXPECT_EQ(MountingOption::Parse("-x,-y,z").text(), "-x,-y,z");
  EXPECT_THROW(MountingOption::Parse("autox,y,z"), InvalidArgument);
  EXPECT_THROW(MountingOption::Parse("auto:auto"), InvalidArgument);
  EXPECT_THROW(MountingOption::Parse("auto:x,y,-z"), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
