// The simulator as a trajectory model: samples exactly where asked, failures as categories, never throws.
#include "rockfit/fitting/simulator_model.hpp"

#include <gtest/gtest.h>

namespace rockfit::fitting {
namespace {

const core::Block kBlock = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);

core::ModelParameters Params(double alpha, double lambda_lat) {
  core::ModelParameters p;
  p.alpha_rad = alpha;
  p.lambda = 0.8;
  p.lambda_lat = lambda_lat;
  p.lambda_lon = 0.6;
  return p;
}

TEST(SimulatorModel, SamplesAreTheSimulatorsOwnAtTheRequestedTimes) {
  const std::vector<double> times = {0.0, 0.013, 0.2, 0.39871, 0.5, 0.73};
  ModelOutput out;
  SimulatorModel(kBlock).Evaluate(Params(0.2, -2.0), times, &out);
  ASSERT_TRUE(out.ok()) << out.failure_detail;
  core::SimulationOptions direct = SimulatorModelOptions::DefaultFittingSimulation();
  direct.sample_times_s = times;
  direct.stop = core::StopCondition::kTMax;
  direct.t_max_s = times.back();
  const core::Trajectory reference = core::Simulate(kBlock, Params(0.2, -2.0), direct);
  ASSERT_EQ(out.w_B.size(), times.size());
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_EQ(out.w_B[k], reference.w_B[k]) << "sample " << k;
  EXPECT_EQ(out.w_B.front(), Eigen::Vector3d::Zero());  // released from rest
  ASSERT_FALSE(out.events.empty());
  EXPECT_EQ(out.events.front().kind, core::ImpactKind::kFacet);
  EXPECT_EQ(out.events.front().t_s, reference.impacts.front().t_s);
}

TEST(SimulatorModel, ALooserToleranceLoosensButNeverTightensAndStaysCloseToTheDefault) {
  const SimulatorModel model(kBlock);
  const auto loose = std::dynamic_pointer_cast<const SimulatorModel>(model.WithLooserTolerance(1e-9));
  ASSERT_TRUE(loose);
  EXPECT_EQ(loose->options().simulation.rel_tol, 1e-9);
  EXPECT_DOUBLE_EQ(loose->options().simulation.abs_tol, 1e-11);
  // Asking for a tighter tolerance than the model's own keeps the model's own.
  const auto same = std::dynamic_pointer_cast<const SimulatorModel>(model.WithLooserTolerance(1e-15));
  ASSERT_TRUE(same);
  EXPECT_EQ(same->options().simulation.rel_tol, model.options().simulation.rel_tol);
  EXPECT_EQ(same->options().simulation.abs_tol, model.options().simulation.abs_tol);
  // The samples move by far less than the gyro noise (~1e-3 rad/s) through ~15 impacts.
  std::vector<double> times;
  for (int k = 0; k <= 256; ++k) times.push_back(k / 256.0);
  ModelOutput fine, coarse;
  model.Evaluate(Params(0.2, -2.0), times, &fine);
  loose->Evaluate(Params(0.2, -2.0), times, &coarse);
  ASSERT_TRUE(fine.ok() && coarse.ok());
  ASSERT_EQ(fine.events.size(), coarse.events.size());
  double largest_rad_s = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) largest_rad_s = std::max(largest_rad_s, (fine.w_B[k] - coarse.w_B[k]).norm());
  EXPECT_LT(largest_rad_s, 1e-6);
  EXPECT_GT(fine.events.size(), 5u);
}

TEST(SimulatorModel, ATiltBeyondTheCriticalAngleIsAFailureNotAnException) {
  ModelOutput out;
  SimulatorModel(kBlock).Evaluate(Params(0.26, 0.0), {0.0, 0.1, 0.5}, &out);  // θ_c = atan(0.05/0.2) = 0.245
  EXPECT_FALSE(out.ok());
  EXPECT_EQ(out.failure, ModelFailure::kOverturned);
  EXPECT_TRUE(out.w_B.empty());
}

TEST(SimulatorModel, InvalidParametersAreAFailureNotAnException) {
  ModelOutput out;
  SimulatorModel(kBlock).Evaluate(Params(-0.1, 0.0), {0.0, 0.1}, &out);
  EXPECT_FALSE(out.ok());
  EXPECT_EQ(out.failure, ModelFailure::kInvalidParameters);
  EXPECT_FALSE(out.failure_detail.empty());
}

TEST(ModelFailure, FromSimulationNamesTheImpactStatusOrTheIntegrator) {
  using core::FailureReason;
  using core::ImpactStatus;
  const auto category = [](FailureReason reason, ImpactStatus status = ImpactStatus::kOk) {
    return FailureCategory(FromSimulation(reason, status), status);
  };
  EXPECT_EQ(category(FailureReason::kEdgeImpact, ImpactStatus::kSingular), "edge impact singular");
  EXPECT_EQ(category(FailureReason::kEdgeImpact, ImpactStatus::kAmbiguous), "edge impact ambiguous");
  EXPECT_EQ(category(FailureReason::kFacetImpact, ImpactStatus::kInfeasible), "facet impact infeasible");
  EXPECT_EQ(FromSimulation(FailureReason::kFacetImpact, ImpactStatus::kOk), ModelFailure::kFailed);  // non-finite ω⁺
  EXPECT_EQ(category(FailureReason::kIntegratorStep), "integrator");
  EXPECT_EQ(category(FailureReason::kImpactCascade), "impact cascade");
  EXPECT_EQ(category(FailureReason::kMaxImpacts), "too many impacts");
  EXPECT_EQ(FromSimulation(FailureReason::kEnergyBlowUp, ImpactStatus::kOk), ModelFailure::kFailed);
}

TEST(SimulatorModel, ARunWithTooManyImpactsFailsAsTooManyImpacts) {
  SimulatorModelOptions options;
  options.simulation.max_impacts = 2;
  ModelOutput out;
  SimulatorModel(kBlock, options).Evaluate(Params(0.2, -2.0), {0.0, 0.5, 1.0, 2.0}, &out);
  EXPECT_EQ(out.failure, ModelFailure::kTooManyImpacts) << out.failure_detail;
  EXPECT_NE(out.failure_detail.find("max_impacts"), std::string::npos) << out.failure_detail;
}

}  // namespace
}  // namespace rockfit::fitting
