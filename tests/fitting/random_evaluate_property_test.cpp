// Random physics through `fit --evaluate`: the error (28) of one synthetic trial (noise, ringing, bias) at random
// parameter sets — t0 anywhere (before, inside and after the recording), tilts at and beyond θ_c, λ, λ_lat and
// λ_lon far outside (25)/(27), non-finite values. Each evaluation ends feasible with a finite ε, or infeasible
// with a reason and the documented penalty; never NaN or inf, never an exception.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

#include "random_physics.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "synth_trial.hpp"

namespace rockfit::fitting {
namespace {

using testing::RandomPhysics;
using testing::RandomPhysicsRuns;

TEST(RandomPhysicsProperty, FitEvaluateGivesAFiniteErrorOrAReasonForRandomParameters) {
  const testing::SynthTrial trial = testing::MakeSynthTrial(0.2, 0.8, -2.0, 0.6, 11);
  const TrialProblem problem = PrepareTrialProblem(trial.signal, trial.block, ParameterSet::Defaults());
  const double critical = std::atan(trial.block.b1() / trial.block.h());
  const double t_first = trial.signal.t_s.front();
  const double t_last = trial.signal.t_s.back();
  RandomPhysics r(20261128);
  const long runs = RandomPhysicsRuns(2000, 100) / 4;  // an evaluation is one simulation of the window
  std::map<std::string, long> counts;
  for (long run = 0; run < runs; ++run) {
    ParameterSet values = problem.start;
    values[ParameterId::kT0].value = r.Uniform(t_first - 1.0, t_last + 1.0);
    values[ParameterId::kAlpha].value = r.Chance(0.05) ? -r.LogUniform(1e-9, 1.0) : r.Tilt(critical);
    values[ParameterId::kLambda].value = r.ImpactParameter() * (r.Chance(0.5) ? 1.0 : 3.0);
    values[ParameterId::kLambdaLat].value = r.ImpactParameter() * (r.Chance(0.5) ? 1.0 : 3.0);
    values[ParameterId::kLambdaLon].value = r.ImpactParameter();
    if (r.Chance(0.02)) values[ParameterId::kLambda].value = std::numeric_limits<double>::quiet_NaN();
    if (r.Chance(0.02)) values[ParameterId::kAlpha].value = std::numeric_limits<double>::infinity();
    const Evaluation e = problem.objective.Evaluate(values);
    const std::string what = "run " + std::to_string(run) + ": t0 " + std::to_string(values.value(ParameterId::kT0)) +
                             " α " + std::to_string(values.value(ParameterId::kAlpha)) + " λ " +
                             std::to_string(values.value(ParameterId::kLambda)) + " λ_lat " +
                             std::to_string(values.value(ParameterId::kLambdaLat)) + " λ_lon " +
                             std::to_string(values.value(ParameterId::kLambdaLon));
    ASSERT_TRUE(std::isfinite(e.epsilon_rad_s)) << what;
    EXPECT_GE(e.epsilon_rad_s, 0.0) << what;
    if (e.feasible) {
      EXPECT_EQ(e.failure, ModelFailure::kNone) << what;
      ++counts["feasible"];
    } else {
      EXPECT_NE(e.failure, ModelFailure::kNone) << what;
      ++counts["infeasible: " + e.failure_category()];
    }
  }
  EXPECT_GT(counts["feasible"], runs / 10);
  for (const auto& [outcome, n] : counts) std::printf("fit --evaluate %-60s %ld\n", outcome.c_str(), n);
}

}  // namespace
}  // namespace rockfit::fitting
