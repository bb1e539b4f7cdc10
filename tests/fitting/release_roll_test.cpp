// The release roll β as a fit parameter (parameters.hpp, core/rolled_release.hpp): held at 0 and not reported
// unless freed, and recovered with the other parameters from a noisy synthetic recording of a rolled release.
#include <cmath>

#include <gtest/gtest.h>

#include "build_type.hpp"
#include "fit_acceptance.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "rockfit/io/synth_recording.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

constexpr std::size_t Index(ParameterId id) { return static_cast<std::size_t>(id); }

bool Holds(const Interval& i, double value) { return testing::IntervalHolds(i, value); }

TEST(ReleaseRoll, IsFixedAtZeroAndNotReportedUnlessFreed) {
  ParameterSet set = ParameterSet::Defaults();
  EXPECT_TRUE(set[ParameterId::kReleaseRoll].fixed);
  EXPECT_EQ(set.value(ParameterId::kReleaseRoll), 0.0);
  EXPECT_EQ(set.ToModel().release_roll_rad, 0.0);
  EXPECT_EQ(set.ReportedIds().size(), kNumParameters - 1);
  EXPECT_EQ(ParseParameterName("release_roll"), ParameterId::kReleaseRoll);
  set[ParameterId::kReleaseRoll].fixed = false;
  set[ParameterId::kReleaseRoll].value = 0.004;
  EXPECT_EQ(set.ReportedIds().size(), kNumParameters);
  EXPECT_EQ(set.ToModel().release_roll_rad, 0.004);
  EXPECT_NO_THROW(set.Validate());
}

TEST(ReleaseRoll, ARollIsRecoveredFromANoisySynthRecordingWithTheTruthInItsInterval) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  for (double roll : {0.004, -0.008}) {
    const testing::SynthTrial trial = testing::MakeRolledSynthTrial(0.2, roll, 7);
    ParameterSet free = ParameterSet::Defaults();
    free[ParameterId::kReleaseRoll].fixed = false;
    const TrialProblem p = PrepareTrialProblem(trial.signal, trial.block, free);
    FitOptions options;
    options.num_threads = 1;
    options.intervals.method = IntervalMethod::kThorough;
    const FitSummary s = Fit(p.objective, p.start, options);
    ASSERT_TRUE(s.feasible);
    const ParameterSet& t = trial.truth;
    EXPECT_NEAR(s.parameters.value(ParameterId::kT0), t.value(ParameterId::kT0), testing::kT0Tolerance_s) << s.FullReport();
    EXPECT_NEAR(s.parameters.value(ParameterId::kAlpha), t.value(ParameterId::kAlpha), testing::kAlphaTolerance_rad);
    // A tenth of the roll: the roll is fixed by the lateral rocking of the whole fall.
    EXPECT_NEAR(s.parameters.value(ParameterId::kReleaseRoll), roll, 0.1 * std::abs(roll)) << s.FullReport();
    EXPECT_TRUE(Holds(s.uncertainty.interval_95[Index(ParameterId::kReleaseRoll)], roll)) << s.FullReport();
    EXPECT_TRUE(Holds(s.uncertainty.interval_95[Index(ParameterId::kT0)], t.value(ParameterId::kT0)));
    EXPECT_TRUE(Holds(s.uncertainty.interval_95[Index(ParameterId::kAlpha)], t.value(ParameterId::kAlpha)));
    EXPECT_LE(s.epsilon_rad_s, testing::kEpsilonRatio * p.objective.Evaluate(t).epsilon_rad_s) << s.FullReport();
  }
}

}  // namespace
}  // namespace rockfit::fitting
