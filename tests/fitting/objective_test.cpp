// The fitting problem: (28) through a model, infeasible points as finite penalties counted by reason.
#include "rockfit/fitting/objective.hpp"

#include <cmath>
#include <cstdint>
#include <memory>

#include <gtest/gtest.h>

#include "analytic_rocking_model.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

// A model that returns ω = (c, 0, 0) for c = λ_lon, and can be told to fail or to return NaN.
class ConstantModel final : public TrajectoryModel {
 public:
  void Evaluate(const core::ModelParameters& p, const std::vector<double>& times, ModelOutput* out) const override {
    out->Clear();
    if (p.lambda_lat > 0.5) {
      out->failure = ModelFailure::kOverturned;
      return;
    }
    last_times = times;
    const double value = p.lambda_lat < -0.5 ? std::nan("") : p.lambda_lon;
    out->w_B.assign(times.size(), Eigen::Vector3d(value, 0.0, 0.0));
  }
  std::string Describe() const override { return "constant"; }
  mutable std::vector<double> last_times;
};

MeasuredSignal ZeroSignal() {
  MeasuredSignal s;
  for (int k = 0; k <= 256; ++k) {
    s.t_s.push_back(k / 256.0);
    s.w_B.push_back(Eigen::Vector3d::Zero());
  }
  return s;
}

ParameterSet StartAt(double t0, double lambda_lon, double lambda_lat) {
  ParameterSet set = ParameterSet::Defaults();
  set[ParameterId::kT0] = {t0, 0.0, 0.9, false};
  set[ParameterId::kLambdaLon].value = lambda_lon;
  set[ParameterId::kLambdaLat].value = lambda_lat;
  return set;
}

TEST(Objective, EvaluatesTheErrorOfTheModelAtTheMeasuredTimesAfterRelease) {
  auto model = std::make_shared<ConstantModel>();
  const Objective objective(ZeroSignal(), 1.0, model, StartAt(0.1, 0.7, 0.0));
  const Evaluation e = objective.Evaluate(StartAt(0.1, 0.7, 0.0));
  ASSERT_TRUE(e.feasible);
  EXPECT_NEAR(e.epsilon_rad_s, 0.7, 1e-14);
  ASSERT_FALSE(model->last_times.empty());
  EXPECT_EQ(model->last_times.front(), 0.0);
  EXPECT_NEAR(model->last_times[1], 26.0 / 256.0 - 0.1, 1e-15);  // first sample after t0 = 0.1 s
  EXPECT_EQ(objective.counters().runs(), 1);
}

TEST(Objective, AFailedModelRunIsAFinitePenaltyCountedByReason) {
  auto model = std::make_shared<ConstantModel>();
  const Objective objective(ZeroSignal(), 1.0, model, StartAt(0.1, 0.7, 0.0));
  const Evaluation failed = objective.Evaluate(StartAt(0.1, 0.7, 1.0));
  EXPECT_FALSE(failed.feasible);
  EXPECT_EQ(failed.failure, ModelFailure::kOverturned);
  EXPECT_EQ(failed.epsilon_rad_s, objective.options().failure_penalty_rad_s);
  const Evaluation nan = objective.Evaluate(StartAt(0.1, 0.7, -1.0));
  EXPECT_FALSE(nan.feasible);
  EXPECT_TRUE(std::isfinite(nan.epsilon_rad_s));
  const Evaluation outside = objective.Evaluate(StartAt(1.5, 0.7, 0.0));
  EXPECT_FALSE(outside.feasible);
  EXPECT_EQ(outside.failure, ModelFailure::kT0OutsideWindow);
  const auto by_reason = objective.counters().failures_by_reason();
  EXPECT_EQ(by_reason.at("overturned"), 1);
  EXPECT_EQ(by_reason.at("t0 outside the recording window"), 1);
  EXPECT_EQ(objective.counters().failures(), 3);
}

TEST(Objective, FreeVectorRoundTripsInTheOrderOfTheFreeParameters) {
  auto model = std::make_shared<ConstantModel>();
  ParameterSet set = StartAt(0.1, 0.7, 0.0);
  set[ParameterId::kLambda].fixed = true;
  const Objective objective(ZeroSignal(), 1.0, model, set);
  ASSERT_EQ(objective.num_free(), 4u);
  Eigen::VectorXd x(4);
  x << 0.2, 0.11, -0.3, 0.9;  // t0, alpha, lambda_lat, lambda_lon
  const ParameterSet back = objective.WithFree(x);
  EXPECT_EQ(back.value(ParameterId::kT0), 0.2);
  EXPECT_EQ(back.value(ParameterId::kAlpha), 0.11);
  EXPECT_EQ(back.value(ParameterId::kLambda), set.value(ParameterId::kLambda));
  EXPECT_EQ(back.value(ParameterId::kLambdaLat), -0.3);
  EXPECT_EQ(back.value(ParameterId::kLambdaLon), 0.9);
  EXPECT_EQ(objective.FreeValues(back), x);
}

TEST(Objective, WithModelEvaluatesTheOtherModelAndSharesTheCounters) {
  auto first = std::make_shared<ConstantModel>();
  auto second = std::make_shared<ConstantModel>();
  const Objective objective(ZeroSignal(), 1.0, first, StartAt(0.1, 0.7, 0.0));
  const Objective other = objective.WithModel(second);
  EXPECT_NEAR(other.Evaluate(StartAt(0.1, 0.4, 0.0)).epsilon_rad_s, 0.4, 1e-14);
  EXPECT_TRUE(first->last_times.empty());
  EXPECT_FALSE(second->last_times.empty());
  EXPECT_EQ(objective.counters().runs(), 1);  // the run of `other` counts for the whole fit
  EXPECT_THROW(objective.WithModel(nullptr), InvalidArgument);
  // A model without a tolerance has no looser copy.
  EXPECT_EQ(first->WithLooserTolerance(1e-9), nullptr);
}

TEST(Objective, RejectsAWindowEndOutsideTheRecording) {
  auto model = std::make_shared<ConstantModel>();
  EXPECT_THROW(Objective(ZeroSignal(), 1.5, model, StartAt(0.1, 0.7, 0.0)), InvalidArgument);
}

TEST(Objective, EvaluateOnNodesIsTheEvaluationOfTheShorterWindowBitForBit) {
  // The prefix screen evaluates its shorter windows on nodes it built itself: every outcome (a value, a model
  // failure, a non-finite output, a non-finite parameter) must be what the objective of that window gives, and be
  // counted the same. A varying signal with excluded samples, so that the weights and the divisor matter.
  MeasuredSignal signal = ZeroSignal();
  signal.excluded.assign(signal.size(), false);
  for (std::size_t k = 0; k < signal.size(); ++k) {
    signal.w_B[k] = Eigen::Vector3d(std::sin(7.0 * signal.t_s[k]), 0.3 * signal.t_s[k], -0.2);
    signal.excluded[k] = k % 17 == 5;
  }
  auto model = std::make_shared<ConstantModel>();
  const Objective objective(signal, 1.0, model, StartAt(0.1, 0.7, 0.0));
  const double t_end_s = signal.t_s[150];
  const Objective shorter = objective.WithWindowEnd(t_end_s);
  for (const ParameterSet& p : {StartAt(0.1, 0.7, 0.0), StartAt(0.2345, -1.3, 0.2), StartAt(0.05, 0.4, 0.9),
                                StartAt(0.3, 0.4, -0.9), StartAt(0.3, std::nan(""), 0.0)}) {
    ErrorNodes nodes;
    ASSERT_TRUE(BuildErrorNodes(signal, p.value(ParameterId::kT0), t_end_s, &nodes));
    // The counters are shared by the two objectives: the counts each evaluation adds.
    const EvaluationCounters& counters = objective.counters();
    const std::int64_t runs_before = counters.runs();
    const std::int64_t failures_before = counters.failures();
    const Evaluation on_nodes = objective.EvaluateOnNodes(p, nodes);
    const std::int64_t runs_on_nodes = counters.runs() - runs_before;
    const std::int64_t failures_on_nodes = counters.failures() - failures_before;
    const Evaluation expected = shorter.Evaluate(p);
    EXPECT_EQ(on_nodes.feasible, expected.feasible);
    EXPECT_EQ(on_nodes.epsilon_rad_s, expected.epsilon_rad_s);
    EXPECT_EQ(on_nodes.failure, expected.failure);
    EXPECT_EQ(on_nodes.gyro_scale, expected.gyro_scale);
    EXPECT_EQ(counters.runs() - runs_before - runs_on_nodes, runs_on_nodes);
    EXPECT_EQ(counters.failures() - failures_before - failures_on_nodes, failures_on_nodes);
  }
}

TEST(AnalyticRockingModel, FirstImpactMatchesTheClosedFormOfLinearisedRocking) {
  // Test support sanity: phase 1 ends when cosh(p t1) = θ_c / (θ_c − α).
  const core::Block block = core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0);
  const testing::AnalyticRockingModel model(block);
  core::ModelParameters p;
  p.alpha_rad = 0.1;
  p.lambda_lat = 1.0;
  ModelOutput out;
  model.Evaluate(p, {0.0, 0.01, 1.0}, &out);
  ASSERT_TRUE(out.ok());
  const double theta_c = std::atan2(0.05, 0.2);
  const double R = std::hypot(0.05, 0.2);
  const double J = block.inertia_C_B()(1, 1) + block.mass() * R * R;
  const double pp = std::sqrt(block.mass() * core::kStandardGravity * R / J);
  EXPECT_NEAR(out.events.front().t_s, std::acosh(theta_c / (theta_c - 0.1)) / pp, 1e-12);
  EXPECT_EQ(out.w_B[0], Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace rockfit::fitting
