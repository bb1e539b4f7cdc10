// The sensor's mounting on the block estimated from the recording itself (io/README.md, "Mounting estimate").
// A hand-glued IMU sits a few degrees off the block's axes; three facts of every release fix how much:
//
//  * rest before the release: the block leans on its release edge V1V2 at the tilt α about y (φy = −α), so
//    the accelerometer reads g·(sin α, 0, cos α) in block axes: no y component;
//  * phase 1 (release to the first impact): the block turns about the release edge, w_B = (0, ω, 0), ω > 0;
//  * rest after the rocking: the block stands flat, the accelerometer reads g·(0, 0, 1).
//
// The recording is in the axes B' of the given mounting. With R = R_B'B (block axes → given axes) the three
// clues are R·(sin α, 0, cos α) = a_rest, R·e_y = axis of phase 1, R·e_z = a_final (directions). They are
// solved by weighted least squares over R and α (Gauss–Newton on R = R0·Exp(θ)), each clue weighted by its
// measured scatter, with a weak prior on θ. Rest before the release and phase 1 fix the rotations about x and
// z; the rotation about y looks like a change of α there and is fixed only by the final rest (or stays at
// the given mounting, status "partial", with the reason in the message).
//
// A block released rolled by β on one corner of its release edge breaks two of the clues: at rest it leans sideways
// (a = (sin α cos β, −sin β, cos α cos β)), and in phase 1 it turns about the corner, off its y axis. To first order
// both are what a sensor turned by −β/sin α about z shows (0.3–0.4° per mrad of roll on a block of the paper's): the
// three clues cannot tell the two apart. The gyro can: a rolled block's rate strays from its mean axis as the roll
// runs out, a yawed sensor's does not. Where phase 1 shows such a roll (phase1_across_to_noise, max_roll_yaw_deg), the
// estimate is made with β free and without phase 1: the rotation about z is then not fixed by the data (kept at the
// given mounting, status "partial"), and the message says why.
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "rockfit/io/mounting.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

struct MountingEstimateOptions {
  // At rest when |ω − bias| stays below this. 0.03 rad/s ≈ 1.7 °/s: ten times the gyro noise of an x-IMU at
  // rest; a block of the paper (b1 = 5 cm, h = 20 cm, α = 0.8 θc) passes it about 20 ms after its release.
  double rest_rate_rad_s = 0.03;
  // Samples this close to the release or to the last motion are not counted as rest (hand, ringing).
  double rest_margin_s = 0.05;
  // Shortest usable rest before the release or after the rocking: 50 samples at 256 Hz.
  double min_rest_s = 0.2;
  // Largest turn of the block between the rest before the release and the start of its fall [deg] (a hand that
  // lifts or pushes it as it lets go; a stop shorter than min_rest_s at the top is no rest): 2° is three times
  // what a push of 0.2 rad/s lifts a block of the paper (0.63° at α = 0.19 rad) and well below its release tilts
  // (0.17–0.24 rad, 10–14°), so the block standing flat before it was tilted into place is not taken for the rest.
  // 0: the rest must end where the fall begins.
  double max_turn_before_fall_deg = 2.0;
  // Phase 1 is the samples before the first impact with |ω| ≥ this fraction of the landing rate (smaller rates
  // are dominated by noise in their direction).
  double phase1_min_fraction = 0.2;
  // The first impact is the first local maximum of |ω| of at least this fraction of the largest.
  double first_impact_fraction = 0.5;
  // σ of the prior on each angle about the starting mounting [deg]: weak against any data clue.
  double prior_deg = 10.0;
  // An angle whose standard error exceeds this [deg] is not determined by the data.
  double undetermined_std_deg = 1.0;
  // Per-clue floor on the direction uncertainty [deg]: accelerometer calibration and the gyro's axis
  // alignment are good to about this on the x-IMU.
  double direction_floor_deg = 0.02;
  // A release on one corner (above) is recognised by two signs together: the RMS of phase 1's rate across its mean
  // axis exceeds this many times the gyro's noise at rest (per axis; about 1 on a release about the edge, 19 on one
  // rolled by 1 mrad)…
  double phase1_across_to_noise = 4.0;
  // … and the roll the gyro sees in the fall (largest |∫ω_x dt|, what is proportional to ω_y taken out) would fake a
  // yaw β/sin α above this [deg]: half the 1° warning (a roll of 1 mrad at α = 0.18 rad shows about 0.5°, and moves the
  // estimate about z by 0.3°).
  double max_roll_yaw_deg = 0.5;
  // The rest after the rocking is a clue only when it lies within this of the rest before the release [deg]: a block
  // back on its base rests within its release tilt of it (below θ_c ≤ 45° for a block no wider than tall), one that
  // overturned far from it, on another face (77–78° on MuJoCo boxes pushed over onto their side).
  double max_rests_apart_deg = 60.0;
  // The fall before the first impact is a clue only when the block turns by at most this in it [deg]: a fall onto the
  // base turns by the release tilt and a lift (below θ_c ≤ 45°), a block pushed over its release edge falls onto a
  // side, turning by 90° − α or so (73–77° on MuJoCo boxes pushed past θ_c), and its fall's axis, reversed, would
  // read as a sensor turned by 180° about z.
  double max_fall_turn_deg = 60.0;
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

struct MountingEstimate {
  MountingCheck check;  // status, angles, standard errors, which angles are determined, α at rest, turn before the fall
  Eigen::Matrix3d R_BBg = Eigen::Matrix3d::Identity();  // block axes from the given mounting's axes
  std::size_t rest_before_first = 0;    // first sample of the rest before the release
  std::size_t rest_before_samples = 0;  // its length (0: no rest found)
  std::size_t phase1_samples = 0;
  std::size_t rest_after_samples = 0;
  Eigen::Vector3d gyro_bias_rad_s = Eigen::Vector3d::Zero();  // measured at rest before the release (given axes)
};

// The estimate from a recording read with the given mounting (its accel_B and w_B are in the given axes).
// Never throws for data it cannot use: the status says why ("no_accelerometer", "no_release", "no_rest").
MountingEstimate EstimateMounting(const Recording& recording, const MountingEstimateOptions& options = {});

// The mounting the estimate shows: R_BS = R_BBg·R_BS,given.
Mounting CorrectedMounting(const Mounting& given, const MountingEstimate& estimate);

// Total disagreement [deg] between the data and the given mounting over the determined angles (the norm of
// those rotation-vector components); NaN without an estimate.
double MountingDisagreementDeg(const MountingCheck& check);

// The data disagree with a given mounting by more than this: the warning says by how much and how to fix it.
// 1° of yaw mixes 1.7 % of φy into φx, a tenth of the smallest OPMF of the paper's blocks.
inline constexpr double kMountingWarningDeg = 1.0;

// The warning for a given (not estimated) mounting, or "" when the data agree within kMountingWarningDeg.
std::string MountingWarning(const MountingCheck& check, const Mounting& suggested);

}  // namespace rockfit::io
