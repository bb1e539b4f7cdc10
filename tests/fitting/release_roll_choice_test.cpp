// Whether the release roll β is fitted (release_roll_choice.hpp): a planar release keeps it off and its problem
// unchanged, a rolled one turns it on with a start near the roll, whatever leaks of ω_y into ω_x a sensor makes.
#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/release_roll_choice.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "rockfit/io/synth_recording.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

TrialProblem Prepare(const testing::SynthTrial& trial, ReleaseRollMode mode) {
  TrialProblemOptions options;
  options.release_roll.mode = mode;
  return PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults(), options);
}

// The start of a rolled release within this fraction of the roll: the running sum of ω_x up to the other corner's
// landing, sampled at 256 Hz (a roll of a few mrad lands in 10–30 ms, a few samples).
constexpr double kStartRelativeTolerance = 0.35;

TEST(ReleaseRollChoice, APlanarReleaseKeepsTheRollOffAndItsProblemUnchanged) {
  for (std::uint64_t seed : {1, 2, 3, 4, 5, 6}) {
    const testing::SynthTrial trial = testing::MakeRolledSynthTrial(0.2, 0.0, seed);
    const TrialProblem automatic = Prepare(trial, ReleaseRollMode::kAuto);
    const TrialProblem off = Prepare(trial, ReleaseRollMode::kOff);
    const ReleaseRollChoice& c = automatic.release_roll;
    ASSERT_TRUE(c.judged) << "seed " << seed;
    EXPECT_FALSE(c.fitted) << "seed " << seed << ": " << c.reason;
    EXPECT_LT(c.roll_seen_rad, ReleaseRollChoiceOptions{}.min_roll_to_noise * c.roll_noise_rad);
    EXPECT_TRUE(automatic.start[ParameterId::kReleaseRoll].fixed);
    // The same problem as with the roll off: start, free parameters and (28) at the start, to the bit.
    for (ParameterId id : kAllParameters) {
      EXPECT_EQ(automatic.start[id].value, off.start[id].value) << Name(id);
      EXPECT_EQ(automatic.start[id].fixed, off.start[id].fixed) << Name(id);
    }
    EXPECT_EQ(automatic.objective.free_ids(), off.objective.free_ids());
    EXPECT_EQ(automatic.objective.Evaluate(automatic.start).epsilon_rad_s,
              off.objective.Evaluate(off.start).epsilon_rad_s);
  }
}

TEST(ReleaseRollChoice, ARolledReleaseTurnsTheRollOnWithAStartNearIt) {
  for (double roll : {0.004, -0.008, 0.002}) {
    const testing::SynthTrial trial = testing::MakeRolledSynthTrial(0.2, roll, 7);
    const TrialProblem p = Prepare(trial, ReleaseRollMode::kAuto);
    const ReleaseRollChoice& c = p.release_roll;
    ASSERT_TRUE(c.judged) << "roll " << roll;
    EXPECT_TRUE(c.fitted) << "roll " << roll << ": " << c.reason;
    EXPECT_FALSE(p.start[ParameterId::kReleaseRoll].fixed);
    EXPECT_NEAR(p.start.value(ParameterId::kReleaseRoll), roll, kStartRelativeTolerance * std::abs(roll))
        << "roll " << roll << ": " << c.reason;
    EXPECT_EQ(p.start.value(ParameterId::kReleaseRoll), c.start_rad);
    const auto& free = p.objective.free_ids();
    EXPECT_NE(std::find(free.begin(), free.end(), ParameterId::kReleaseRoll), free.end());
  }
}

TEST(ReleaseRollChoice, ALeakOfTheRockingRateIntoTheLateralAxisDoesNotTurnItOn) {
  // A gyro whose x axis leans 1° towards y sees 1.7 % of ω_y on x: over the fall that adds up to 3.5 mrad of
  // apparent roll, far above the noise; the choice takes the leak out before it sums.
  const double lean_rad = 1.0 * M_PI / 180.0;
  for (std::uint64_t seed : {1, 2, 3}) {
    testing::SynthTrial trial = testing::MakeRolledSynthTrial(0.2, 0.0, seed);
    for (Eigen::Vector3d& w : trial.signal.w_B) w.x() += std::sin(lean_rad) * w.y();
    const ReleaseRollChoice c = Prepare(trial, ReleaseRollMode::kAuto).release_roll;
    ASSERT_TRUE(c.judged);
    EXPECT_FALSE(c.fitted) << "seed " << seed << ": " << c.reason;
    EXPECT_NEAR(c.leak, std::sin(lean_rad), 0.1 * std::sin(lean_rad)) << "seed " << seed;
  }
}

TEST(ReleaseRollChoice, OffNeverFitsItAndOnAlwaysDoesFromTheData) {
  const testing::SynthTrial rolled = testing::MakeRolledSynthTrial(0.2, 0.004, 7);
  const TrialProblem off = Prepare(rolled, ReleaseRollMode::kOff);
  EXPECT_FALSE(off.release_roll.fitted);
  EXPECT_TRUE(off.start[ParameterId::kReleaseRoll].fixed);
  EXPECT_EQ(off.start.value(ParameterId::kReleaseRoll), 0.0);

  const testing::SynthTrial planar = testing::MakeRolledSynthTrial(0.2, 0.0, 1);
  const TrialProblem on = Prepare(planar, ReleaseRollMode::kOn);
  EXPECT_TRUE(on.release_roll.fitted);
  EXPECT_FALSE(on.start[ParameterId::kReleaseRoll].fixed);
  // A planar fall shows no roll: the start is the noise's, well inside the bounds.
  EXPECT_LT(std::abs(on.start.value(ParameterId::kReleaseRoll)), 5.0 * on.release_roll.roll_noise_rad);

  // A β freed by the caller is fitted whatever the mode; one fixed at another value than 0 stays as given.
  ParameterSet freed = ParameterSet::Defaults();
  freed[ParameterId::kReleaseRoll].fixed = false;
  TrialProblemOptions options;
  options.release_roll.mode = ReleaseRollMode::kOff;
  EXPECT_TRUE(PrepareTrialProblem(rolled.signal, rolled.block, freed, options).release_roll.fitted);
  ParameterSet held = ParameterSet::Defaults();
  held[ParameterId::kReleaseRoll].value = 0.003;
  const TrialProblem given = PrepareTrialProblem(rolled.signal, rolled.block, held);
  EXPECT_FALSE(given.release_roll.fitted);
  EXPECT_EQ(given.start.value(ParameterId::kReleaseRoll), 0.003);
}

TEST(ReleaseRollChoice, WithoutARestBeforeTheReleaseAutoLeavesItOff) {
  const testing::SynthTrial trial = testing::MakeRolledSynthTrial(0.2, 0.004, 7);
  const double t_release_s = 1.0, t_first_impact_s = 1.3;
  // The recording starts 0.02 s before the release: no rest segment to measure the noise on.
  MeasuredSignal late;
  for (std::size_t k = 0; k < trial.signal.size(); ++k) {
    if (trial.signal.t_s[k] < t_release_s - 0.02) continue;
    late.t_s.push_back(trial.signal.t_s[k]);
    late.w_B.push_back(trial.signal.w_B[k]);
  }
  const ReleaseRollChoice c = ChooseReleaseRoll(late, t_release_s, t_first_impact_s);
  EXPECT_FALSE(c.judged);
  EXPECT_FALSE(c.fitted);
  EXPECT_FALSE(c.reason.empty());
}

TEST(ReleaseRollChoice, ModesReadAndWriteTheirNamesAndRejectOthers) {
  for (ReleaseRollMode m : {ReleaseRollMode::kOff, ReleaseRollMode::kAuto, ReleaseRollMode::kOn}) {
    EXPECT_EQ(ParseReleaseRollMode(ToString(m)), m);
  }
  EXPECT_THROW(ParseReleaseRollMode("yes"), InvalidArgument);
  ReleaseRollChoiceOptions bad;
  bad.min_roll_to_noise = -1.0;
  EXPECT_THROW(bad.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
