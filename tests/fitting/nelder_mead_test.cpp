// The NLopt Nelder–Mead back end on problems whose minimiser is known.
#include <gtest/gtest.h>

#include "analytic_trial.hpp"
#include "rockfit/fitting/local_optimizer.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeAnalyticTrial;

// Noise-free data: the minimiser is the truth, with ε = 0 there. Tolerances are what the default xtol/ftol
// allow on this problem.
constexpr double kAlphaTolerance = 1e-4;     // rad
constexpr double kLambdaLonTolerance = 1e-3;

ParameterSet TwoFree(const testing::AnalyticTrial& trial) {
  ParameterSet p = trial.truth;
  for (ParameterId id : kAllParameters) p[id].fixed = true;
  p[ParameterId::kAlpha].fixed = false;
  p[ParameterId::kLambdaLon].fixed = false;
  return p;
}

TEST(TerminationType, NamesAreTheDocumentedOnes) {
  EXPECT_STREQ(ToString(TerminationType::kConvergence), "convergence");
  EXPECT_STREQ(ToString(TerminationType::kNoConvergence), "no_convergence");
  EXPECT_STREQ(ToString(TerminationType::kFailure), "failure");
  EXPECT_STREQ(ToString(TerminationType::kNotASearch), "not_a_search");
}

TEST(NelderMead, FindsTheTrueParametersOfNoiseFreeData) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective = trial.MakeObjective(TwoFree(trial));
  Eigen::VectorXd x0(2);
  x0 << 0.195, 0.7;
  const LocalResult r = MakeNelderMead(NelderMeadOptions{})->Minimize(objective, x0);
  ASSERT_TRUE(r.feasible) << r.termination;
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_EQ(r.termination_type, TerminationType::kConvergence) << r.termination;
  EXPECT_NEAR(r.x[0], 0.2, kAlphaTolerance);
  EXPECT_NEAR(r.x[1], 0.6, kLambdaLonTolerance);
  EXPECT_LT(r.epsilon_rad_s, objective.EvaluateFree(x0).epsilon_rad_s);
  EXPECT_EQ(r.epsilon_rad_s, objective.EvaluateFree(r.x).epsilon_rad_s);  // reported ε is (28) at x
  EXPECT_GT(r.evaluations, 0);
}

TEST(NelderMead, StaysInsideTheBoundsWhenTheMinimiserIsOutside) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  ParameterSet p = TwoFree(trial);
  p[ParameterId::kLambdaLon] = {0.9, 0.8, 1.0, false};  // the truth 0.6 lies below the lower bound
  const Objective objective = trial.MakeObjective(p);
  const LocalResult r = MakeNelderMead(NelderMeadOptions{})->Minimize(objective, objective.FreeValues(p));
  EXPECT_GE(r.x[1], 0.8);
  EXPECT_NEAR(r.x[1], 0.8, 1e-3);
}

TEST(NelderMead, ABudgetStopIsReportedAsNotConverged) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective = trial.MakeObjective(TwoFree(trial));
  NelderMeadOptions options;
  options.max_evaluations = 5;
  Eigen::VectorXd x0(2);
  x0 << 0.15, 1.0;
  const LocalResult r = MakeNelderMead(options)->Minimize(objective, x0);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.termination_type, TerminationType::kNoConvergence) << r.termination;
  EXPECT_EQ(r.termination, "nlopt: max evaluations reached");
  EXPECT_LE(r.evaluations, 5);
}

TEST(NelderMead, AStartOnTheInfeasiblePlateauIsReportedNotHidden) {
  // Every point near the start overturns: the penalty is flat there, the simplex cannot move. The result must
  // say so (infeasible, not converged, finite ε) — the global stage is what finds feasible points.
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective = trial.MakeObjective(TwoFree(trial));
  Eigen::VectorXd x0(2);
  x0 << 0.27, 0.6;  // beyond θ_c = 0.245 rad: the block overturns
  ASSERT_FALSE(objective.EvaluateFree(x0).feasible);
  const LocalResult r = MakeNelderMead(NelderMeadOptions{})->Minimize(objective, x0);
  EXPECT_FALSE(r.feasible);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.termination_type, TerminationType::kFailure) << r.termination;
  EXPECT_EQ(r.epsilon_rad_s, objective.options().failure_penalty_rad_s);
  EXPECT_GT(objective.counters().failures_by_reason().at("overturned"), 0);
}

}  // namespace
}  // namespace rockfit::fitting
